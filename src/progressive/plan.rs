//! The plan of a progressive render, whatever traces it: its passes (block sizes, then
//! anti-aliasing samples or rounds), which pixel samples each pass takes, and how far the
//! adaptive rounds look. A tracer backend sweeps the film pass by pass as this says.

use std::ops::Range;

use rayon::prelude::*;

use crate::camera::{Camera, PIXEL_CENTRE};
use crate::color::srgb8;
use crate::film::Film;
use crate::ray::Ray;
use crate::sampling::jitter;
use crate::settings::RenderSettings;

/// One pass of refinement.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// Trace one pixel per `b × b` block and paint the block.
    Block(u32),
    /// Add jittered sample number `k` (k ≥ 1; sample 0 is the pixel centre) to every pixel.
    Sample(u32),
    /// A round of adaptive anti-aliasing: bring every pixel whose colour differs from a
    /// neighbour's by more than the threshold up to `n` samples.
    Refine(u32),
    /// Trace samples 0 to `n - 1` of every pixel in one sweep: what the block passes and the
    /// sample passes up to `Sample(n - 1)` leave in the film, when nobody watches them.
    Sweep(u32),
}

impl Pass {
    /// The side of the blocks of the pass's grid (1 but for block passes).
    pub fn step(self) -> u32 {
        match self {
            Pass::Block(b) => b,
            Pass::Sample(_) | Pass::Refine(_) | Pass::Sweep(_) => 1,
        }
    }

    /// The samples per pixel the pass brings its pixels to (1 for block passes).
    pub fn samples(self) -> u32 {
        match self {
            Pass::Block(_) => 1,
            Pass::Sample(k) => k + 1,
            Pass::Refine(n) | Pass::Sweep(n) => n,
        }
    }
}

/// The passes of a render starting at `block_size` (a power of two) with `samples` per pixel:
/// after the block passes, one pass per sample, or with `adaptive` anti-aliasing rounds to 2, 4,
/// 8, … samples, the last to `samples`.
pub fn passes(block_size: u32, samples: u32, adaptive: bool) -> Vec<Pass> {
    let blocks = std::iter::successors(Some(block_size.max(1)), |&b| (b > 1).then_some(b / 2));
    let sampling: Vec<Pass> = if adaptive {
        let doubling = std::iter::successors(Some(2), |&n: &u32| Some(n.saturating_mul(2)));
        doubling
            .take_while(|&n| n < samples)
            .chain((samples > 1).then_some(samples))
            .map(Pass::Refine)
            .collect()
    } else {
        (1..samples).map(Pass::Sample).collect()
    };
    blocks.map(Pass::Block).chain(sampling).collect()
}

/// The passes of a render whose coarse passes nobody watches (a render to a file): every pixel
/// and, with uniform sampling, all its samples in one [`Pass::Sweep`], without the block passes'
/// painting and the waits between passes; then the adaptive rounds of [`passes`], which decide
/// from the whole film. The film ends as after [`passes`], whatever the starting block size.
pub fn unwatched_passes(samples: u32, adaptive: bool) -> Vec<Pass> {
    if !adaptive {
        return vec![Pass::Sweep(samples.max(1))];
    }
    // The rounds after block pass 1.
    let rounds = passes(1, samples, adaptive).into_iter().skip(1);
    std::iter::once(Pass::Sweep(1)).chain(rounds).collect()
}

/// How many pixels away the adaptive rounds of a render with `settings` look, all rounds
/// together: one per round (0 with uniform sampling). A window grown by this much on every side
/// renders its inner pixels exactly as the whole image does.
pub fn decision_reach(settings: &RenderSettings) -> u32 {
    let plan = unwatched_passes(settings.samples, settings.aa_threshold > 0.0);
    plan.iter().filter(|p| matches!(p, Pass::Refine(_))).count() as u32
}

/// Whether block pass `b` of a render that started at `start` traces pixel (x, y).
pub fn traces_pixel(b: u32, start: u32, x: u32, y: u32) -> bool {
    let on_grid = |s: u32| x.is_multiple_of(s) && y.is_multiple_of(s);
    on_grid(b) && (b >= start || !on_grid(2 * b))
}

