//! What `raylab check` finds: how an image differs from raylab's render of the same scene
//! ([`check`]), the common mistakes that account for it (found by making raylab's image with
//! them, [`super::mistakes`], and keeping those that bring it closest), and for the worst pixel
//! of each of the largest regions that differ, the ray tree's account of why
//! ([`super::explain`]).

use std::fmt::Write;

use serde::Serialize;
use strum::IntoEnumIterator;

use super::difference::{Difference, difference, difference_from};
use super::evidence::{Evidence, evidence};
use super::explain::{PixelExplanation, explain_pixel};
use super::mistakes::{Mistake, Written, fitted_scale, trace_with};
use super::regions::{Region, regions};
use crate::film::Film;
use crate::inspect::trace_ray_tree;
use crate::render::Assembled;
use crate::settings::RenderSettings;
use crate::srgb_image::SrgbImage;

/// How many mistakes at once are looked for.
const MOST_MISTAKES: usize = 3;

/// How many of the largest regions have their worst pixel explained.
const REGIONS_EXPLAINED: usize = 3;

/// What `raylab check` found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CheckReport {
    /// The image against raylab's render of the scene.
    pub difference: Difference,
    /// What the image shows on its own, or against raylab's, when that says where to look:
    /// all one colour, edges that do not line up with raylab's.
    pub evidence: Vec<Evidence>,
    /// How many regions differ (after the mistakes found are made, where they change the whole
    /// image alike).
    pub region_count: usize,
    /// The mistakes that account for the difference, in the order found: with each (and those
    /// before it) made, raylab's image has `over_tolerance` pixels over the tolerance.
    pub causes: Vec<Cause>,
    /// The largest regions, each with its worst pixel explained.
    pub regions: Vec<ExplainedRegion>,
    /// The samples per pixel of raylab's render (more than one: anti-aliased).
    pub samples: u32,
}

/// A mistake that accounts for (part of) the difference.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cause {
    pub mistake: Mistake,
    pub description: String,
    pub over_tolerance: u64,
}

/// A region where the images differ, and why its worst pixel does.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExplainedRegion {
    pub region: Region,
    pub explanation: PixelExplanation,
}

/// The memory [`check`] takes for an image of `settings`' size beyond the scene and the image
/// itself: raylab's image as written (3 bytes a pixel), two traced films at once (the one the
/// mistakes found so far make and the one being tried, 16 bytes a pixel each), the render's own
/// copy for its anti-aliasing rounds, and the regions' marks and their search's stack (6).
pub fn memory_bytes(settings: &RenderSettings) -> u64 {
    let (width, height) = (settings.width, settings.height);
    let pixels = u64::from(width) * u64::from(height);
    pixels * (3 + 6)
        + 2 * Film::memory_bytes(width, height)
        + crate::progressive::memory_bytes(settings)
}

