//! Progressive rendering by block size, as in the lecture: trace only the top-left pixel of each
//! `b × b` block and paint the whole block, starting with a coarse `b` and halving it down to 1.
//! Pass `b` traces exactly the pixels whose row and column are multiples of `b` and that no
//! coarser pass traced, so all passes together trace every pixel once. After block size 1,
//! optional passes add jittered samples (anti-aliasing), in one of two ways:
//!
//! - uniform sampling (`aa_threshold = 0`): each pass adds one sample to every pixel, up to
//!   `samples` per pixel;
//! - adaptive anti-aliasing (`aa_threshold > 0`, as POV-Ray's): a Whitted image has no noise,
//!   only edges, so each round supersamples only the pixels whose colour differs from one of
//!   their four neighbours' by more than the threshold, bringing them to a number of samples
//!   that doubles each round (2, 4, 8, … up to the `samples` cap). The colours compared are the
//!   film's at the start of the round as they are saved and shown: 8-bit sRGB, clamped, the
//!   largest difference of one channel, on a 0–1 scale (0.03 is about 8 levels of 255). A pixel
//!   can join in any round (its neighbour changed), and flat regions keep their one sample.
//!
//! Either way the image depends only on the settings: samples are numbered and placed by the
//! pixel ([`jitter`](crate::sampling::jitter)), and a round decides from a snapshot of the film
//! taken between passes, so the threads' order does not matter. A pixel given all `samples`
//! samples by the adaptive rounds is exactly the uniform render's pixel.
//!
//! A film can be a window of the image ([`Film::window`](crate::film::Film::window)): its pixels
//! are traced as the image's pixels at their place. A tile of an image renders the same as in
//! the whole image if its film reaches [`decision_reach`] pixels further on every side (where the
//! image has them): each adaptive round decides from the four neighbours as they were after the
//! round before, so after `r` rounds a pixel depends on the first sweep's colours up to `r`
//! pixels away, and a window's edge, which has no neighbours beyond it, disturbs only the pixels
//! within `r` of it.
//!
//! A render nobody watches before it ends (to a file) needs none of the coarse passes: it traces
//! every pixel, with all its samples under uniform sampling, in one sweep ([`unwatched_passes`],
//! [`render_unwatched`]), and ends with the same film.
//!
//! Each pixel sample is what the caller's [`SampleColoring`] makes of its eye ray: the Whitted colour
//! ([`Shaded`]), or another view of the scene (the inspector's debug views implement
//! [`SampleColoring`] too), refined by the same passes.
//!
//! The plan ([`plan`]: the passes and the samples each takes) and the control ([`control`]:
//! cancel, pause, progress, statistics) belong to no device; [`cpu`] sweeps the passes on all
//! of rayon's threads, the eye rays of each 8 × 8 tile traced together; [`gpu`] (with the `gpu`
//! feature) traces the same passes' samples on the GPU. A program chooses between them in
//! one place, [`crate::backend`].

mod coloring;
pub mod control;
pub mod cpu;
#[cfg(feature = "gpu")]
pub mod gpu;
mod pass;
pub mod plan;

pub use coloring::{SampleColoring, Shaded};
pub use control::{Cancelled, PassStats, Progress, RenderControl, RenderStats, run_plan};
pub use cpu::{
    render, render_film, render_image, render_image_with, render_pass, render_unwatched,
};
pub use plan::{Pass, decision_reach, memory_bytes, passes, traces_pixel, unwatched_passes};
