//! What `raylab check` finds: how an image differs from raylab's render of the same scene
//! ([`check`]), the common mistakes that account for it (found by making raylab's image with
//! them, [`super::mistakes`], and keeping those that bring it closest), and for the worst pixel
//! of each of the largest regions that differ, the ray tree's account of why
//! ([`super::explain`]).

use std::fmt::Write;
use std::sync::Arc;

use serde::Serialize;
use strum::IntoEnumIterator;

use super::difference::{Difference, difference, difference_from};
use super::evidence::{Evidence, evidence};
use super::explain::{PixelExplanation, explain_pixel};
use super::mistakes::{Mistake, Written, fitted_scale};
use super::regions::{Region, regions};
use super::traces::Traces;
use crate::film::Film;
use crate::inspect::trace_ray_tree;
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
/// itself, with no images traced with mistakes kept ([`Traces`]): raylab's image as written (3
/// bytes a pixel), three traced films at once (raylab's own, the one the mistakes found so far
/// make and the one being tried, 16 bytes a pixel each), the render's own copy for its
/// anti-aliasing rounds, and the regions' marks and their search's stack (6).
pub fn memory_bytes(settings: &RenderSettings) -> u64 {
    let (width, height) = (settings.width, settings.height);
    let pixels = u64::from(width) * u64::from(height);
    pixels * (3 + 6)
        + 3 * Film::memory_bytes(width, height)
        + crate::progressive::memory_bytes(settings)
}

/// Compares `image` with raylab's render of `traces`' scene (which must be of the image's
/// size) with a tolerance of `tolerance` levels, and finds why they differ. `step` hears of each
/// image traced, as it starts (what it is for).
pub fn check(
    traces: &Traces,
    image: &SrgbImage,
    tolerance: u8,
    step: &mut dyn FnMut(&str),
) -> Result<CheckReport, String> {
    let assembled = &traces.assembled;
    let reference = &traces.reference;
    let figures = difference(reference, image, tolerance)?;
    let mut report = CheckReport {
        difference: figures,
        evidence: Vec::new(),
        region_count: 0,
        causes: Vec::new(),
        regions: Vec::new(),
        samples: assembled.scene.settings.samples,
    };
    if report.difference.within_tolerance() {
        return Ok(report);
    }
    let scale = fitted_scale(&traces.film, image);
    let over = report.difference.over_tolerance;
    let (causes, made) = find_mistakes(traces, image, tolerance, over, scale, step);
    // A mistake that changes the whole image alike (a flip, a curve, the camera) is no term of
    // a pixel's ray tree: the regions are what is left once it is made.
    let written;
    let compared = match causes.iter().any(|c| !c.mistake.is_local()) {
        true => {
            let mistakes: Vec<Mistake> = causes.iter().map(|c| c.mistake).collect();
            written = Written {
                colors: &made,
                mistakes: &mistakes,
                scale,
            }
            .image();
            &written
        }
        false => reference,
    };
    drop(made);
    let found = regions(compared, image, tolerance)?;
    if causes.is_empty() {
        report.evidence = evidence(compared, image, scale);
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
/// difference), as long as it at least halves them. `over` is the pixels over the tolerance
/// raylab's own image leaves; `scale` the factor [`Mistake::Scaled`] multiplies by. Returns
/// them and the image traced with them.
fn find_mistakes(
    traces: &Traces,
    image: &SrgbImage,
    tolerance: u8,
    mut over: u64,
    scale: f32,
    step: &mut dyn FnMut(&str),
) -> (Vec<Cause>, Arc<Film>) {
    let mut base = traces.film.clone();
    let mut made: Vec<Mistake> = Vec::new();
    let mut causes = Vec::new();
    while made.len() < MOST_MISTAKES && over > 0 {
        let mut best: Option<(u64, f64, Mistake)> = None;
        for mistake in Mistake::iter() {
            if made.contains(&mistake)
                || made.iter().any(|m| m.excludes(mistake))
                || !mistake.applies_to(&traces.assembled.scene)
            {
                continue;
            }
            let mut trial = made.clone();
            trial.push(mistake);
            let colors = match mistake.retraces() {
                true => traces.traced(&trial, step),
                false => base.clone(),
            };
            let written = Written {
                colors: &colors,
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
                    base = traces.traced(&made, step);
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
    (causes, base)
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
        for line in self.findings() {
            let _ = writeln!(out, "{line}");
        }
        for (i, explained) in self.regions.iter().enumerate() {
            let mut lines = explained.lines(i, self.region_count).into_iter();
            let _ = writeln!(out, "{}", lines.next().unwrap_or_default());
            for line in lines {
                let _ = writeln!(out, "  {line}");
            }
        }
        let _ = writeln!(out, "different");
        out
    }

    /// What was found, a sentence a line: the mistakes that account for the difference, what
    /// the image shows, and the notes on the regions and the samples.
    pub fn findings(&self) -> Vec<String> {
        let mut lines = Vec::new();
        for (i, cause) in self.causes.iter().enumerate() {
            lines.push(format!(
                "{}: {}; raylab's image made with it has {} pixels over the tolerance",
                if i == 0 { "likely cause" } else { "and" },
                cause.description,
                cause.over_tolerance
            ));
        }
        if self.causes.is_empty() {
            lines.push("no common mistake accounts for it".into());
        }
        for evidence in &self.evidence {
            lines.push(format!("what your image shows: {}", evidence.says));
        }
        if !self.evidence.is_empty() {
            lines.push(format!(
                "its {} regions are not explained pixel by pixel from raylab's ray tree: they \
                 follow from what the image shows",
                self.region_count
            ));
        }
        if self.region_count == 0 {
            lines.push(
                "with the mistakes found made, raylab's image is yours within the tolerance".into(),
            );
        }
        if self.samples > 1 {
            lines.push(format!(
                "note: raylab's render takes up to {} samples per pixel (anti-aliased); a tracer \
                 with one ray per pixel differs at every edge: add --samples 1",
                self.samples
            ));
        }
        lines
    }
}

impl ExplainedRegion {
    /// The region, region `index` of `count`, a line at a time: where it is and its worst
    /// pixel, what raylab's eye ray hits there, the terms of raylab's pixel, and the term that
    /// accounts for the difference.
    pub fn lines(&self, index: usize, count: usize) -> Vec<String> {
        let (region, e) = (&self.region, &self.explanation);
        let [x0, y0, x1, y1] = region.bounds;
        let levels = |c: [u8; 3]| format!("({}, {}, {})", c[0], c[1], c[2]);
        let terms: Vec<String> = e
            .terms
            .iter()
            .map(|t| match &t.note {
                Some(note) => format!("{} {:.2} ({note})", t.what, t.share),
                None => format!("{} {:.2}", t.what, t.share),
            })
            .collect();
        vec![
            format!(
                "region {} of {count}: {} pixels in x {x0}–{x1}, y {y0}–{y1}; its worst pixel \
                 ({}, {}): yours {}, raylab's {}",
                index + 1,
                region.pixels,
                e.pixel.0,
                e.pixel.1,
                levels(e.yours),
                levels(e.raylab)
            ),
            format!("raylab's eye ray hits {}", e.first_hit),
            format!("terms: {}", terms.join("; ")),
            e.accounted_for.clone().unwrap_or_else(|| {
                "no single term of raylab's ray tree accounts for it".to_string()
            }),
        ]
    }
}