/// Compares `image` with raylab's render of `assembled`'s scene (which must be of the image's
/// size) with a tolerance of `tolerance` levels, and finds why they differ. `step` hears of each
/// image traced, as it starts (what it is for).
pub fn check(
    assembled: &Assembled,
    image: &SrgbImage,
    tolerance: u8,
    step: &mut dyn FnMut(&str),
) -> Result<CheckReport, String> {
    let settings = &assembled.scene.settings;
    step("tracing raylab's image");
    let traced = trace_with(assembled, &[]);
    let reference = Written {
        colors: &traced,
        mistakes: &[],
        scale: 1.0,
    }
    .image();
    let figures = difference(&reference, image, tolerance)?;
    let mut report = CheckReport {
        difference: figures,
        evidence: Vec::new(),
        region_count: 0,
        causes: Vec::new(),
        regions: Vec::new(),
        samples: settings.samples,
    };
    if report.difference.within_tolerance() {
        return Ok(report);
    }
    let scale = fitted_scale(&traced, image);
    let over = report.difference.over_tolerance;
    let (causes, made) = find_mistakes(assembled, image, tolerance, (traced, over), scale, step)?;
    // A mistake that changes the whole image alike (a flip, a curve, the camera) is no term of
    // a pixel's ray tree: the regions are what is left once it is made.
    let compared = match causes.iter().any(|c| !c.mistake.is_local()) {
        true => {
            let mistakes: Vec<Mistake> = causes.iter().map(|c| c.mistake).collect();
            Written {
                colors: &made,
                mistakes: &mistakes,
                scale,
            }
            .image()
        }
        false => reference,
    };
    drop(made);
    let found = regions(&compared, image, tolerance)?;
    if causes.is_empty() {
        report.evidence = evidence(&compared, image, scale);
    }
    // Where the image as a whole points elsewhere (one colour, the camera), no pixel's ray tree
    // speaks to it.
    let explained = if report.evidence.is_empty() {
        REGIONS_EXPLAINED
    } else {
        0
    };
    let tracer = assembled.tracer();
    report.regions = found
        .iter()
        .take(explained)
        .map(|region| {
            let (x, y) = region.worst;
            let tree = trace_ray_tree(&tracer, x, y);
            ExplainedRegion {
                region: region.clone(),
                explanation: explain_pixel(&tree, image.at(x, y), compared.at(x, y)),
            }
        })
        .collect();
    report.region_count = found.len();
    report.causes = causes;
    Ok(report)
}

/// The mistakes, at most [`MOST_MISTAKES`], that bring raylab's image closest to `image`: one
/// at a time, the one that leaves the fewest pixels over the tolerance (then the smallest mean
/// difference), as long as it at least halves them. `traced` is raylab's image and the pixels
/// over the tolerance it leaves; `scale` the factor [`Mistake::Scaled`] multiplies by. Returns them and the image traced with them. At
/// most two traced images are held at once: the one the mistakes found so far make, and the one
/// being tried.
fn find_mistakes(
    assembled: &Assembled,
    image: &SrgbImage,
    tolerance: u8,
    (traced, mut over): (Film, u64),
    scale: f32,
    step: &mut dyn FnMut(&str),
) -> Result<(Vec<Cause>, Film), String> {
    let mut base = traced;
    let mut made: Vec<Mistake> = Vec::new();
    let mut causes = Vec::new();
    while made.len() < MOST_MISTAKES && over > 0 {
        let mut best: Option<(u64, f64, Mistake)> = None;
        for mistake in Mistake::iter() {
            if made.contains(&mistake)
                || made.iter().any(|m| m.excludes(mistake))
                || !mistake.applies_to(&assembled.scene)
            {
                continue;
            }
            let mut trial = made.clone();
            trial.push(mistake);
            let retraced = if mistake.retraces() {
                let retraced: Vec<Mistake> =
                    trial.iter().copied().filter(|m| m.retraces()).collect();
                step(&format!(
                    "tracing raylab's image as if {}",
                    mistake.describe()
                ));
                Some(trace_with(assembled, &retraced))
            } else {
                None
            };
            let written = Written {
                colors: retraced.as_ref().unwrap_or(&base),
                mistakes: &trial,
                scale,
            };
            let d = difference_from(|x, y| written.at(x, y), image, tolerance);
            let score = (d.over_tolerance, d.mean_absolute);
            if best.is_none_or(|(o, m, _)| score < (o, m)) {
                best = Some((score.0, score.1, mistake));
            }
        }
        match best {
            Some((after, _, mistake)) if after * 2 <= over && after < over => {
                made.push(mistake);
                if mistake.retraces() {
                    let retraced: Vec<Mistake> =
                        made.iter().copied().filter(|m| m.retraces()).collect();
                    step(&format!(
                        "tracing raylab's image as if {}",
                        mistake.describe()
                    ));
                    base = trace_with(assembled, &retraced);
                }
                causes.push(Cause {
                    mistake,
                    description: describe(mistake, scale),
                    over_tolerance: after,
                });
                over = after;
            }
            _ => break,
        }
    }
    Ok((causes, base))
}

