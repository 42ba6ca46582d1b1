//! Why one pixel differs, told from raylab's ray tree there: the terms of its shading (the
//! ambient, each light's diffuse and specular, each shadow ray clear, tinted or blocked and by
//! what, the reflected and transmitted rays' shares), each as what the pixel would lose or gain
//! without it, and the term or terms that account for the difference measured.

use serde::Serialize;

use crate::color::{Color, srgb_to_linear};
use crate::inspect::{RayNode, RayTree};
use crate::whitted::RayKind;

/// A difference smaller than this (the mean over the channels of the linear difference) is
/// left unexplained: it is rounding.
const NOTHING: f32 = 2.0 / 255.0;

/// One pixel's difference and what in raylab's ray tree accounts for it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PixelExplanation {
    pub pixel: (u32, u32),
    pub yours: [u8; 3],
    pub raylab: [u8; 3],
    /// How much brighter your pixel is (negative: darker), the mean over the channels of the
    /// linear difference.
    pub brighter_by: f32,
    /// What raylab's eye ray hit, or that it saw the background.
    pub first_hit: String,
    /// The terms of raylab's pixel, each with its share of the pixel (the mean over the
    /// channels), the eye ray's first.
    pub terms: Vec<Term>,
    /// The sentence that says which term accounts for the difference, if one does.
    pub accounted_for: Option<String>,
}

/// A term of raylab's pixel.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Term {
    /// E.g. "light 0 diffuse", "reflected ray".
    pub what: String,
    /// Its share of the pixel, the mean over the channels.
    pub share: f32,
    /// What else there is to say: for a light's diffuse term, its shadow ray, and what the term
    /// would be unshadowed.
    pub note: Option<String>,
}

/// A way your pixel could have been made: raylab's pixel changed by `change` (linear).
struct Candidate {
    words: String,
    change: Color,
}

/// Explains why `yours` differs from `raylab` (the pixel's levels in the two images) at the
/// pixel of `tree`, raylab's ray tree there.
pub fn explain_pixel(tree: &RayTree, yours: [u8; 3], raylab: [u8; 3]) -> PixelExplanation {
    let linear =
        |levels: [u8; 3]| Color::from_array(levels.map(|l| srgb_to_linear(f32::from(l) / 255.0)));
    let measured = linear(yours) - linear(raylab);
    let brighter_by = mean(measured);
    let eye = &tree.nodes[0];
    let first_hit = match &eye.hit {
        Some(hit) => format!(
            "{} (material {} \"{}\") at t = {:.4}",
            hit.label, hit.material, hit.material_name, hit.t
        ),
        None => "nothing: the background".to_string(),
    };
    let accounted_for = if brighter_by.abs() < NOTHING && measured.abs().max_element() < NOTHING {
        None
    } else if eye.hit.is_none() {
        Some(format!(
            "your pixel is {}; raylab's eye ray sees the background here, so your camera \
             (eye, look-at, view angle, pixel positions) or your objects may differ",
            by(brighter_by)
        ))
    } else {
        best_candidate(tree, measured)
            .map(|c| format!("your pixel is {}; {}", by(brighter_by), c.words))
    };
    PixelExplanation {
        pixel: tree.pixel,
        yours,
        raylab,
        brighter_by,
        first_hit,
        terms: eye_terms(tree),
        accounted_for,
    }
}

fn by(brighter_by: f32) -> String {
    if brighter_by >= 0.0 {
        format!("brighter by {brighter_by:.2}")
    } else {
        format!("darker by {:.2}", -brighter_by)
    }
}

fn mean(c: Color) -> f32 {
    (c.x + c.y + c.z) / 3.0
}

/// The candidate whose change best matches `measured` on the display (both clamped to [0, 1]),
/// if it accounts for at least half of the difference.
fn best_candidate(tree: &RayTree, measured: Color) -> Option<Candidate> {
    let shown = |c: Color| c.clamp(Color::ZERO, Color::ONE);
    let residual = |c: &Candidate| {
        let expected = shown(tree.color + c.change) - shown(tree.color);
        (measured - expected).abs().element_sum()
    };
    let best = candidates(tree)
        .into_iter()
        .map(|c| (residual(&c), c))
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    (best.0 <= 0.5 * measured.abs().element_sum()).then_some(best.1)
}

