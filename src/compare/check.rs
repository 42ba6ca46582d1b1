//! What `raylab check` finds: how an image differs from raylab's render of the same scene
//! ([`check`]), the common mistakes that account for it (found by making raylab's image with
//! them, [`super::mistakes`], and keeping those that bring it closest), and for the worst pixel
//! of each of the largest regions that differ, the ray tree's account of why
//! ([`super::explain`]).

use std::collections::HashMap;
use std::fmt::Write;

use serde::Serialize;
use strum::IntoEnumIterator;

use super::difference::{Difference, difference};
use super::explain::{PixelExplanation, explain_pixel};
use super::mistakes::{Mistake, trace_with, write_with};
use super::regions::{Region, regions};
use crate::color::Color;
use crate::inspect::trace_ray_tree;
use crate::render::Assembled;
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
    /// How many regions differ.
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
    pub description: &'static str,
    pub over_tolerance: u64,
}

/// A region where the images differ, and why its worst pixel does.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExplainedRegion {
    pub region: Region,
    pub explanation: PixelExplanation,
}

/// Compares `image` with raylab's render of `assembled`'s scene (which must be of the image's
/// size) with a tolerance of `tolerance` levels, and finds why they differ.
pub fn check(
    assembled: &Assembled,
    image: &SrgbImage,
    tolerance: u8,
) -> Result<CheckReport, String> {
    let settings = &assembled.scene.settings;
    let (width, height) = (settings.width, settings.height);
    let mut traced: HashMap<Vec<Mistake>, Vec<Color>> = HashMap::new();
    let colors = traced
        .entry(Vec::new())
        .or_insert_with(|| trace_with(assembled, &[]));
    let reference = write_with(width, height, colors, &[]);
    let figures = difference(&reference, image, tolerance)?;
    if figures.within_tolerance() {
        return Ok(CheckReport {
            difference: figures,
            region_count: 0,
            causes: Vec::new(),
            regions: Vec::new(),
            samples: settings.samples,
        });
    }
    let found = regions(&reference, image, tolerance)?;
    let causes = find_mistakes(assembled, image, tolerance, &figures, &mut traced)?;
    let tracer = assembled.tracer();
    let explained = found
        .iter()
        .take(REGIONS_EXPLAINED)
        .map(|region| {
            let (x, y) = region.worst;
            let tree = trace_ray_tree(&tracer, x, y);
            ExplainedRegion {
                region: region.clone(),
                explanation: explain_pixel(&tree, image.at(x, y), reference.at(x, y)),
            }
        })
        .collect();
    Ok(CheckReport {
        difference: figures,
        region_count: found.len(),
        causes,
        regions: explained,
        samples: settings.samples,
    })
}

/// The mistakes, at most [`MOST_MISTAKES`], that bring raylab's image closest to `image`: one
/// at a time, the one that leaves the fewest pixels over the tolerance (then the smallest mean
/// difference), as long as it at least halves them. `traced` keeps the images traced, by the
/// mistakes that change the tracing.
fn find_mistakes(
    assembled: &Assembled,
    image: &SrgbImage,
    tolerance: u8,
    figures: &Difference,
    traced: &mut HashMap<Vec<Mistake>, Vec<Color>>,
) -> Result<Vec<Cause>, String> {
    let (width, height) = (figures.width, figures.height);
    let mut made: Vec<Mistake> = Vec::new();
    let mut causes = Vec::new();
    let mut over = figures.over_tolerance;
    while made.len() < MOST_MISTAKES && over > 0 {
        // Only images traced with every mistake made so far can serve again: the others go, so
        // that at most one round's images are held (a dozen at most).
        traced.retain(|key, _| made.iter().all(|m| !m.retraces() || key.contains(m)));
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
            trial.sort();
            let retraced: Vec<Mistake> = trial.iter().copied().filter(|m| m.retraces()).collect();
            let colors = traced
                .entry(retraced.clone())
                .or_insert_with(|| trace_with(assembled, &retraced));
            let made_image = write_with(width, height, colors, &trial);
            let d = difference(&made_image, image, tolerance)?;
            let score = (d.over_tolerance, d.mean_absolute);
            if best.is_none_or(|(o, m, _)| score < (o, m)) {
                best = Some((score.0, score.1, mistake));
            }
        }
        match best {
            Some((after, _, mistake)) if after * 2 <= over && after < over => {
                made.push(mistake);
                causes.push(Cause {
                    mistake,
                    description: mistake.describe(),
                    over_tolerance: after,
                });
                over = after;
            }
            _ => break,
        }
    }
    Ok(causes)
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
            "{} pixels ({:.2} %) over the tolerance of {} levels, in {} regions; mean absolute \
             difference {:.4} levels, largest {} at pixel ({}, {})",
            d.over_tolerance,
            100.0 * d.over_tolerance_share(),
            d.tolerance,
            self.region_count,
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