/// What `check` says of a mistake found: its description, with the factor of a scaling.
fn describe(mistake: Mistake, scale: f32) -> String {
    match mistake {
        Mistake::Scaled => format!(
            "{} (your colours are raylab's × {scale:.2})",
            mistake.describe()
        ),
        _ => mistake.describe().to_string(),
    }
}

impl CheckReport {
    /// The report as text: `image` against raylab's render of `scene` (their names).
    pub fn to_text(&self, image: &str, scene: &str) -> String {
        let d = &self.difference;
        let mut out = format!(
            "{image} against raylab's render of {scene}: {}×{} pixels\n",
            d.width, d.height
        );
        if d.within_tolerance() {
            let _ = writeln!(
                out,
                "every pixel within the tolerance of {} levels (largest difference {})\nwithin tolerance",
                d.tolerance, d.largest
            );
            return out;
        }
        let _ = writeln!(
            out,
            "{} pixels ({:.2} %) over the tolerance of {} levels; mean absolute difference {:.4} \
             levels, largest {} at pixel ({}, {})",
            d.over_tolerance,
            100.0 * d.over_tolerance_share(),
            d.tolerance,
            d.mean_absolute,
            d.largest,
            d.largest_at.0,
            d.largest_at.1
        );
        for (i, cause) in self.causes.iter().enumerate() {
            let _ = writeln!(
                out,
                "{}: {}; raylab's image made with it has {} pixels over the tolerance",
                if i == 0 { "likely cause" } else { "and" },
                cause.description,
                cause.over_tolerance
            );
        }
        if self.causes.is_empty() {
            let _ = writeln!(out, "no common mistake accounts for it");
        }
        for evidence in &self.evidence {
            let _ = writeln!(out, "what your image shows: {}", evidence.says);
        }
        if !self.evidence.is_empty() {
            let _ = writeln!(
                out,
                "its {} regions are not explained pixel by pixel from raylab's ray tree: they \
                 follow from what the image shows",
                self.region_count
            );
        }
        if self.region_count == 0 {
            let _ = writeln!(
                out,
                "with the mistakes found made, raylab's image is yours within the tolerance"
            );
        }
        if self.samples > 1 {
            let _ = writeln!(
                out,
                "note: raylab's render takes up to {} samples per pixel (anti-aliased); a tracer \
                 with one ray per pixel differs at every edge: add --samples 1",
                self.samples
            );
        }
        for (i, explained) in self.regions.iter().enumerate() {
            write_region(&mut out, i, self.region_count, explained);
        }
        let _ = writeln!(out, "different");
        out
    }
}

fn write_region(out: &mut String, index: usize, count: usize, explained: &ExplainedRegion) {
    let (region, e) = (&explained.region, &explained.explanation);
    let [x0, y0, x1, y1] = region.bounds;
    let levels = |c: [u8; 3]| format!("({}, {}, {})", c[0], c[1], c[2]);
    let _ = writeln!(
        out,
        "region {} of {count}: {} pixels in x {x0}–{x1}, y {y0}–{y1}; its worst pixel ({}, {}): \
         yours {}, raylab's {}",
        index + 1,
        region.pixels,
        e.pixel.0,
        e.pixel.1,
        levels(e.yours),
        levels(e.raylab)
    );
    let _ = writeln!(out, "  raylab's eye ray hits {}", e.first_hit);
    let terms: Vec<String> = e
        .terms
        .iter()
        .map(|t| match &t.note {
            Some(note) => format!("{} {:.2} ({note})", t.what, t.share),
            None => format!("{} {:.2}", t.what, t.share),
        })
        .collect();
    let _ = writeln!(out, "  terms: {}", terms.join("; "));
    match &e.accounted_for {
        Some(sentence) => {
            let _ = writeln!(out, "  {sentence}");
        }
        None => {
            let _ = writeln!(out, "  no single term of raylab's ray tree accounts for it");
        }
    }
}