/// Every term of the tree as a candidate, then each kind of term all together.
fn candidates(tree: &RayTree) -> Vec<Candidate> {
    let mut found = Vec::new();
    let (mut shadows, mut speculars) = (Color::ZERO, Color::ZERO);
    for node in &tree.nodes {
        let Some(hit) = &node.hit else { continue };
        let at = match node.kind {
            RayKind::Eye => String::new(),
            kind => format!("at the {} ray's hit on {}, ", kind.name(), hit.label),
        };
        for share in &node.lights {
            let lost_diffuse = node.pixel_share(share.unshadowed_diffuse - share.diffuse);
            let lost_specular = node.pixel_share(share.unshadowed_specular - share.specular);
            if lost_diffuse + lost_specular != Color::ZERO {
                let mut words = format!(
                    "{at}raylab's shadow ray to light {} is {}, and the diffuse term it removes is \
                     {:.2}",
                    share.light,
                    shadow_state(node, share.light),
                    mean(lost_diffuse)
                );
                if mean(lost_specular) >= 0.005 {
                    words += &format!(", the specular term {:.2}", mean(lost_specular));
                }
                shadows += lost_diffuse + lost_specular;
                found.push(Candidate {
                    words,
                    change: lost_diffuse + lost_specular,
                });
            }
            speculars += node.pixel_share(share.specular);
            for (name, term) in [("specular", share.specular), ("diffuse", share.diffuse)] {
                let term = node.pixel_share(term);
                if term != Color::ZERO {
                    found.push(Candidate {
                        words: format!(
                            "{at}raylab's {name} term from light {} adds {:.2}",
                            share.light,
                            mean(term)
                        ),
                        change: -term,
                    });
                }
            }
        }
        let ambient = node.pixel_share(hit.ambient);
        if ambient != Color::ZERO {
            found.push(Candidate {
                words: format!("{at}raylab's ambient term adds {:.2}", mean(ambient)),
                change: -ambient,
            });
        }
        for &child in &node.children {
            let share = subtree_share(tree, child);
            let child_node = &tree.nodes[child];
            let sees = match &child_node.hit {
                Some(hit) => format!("sees {}", hit.label),
                None => "leaves the scene".to_string(),
            };
            found.push(Candidate {
                words: format!(
                    "{at}raylab's {} ray, which {sees}, adds {:.2}",
                    child_node.kind.name(),
                    mean(share)
                ),
                change: -share,
            });
        }
    }
    if shadows != Color::ZERO {
        found.push(Candidate {
            words: format!(
                "raylab's shadow rays, all together, remove {:.2} of light",
                mean(shadows)
            ),
            change: shadows,
        });
    }
    if speculars != Color::ZERO {
        found.push(Candidate {
            words: format!(
                "raylab's specular terms, all together, add {:.2}",
                mean(speculars)
            ),
            change: -speculars,
        });
    }
    for kind in [RayKind::Reflected, RayKind::Transmitted] {
        let share: Color = (0..tree.nodes.len())
            .filter(|&i| below(tree, i, kind))
            .map(|i| tree.nodes[i].contribution)
            .sum();
        if share != Color::ZERO {
            found.push(Candidate {
                words: format!(
                    "raylab's {} rays, all together, add {:.2}",
                    kind.name(),
                    mean(share)
                ),
                change: -share,
            });
        }
    }
    found
}

/// The terms of the eye ray's hit, and its children's shares.
fn eye_terms(tree: &RayTree) -> Vec<Term> {
    let eye = &tree.nodes[0];
    let term = |what: String, share: Color, note: Option<String>| Term {
        what,
        share: mean(eye.pixel_share(share)),
        note,
    };
    let Some(hit) = &eye.hit else {
        return vec![term("background".into(), eye.local_color, None)];
    };
    let mut terms = Vec::new();
    if hit.emission != Color::ZERO {
        terms.push(term("emission".into(), hit.emission, None));
    }
    terms.push(term("ambient".into(), hit.ambient, None));
    for share in &eye.lights {
        let mut note = format!("shadow ray {}", shadow_state(eye, share.light));
        if share.unshadowed_diffuse != share.diffuse {
            let unshadowed = mean(eye.pixel_share(share.unshadowed_diffuse));
            note += &format!("; {unshadowed:.2} unshadowed");
        }
        let light = share.light;
        terms.push(term(
            format!("light {light} diffuse"),
            share.diffuse,
            Some(note),
        ));
        terms.push(term(
            format!("light {light} specular"),
            share.specular,
            None,
        ));
    }
    for &child in &eye.children {
        terms.push(Term {
            what: format!("{} ray", tree.nodes[child].kind.name()),
            share: mean(subtree_share(tree, child)),
            note: None,
        });
    }
    terms
}

/// "clear", "tinted by …" or "blocked by …": the shadow ray of `node` to `light`.
fn shadow_state(node: &RayNode, light: usize) -> String {
    let Some(shadow) = node.shadows.iter().find(|s| s.light == light) else {
        return "not traced (shadows are off)".into();
    };
    let by: Vec<&str> = shadow.blockers.iter().map(|b| b.label.as_str()).collect();
    if shadow.blocked {
        format!("blocked by {}", by.join(", "))
    } else if by.is_empty() {
        "clear".into()
    } else {
        format!("tinted by {}", by.join(", "))
    }
}

/// The share of the pixel of node `index` and all below it.
fn subtree_share(tree: &RayTree, index: usize) -> Color {
    let node = &tree.nodes[index];
    node.contribution
        + node
            .children
            .iter()
            .map(|&c| subtree_share(tree, c))
            .sum::<Color>()
}

/// Whether node `index` is a ray of `kind` or below one.
fn below(tree: &RayTree, index: usize, kind: RayKind) -> bool {
    let mut at = Some(index);
    while let Some(i) = at {
        if tree.nodes[i].kind == kind {
            return true;
        }
        at = tree.nodes[i].parent;
    }
    false
}
