//! The ray tree as indented text, one ray per paragraph, children below their parent: what
//! `raylab inspect` prints.

use std::fmt::Write;

use glam::Vec3;

use super::ray_tree::{FirstHitSource, LightShare, RayNode, RayTree, ShadowRay};
use crate::color::Color;
use crate::whitted::StopReason;

impl RayTree {
    /// The tree as human-readable text.
    pub fn to_text(&self) -> String {
        let mut out = format!(
            "pixel ({}, {}): colour {}\n",
            self.pixel.0,
            self.pixel.1,
            vec3(self.color)
        );
        match &self.first_hit {
            Some(FirstHitSource::ItemBuffer { item, t }) => {
                let _ = writeln!(out, "first hit: from the item buffer ({item}, t = {t:.4})");
            }
            Some(FirstHitSource::NoItem) => {
                let _ = writeln!(
                    out,
                    "first hit: searched in full (the item buffer holds nothing here)"
                );
            }
            Some(FirstHitSource::ItemMissed { item }) => {
                let _ = writeln!(
                    out,
                    "first hit: searched in full (the eye ray misses its item, {item})"
                );
            }
            None => {}
        }
        if !self.nodes.is_empty() {
            self.write_node(&mut out, 0);
        }
        out
    }

    fn write_node(&self, out: &mut String, index: usize) {
        let node = &self.nodes[index];
        let pad = "  ".repeat(node.depth as usize - 1);
        write_ray(out, &pad, index, node);
        for shadow in &node.shadows {
            write_shadow(out, &pad, shadow);
        }
        for share in &node.lights {
            write_light_share(out, &pad, share);
        }
        for cut in &node.cuts {
            let _ = writeln!(
                out,
                "{pad}  {} ray not traced: {} (weight {:.4})",
                cut.branch.name(),
                reason_text(cut.reason),
                cut.weight
            );
        }
        if let Some(stop) = node.stop {
            let _ = writeln!(out, "{pad}  stop: {}", reason_text(stop));
        }
        for &child in &node.children {
            self.write_node(out, child);
        }
    }
}

/// The ray's header (`index` into the tree's nodes), what it hit and its colours.
fn write_ray(out: &mut String, pad: &str, index: usize, node: &RayNode) {
    let _ = writeln!(
        out,
        "{pad}#{} {} ray, depth {}, weight {:.4}, from {} dir {}",
        index,
        node.kind.name(),
        node.depth,
        node.weight,
        vec3(node.origin),
        vec3(node.dir)
    );
    match &node.hit {
        Some(hit) => {
            let _ = writeln!(
                out,
                "{pad}  hit {} (material {} \"{}\") at t {:.4}, point {}, normal {}, uv ({:.3}, {:.3}), {}",
                hit.label,
                hit.material,
                hit.material_name,
                hit.t,
                vec3(hit.point),
                vec3(hit.normal),
                hit.uv.x,
                hit.uv.y,
                if hit.entering {
                    "front side"
                } else {
                    "back side"
                }
            );
        }
        None => {
            let _ = writeln!(out, "{pad}  missed: background");
        }
    }
    if let Some(hit) = node.hit.as_ref().filter(|hit| hit.emission != Color::ZERO) {
        let _ = writeln!(out, "{pad}  emission {}", vec3(hit.emission));
    }
    if let Some(hit) = &node.hit {
        let _ = writeln!(out, "{pad}  ambient {}", vec3(hit.ambient));
    }
    if let Some(caustic) = node.caustic {
        let _ = writeln!(out, "{pad}  caustic irradiance {}", vec3(caustic));
    }
    // In fog, what the ray brings back of its local colour is dimmed and gains the light the
    // fog scattered into it.
    let mut local = vec3(node.local_color);
    if let Some(fog) = &node.fog {
        let _ = writeln!(
            out,
            "{pad}  fog: transmittance {:.4}, in-scattered light {}",
            fog.transmittance,
            vec3(fog.in_scattered)
        );
        let through = fog.transmittance * node.local_color + fog.in_scattered;
        local = format!("{local} through the fog {}", vec3(through));
    }
    let _ = writeln!(
        out,
        "{pad}  local {local} × factor {} = contribution {}; returns {}",
        vec3(node.factor),
        vec3(node.contribution),
        vec3(node.color)
    );
}

fn write_shadow(out: &mut String, pad: &str, shadow: &ShadowRay) {
    let state = if shadow.blocked {
        "blocked"
    } else if shadow.blockers.is_empty() {
        "clear"
    } else {
        "tinted"
    };
    let _ = write!(
        out,
        "{pad}  shadow ray to light {}: {state}, light arriving {}",
        shadow.light,
        vec3(shadow.light_color)
    );
    for blocker in &shadow.blockers {
        let _ = write!(
            out,
            "; {} at t {:.4} leaves {}",
            blocker.label,
            blocker.t,
            vec3(Vec3::from(blocker.transmittance_after))
        );
    }
    out.push('\n');
}

fn write_light_share(out: &mut String, pad: &str, share: &LightShare) {
    let _ = write!(
        out,
        "{pad}  light {}: diffuse {}, specular {}",
        share.light,
        vec3(share.diffuse),
        vec3(share.specular)
    );
    if (share.diffuse, share.specular) != (share.unshadowed_diffuse, share.unshadowed_specular) {
        let _ = write!(
            out,
            " (unshadowed: diffuse {}, specular {})",
            vec3(share.unshadowed_diffuse),
            vec3(share.unshadowed_specular)
        );
    }
    out.push('\n');
}

fn reason_text(reason: StopReason) -> &'static str {
    match reason {
        StopReason::Miss => "missed",
        StopReason::MaxDepth => "max_depth reached",
        StopReason::MinWeight => "weight below min_weight",
        StopReason::TotalInternalReflection => "total internal reflection",
        StopReason::Disabled => "switched off in the settings",
        StopReason::RayBudget => "the pixel's ray budget is used up",
    }
}

fn vec3(v: Vec3) -> String {
    format!("({:.4}, {:.4}, {:.4})", v.x, v.y, v.z)
}