/// The memory a render of `settings` takes besides its film: the copy of the film as shown that
/// the anti-aliasing rounds compare neighbours in (none with uniform sampling).
pub fn memory_bytes(settings: &RenderSettings) -> u64 {
    let adaptive = settings.aa_threshold > 0.0 && settings.samples > 1;
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    if adaptive { pixels * 3 } else { 0 }
}

/// The eye ray of sample `k` of pixel `(x, y)` of `film`: through the pixel's centre for sample
/// 0, through its jittered point ([`jitter`]) for k ≥ 1. Rays and jitter go by the pixel's place
/// in the whole image, of which the film may be a window. The WGSL's twin is `sample_ray_dir`
/// (`shaders/camera.wgsl`).
pub fn sample_ray(camera: &Camera, film: &Film, (x, y): (u32, u32), k: u32) -> Ray {
    let (left, top) = film.origin();
    let pixel = (left + x, top + y);
    let offset = if k == 0 {
        PIXEL_CENTRE
    } else {
        jitter(pixel.0, pixel.1, k)
    };
    camera.eye_ray(pixel, offset, film.image_size())
}

/// Puts the film's pixels as they are saved and shown (8-bit sRGB) into `shown`, row by row.
pub(crate) fn take_snapshot(film: &Film, shown: &mut Vec<[u8; 3]>) {
    let width = film.width() as usize;
    shown.resize(width * film.height() as usize, [0; 3]);
    shown
        .par_chunks_mut(width)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, pixel) in row.iter_mut().enumerate() {
                *pixel = film.get(x as u32, y as u32).to_array().map(srgb8);
            }
        });
}

/// The pixels of one pass: a grid of `step`-pixel blocks over the film, of which the pass traces
/// the top-left pixel of each block it has not traced before, or adds samples to pixels.
pub(crate) struct PassGrid<'a> {
    pub pass: Pass,
    start_block: u32,
    pub step: u32,
    pub film: &'a Film,
    /// The film as shown when an anti-aliasing round started (empty for other passes).
    shown: &'a [[u8; 3]],
    threshold: f32,
}

impl<'a> PassGrid<'a> {
    /// The grid of `pass` of a render that started at `start_block` over `film`; `shown` is the
    /// film as shown at the start of an anti-aliasing round, compared against `threshold`.
    pub fn new(
        pass: Pass,
        start_block: u32,
        film: &'a Film,
        shown: &'a [[u8; 3]],
        threshold: f32,
    ) -> PassGrid<'a> {
        PassGrid {
            pass,
            start_block,
            step: pass.step(),
            film,
            shown,
            threshold,
        }
    }

    /// The numbers of the samples the pass takes at pixel (x, y) (0 is the pixel's centre).
    pub fn samples_at(&self, x: u32, y: u32) -> Range<u32> {
        match self.pass {
            Pass::Block(b) if traces_pixel(b, self.start_block, x, y) => 0..1,
            Pass::Block(_) => 0..0,
            Pass::Sample(k) => k..k + 1,
            Pass::Sweep(n) => 0..n,
            Pass::Refine(n) => {
                let taken = self.film.samples(x, y);
                if taken < n && self.differs_from_a_neighbour(x, y) {
                    taken..n
                } else {
                    0..0
                }
            }
        }
    }

    /// Whether pixel (x, y) as shown differs from one of its four neighbours by more than the
    /// threshold in some channel.
    fn differs_from_a_neighbour(&self, x: u32, y: u32) -> bool {
        let (width, height) = (self.film.width(), self.film.height());
        let at = |x: u32, y: u32| self.shown[y as usize * width as usize + x as usize];
        let pixel = at(x, y);
        let neighbours = [
            (x > 0).then(|| (x - 1, y)),
            (x + 1 < width).then(|| (x + 1, y)),
            (y > 0).then(|| (x, y - 1)),
            (y + 1 < height).then(|| (x, y + 1)),
        ];
        neighbours.into_iter().flatten().any(|(nx, ny)| {
            let neighbour = at(nx, ny);
            (0..3).any(|c| f32::from(pixel[c].abs_diff(neighbour[c])) / 255.0 > self.threshold)
        })
    }
}
