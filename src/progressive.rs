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
//! pixel ([`jitter`]), and a round decides from a snapshot of the film taken between passes, so
//! the threads' order does not matter. A pixel given all `samples` samples by the adaptive rounds
//! is exactly the uniform render's pixel.
//!
//! A film can be a window of the image ([`Film::window`]): its pixels are traced as the image's
//! pixels at their place. A tile of an image renders the same as in the whole image if its film
//! reaches [`decision_reach`] pixels further on every side (where the image has them): each
//! adaptive round decides from the four neighbours as they were after the round before, so
//! after `r` rounds a pixel depends on the first sweep's colours up to `r` pixels away, and a
//! window's edge, which has no neighbours beyond it, disturbs only the pixels within `r` of it.
//!
//! A render nobody watches before it ends (to a file) needs none of the coarse passes: it traces
//! every pixel, with all its samples under uniform sampling, in one sweep ([`unwatched_passes`],
//! [`render_unwatched`]), and ends with the same film.
//!
//! Each pixel sample is what the caller's [`Shader`] makes of its eye ray: the Whitted colour
//! ([`Shaded`]), or another view of the scene (the inspector's debug views implement
//! [`Shader`] too), refined by the same passes.
//!
//! Passes run on all of rayon's threads, band by band of 8 rows of the pass's grid (8 rows of
//! `b × b` blocks, so 8·b rows of pixels in block pass `b`), each band tile by tile of 8 × 8
//! pixels whose eye rays are traced together, up to 64 at a time ([`crate::bvh::packet`]). They
//! report their progress and statistics ([`PassStats`], [`RenderStats`]) as they go, stop at the
//! next band when cancelled from another thread, and wait before the next band, without using
//! the CPU, while paused. Each band marks its rows of the film as changed ([`Film::touch_rows`]).

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::{Duration, Instant};

use arrayvec::ArrayVec;
use rayon::prelude::*;

use crate::bvh::packet::PACKET_SIZE;
use crate::camera::PIXEL_CENTRE;
use crate::color::{Color, srgb8};
use crate::film::Film;
use crate::ray::Ray;
use crate::sampling::jitter;
use crate::settings::RenderSettings;
use crate::stats::{RayCounts, SharedRayCounts};
use crate::whitted::Tracer;

/// What the renderer writes for the pixel samples whose eye rays it traces: the shaded image
/// ([`Shaded`]) or another view of the scene.
pub trait Shader: Sync {
    /// The colours of the neighbouring eye rays `rays` (up to [`PACKET_SIZE`]), into `colors`,
    /// counting the rays traced into `counts`.
    fn shade(&self, tracer: &Tracer, rays: &[Ray], colors: &mut [Color], counts: &mut RayCounts);
}

/// The shaded image: the Whitted colour of each eye ray, the eye rays traced as one packet
/// ([`Tracer::trace_eye_packet`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Shaded;

impl Shader for Shaded {
    #[inline]
    fn shade(&self, tracer: &Tracer, rays: &[Ray], colors: &mut [Color], counts: &mut RayCounts) {
        tracer.trace_eye_packet(rays, colors, counts);
    }
}

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

/// What one pass of progressive rendering did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassStats {
    pub pass: Pass,
    /// Pixels that took samples in this pass: those traced (not painted) in a block pass, all
    /// in a sample pass, those refined in an anti-aliasing round. Its samples are the eye rays
    /// in `rays.primary`.
    pub pixels: u64,
    pub rays: RayCounts,
    pub time: Duration,
}

/// A whole render.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub passes: Vec<PassStats>,
    pub rays: RayCounts,
    pub time: Duration,
}

impl RenderStats {
    /// Millions of rays per second over the whole render.
    pub fn mrays_per_second(&self) -> f64 {
        self.rays.total() as f64 / self.time.as_secs_f64().max(1e-9) / 1e6
    }
}

/// Traced pixels per side of a tile: a tile's eye rays go through the BVH as one packet of
/// [`PACKET_SIZE`].
const TILE: u32 = 8;
const _: () = assert!((TILE * TILE) as usize == PACKET_SIZE);

/// Whether block pass `b` of a render that started at `start` traces pixel (x, y).
pub fn traces_pixel(b: u32, start: u32, x: u32, y: u32) -> bool {
    let on_grid = |s: u32| x.is_multiple_of(s) && y.is_multiple_of(s);
    on_grid(b) && (b >= start || !on_grid(2 * b))
}

/// The render was cancelled before it finished.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cancelled;

/// Where a render is, readable from any thread.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Progress {
    /// Index of the running pass, and how many there are.
    pub pass: u32,
    pub passes: u32,
    /// Block size of the running pass (1 for sample and anti-aliasing passes).
    pub block_size: u32,
    /// Samples per pixel the running pass brings its pixels to (1 for block passes).
    pub samples: u32,
    /// Rows of blocks done in the running pass, and how many it has.
    pub rows_done: u32,
    pub rows: u32,
    pub finished: bool,
}

/// Lets other threads cancel, pause and resume a render and watch its progress.
#[derive(Debug, Default)]
pub struct RenderControl {
    cancelled: AtomicBool,
    /// While set, the tracing threads wait (asleep on `resumed`) before their next band.
    paused: Mutex<bool>,
    resumed: Condvar,
    pass: AtomicU32,
    passes: AtomicU32,
    block_size: AtomicU32,
    samples: AtomicU32,
    rows_done: AtomicU32,
    rows: AtomicU32,
    finished: AtomicBool,
    rays: SharedRayCounts,
    pixels: AtomicU64,
}

impl RenderControl {
    /// Stops the render at the next band (a paused render too).
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
        // Under the lock, so that a thread about to wait sees the flag or hears this.
        let _paused = self.paused.lock();
        self.resumed.notify_all();
    }

    /// Holds the render before its next band until [`resume`](Self::resume) (or a cancel).
    pub fn pause(&self) {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner()) = true;
    }

    pub fn resume(&self) {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner()) = false;
        self.resumed.notify_all();
    }

    pub fn is_paused(&self) -> bool {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Sleeps while the render is paused and not cancelled.
    fn wait_while_paused(&self) {
        let paused = self.paused.lock().unwrap_or_else(|e| e.into_inner());
        let _resumed = self
            .resumed
            .wait_while(paused, |paused| *paused && !self.is_cancelled())
            .unwrap_or_else(|e| e.into_inner());
    }

    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    pub fn progress(&self) -> Progress {
        Progress {
            pass: self.pass.load(Ordering::Relaxed),
            passes: self.passes.load(Ordering::Relaxed),
            block_size: self.block_size.load(Ordering::Relaxed),
            samples: self.samples.load(Ordering::Relaxed),
            rows_done: self.rows_done.load(Ordering::Relaxed),
            rows: self.rows.load(Ordering::Relaxed),
            finished: self.finished.load(Ordering::Relaxed),
        }
    }

    /// Pixel samples traced so far in this render (each pixel once per sample).
    pub fn pixels_traced(&self) -> u64 {
        self.pixels.load(Ordering::Relaxed)
    }

    /// Rays traced so far in this render.
    pub fn rays(&self) -> RayCounts {
        self.rays.get()
    }
}

/// Renders `tracer`'s scene as `shader` shows it into `film` (which must have the settings'
/// size), pass after pass, calling `on_pass` after each. Runs on the current rayon thread pool.
///
/// ```
/// use raylab::bvh::Bvh;
/// use raylab::film::Film;
/// use raylab::formats::load_any;
/// use raylab::progressive::{Pass, RenderControl, Shaded, render};
/// use raylab::whitted::Tracer;
///
/// let mut scene = load_any("assets/scenes/default.toml")?;
/// scene.settings.width = 64;
/// scene.settings.height = 48;
/// scene.settings.block_size = 16;
/// let bvh = Bvh::build(&scene.geometry);
/// let tracer = Tracer::new(&scene, &bvh);
/// let film = Film::new(64, 48);
///
/// let mut block_sizes = Vec::new();
/// let stats = render(&tracer, &Shaded, &film, &RenderControl::default(), |pass| {
///     block_sizes.push(pass.pass) // a viewer would show the film here
/// })
/// .expect("only another thread holding the control can cancel it");
///
/// // Coarse first, refined down to one pixel; every pixel traced exactly once.
/// let expected = [16, 8, 4, 2, 1].map(Pass::Block);
/// assert_eq!(block_sizes, expected);
/// assert_eq!(stats.rays.primary, 64 * 48);
/// # Ok::<(), raylab::formats::SceneError>(())
/// ```
pub fn render(
    tracer: &Tracer,
    shader: &dyn Shader,
    film: &Film,
    control: &RenderControl,
    on_pass: impl FnMut(&PassStats),
) -> Result<RenderStats, Cancelled> {
    let settings = &tracer.scene.settings;
    let plan = passes(
        settings.block_size,
        settings.samples,
        settings.aa_threshold > 0.0,
    );
    render_plan(tracer, shader, film, control, &plan, on_pass)
}

/// [`render`] for a film nobody looks at before it is finished (a render to a file): the
/// [`unwatched_passes`], the same film in the end.
pub fn render_unwatched(
    tracer: &Tracer,
    shader: &dyn Shader,
    film: &Film,
    control: &RenderControl,
) -> Result<RenderStats, Cancelled> {
    let settings = &tracer.scene.settings;
    let plan = unwatched_passes(settings.samples, settings.aa_threshold > 0.0);
    render_plan(tracer, shader, film, control, &plan, |_| {})
}

/// Runs the passes of `plan` one after another, calling `on_pass` after each.
fn render_plan(
    tracer: &Tracer,
    shader: &dyn Shader,
    film: &Film,
    control: &RenderControl,
    plan: &[Pass],
    mut on_pass: impl FnMut(&PassStats),
) -> Result<RenderStats, Cancelled> {
    let settings = &tracer.scene.settings;
    control.passes.store(plan.len() as u32, Ordering::Relaxed);
    let start = Instant::now();
    let mut stats = RenderStats::default();
    // The film as shown, for the anti-aliasing rounds to compare neighbours: allocated once.
    let mut shown = Vec::new();
    for (i, &pass) in plan.iter().enumerate() {
        control.pass.store(i as u32, Ordering::Relaxed);
        let pass_stats = run_pass(
            tracer,
            shader,
            film,
            control,
            pass,
            settings.block_size,
            &mut shown,
        )?;
        stats.rays += pass_stats.rays;
        stats.passes.push(pass_stats);
        on_pass(&pass_stats);
    }
    stats.time = start.elapsed();
    control.finished.store(true, Ordering::Relaxed);
    Ok(stats)
}

/// The memory a render of `settings` takes besides its film: the copy of the film as shown that
/// the anti-aliasing rounds compare neighbours in (none with uniform sampling).
pub fn memory_bytes(settings: &RenderSettings) -> u64 {
    let adaptive = settings.aa_threshold > 0.0 && settings.samples > 1;
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    if adaptive { pixels * 3 } else { 0 }
}

/// Runs one pass over the whole image (an anti-aliasing round compares the pixels as the film
/// has them now).
pub fn render_pass(
    tracer: &Tracer,
    shader: &dyn Shader,
    film: &Film,
    control: &RenderControl,
    pass: Pass,
    start_block: u32,
) -> Result<PassStats, Cancelled> {
    run_pass(
        tracer,
        shader,
        film,
        control,
        pass,
        start_block,
        &mut Vec::new(),
    )
}

/// [`render_pass`], keeping the film's shown colours in `shown` for an anti-aliasing round.
fn run_pass(
    tracer: &Tracer,
    shader: &dyn Shader,
    film: &Film,
    control: &RenderControl,
    pass: Pass,
    start_block: u32,
    shown: &mut Vec<[u8; 3]>,
) -> Result<PassStats, Cancelled> {
    let started = Instant::now();
    let (width, height) = (film.width(), film.height());
    let step = match pass {
        Pass::Block(b) => b,
        Pass::Sample(_) | Pass::Refine(_) | Pass::Sweep(_) => 1,
    };
    if let Pass::Refine(_) = pass {
        take_snapshot(film, shown);
    }
    let rows = height.div_ceil(step);
    control.block_size.store(step, Ordering::Relaxed);
    let samples = match pass {
        Pass::Block(_) => 1,
        Pass::Sample(k) => k + 1,
        Pass::Refine(n) | Pass::Sweep(n) => n,
    };
    control.samples.store(samples, Ordering::Relaxed);
    control.rows.store(rows, Ordering::Relaxed);
    control.rows_done.store(0, Ordering::Relaxed);
    let rays_before = control.rays.get();
    let pixels = AtomicU64::new(0);
    let grid = PassGrid {
        pass,
        start_block,
        step,
        film,
        shown,
        threshold: tracer.scene.settings.aa_threshold,
    };
    let columns = width.div_ceil(step);
    // Bands of TILE rows of the grid go to the threads; each band is traced tile by tile. Each
    // band is a job of its own that an idle thread can take: left to itself, rayon would hand a
    // thread runs of up to a quarter of the bands, and the other would wait at the end of the
    // pass for the rest of the run it cannot take.
    (0..rows.div_ceil(TILE))
        .into_par_iter()
        .with_max_len(1)
        .try_for_each(|band| {
            control.wait_while_paused();
            if control.is_cancelled() {
                return Err(Cancelled);
            }
            let band_rows = band * TILE..((band + 1) * TILE).min(rows);
            let mut counts = RayCounts::default();
            let mut traced = Traced::default();
            for c in (0..columns).step_by(TILE as usize) {
                let tile_columns = c..(c + TILE).min(columns);
                let tile = trace_tile(tracer, shader, &grid, &band_rows, tile_columns, &mut counts);
                traced.pixels += tile.pixels;
                traced.samples += tile.samples;
            }
            control.rays.add(&counts);
            control.pixels.fetch_add(traced.samples, Ordering::Relaxed);
            pixels.fetch_add(traced.pixels, Ordering::Relaxed);
            control
                .rows_done
                .fetch_add(band_rows.len() as u32, Ordering::Relaxed);
            film.touch_rows(band_rows.start * step..band_rows.end * step);
            Ok(())
        })?;
    let rays = control.rays.get() - rays_before;
    Ok(PassStats {
        pass,
        pixels: pixels.into_inner(),
        rays,
        time: started.elapsed(),
    })
}

/// Puts the film's pixels as they are saved and shown (8-bit sRGB) into `shown`, row by row.
fn take_snapshot(film: &Film, shown: &mut Vec<[u8; 3]>) {
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
struct PassGrid<'a> {
    pass: Pass,
    start_block: u32,
    step: u32,
    film: &'a Film,
    /// The film as shown when an anti-aliasing round started (empty for other passes).
    shown: &'a [[u8; 3]],
    threshold: f32,
}

impl PassGrid<'_> {
    /// The numbers of the samples the pass takes at pixel (x, y) (0 is the pixel's centre).
    fn samples_at(&self, x: u32, y: u32) -> Range<u32> {
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

/// What a tile (or a band) traced.
#[derive(Clone, Copy, Debug, Default)]
struct Traced {
    /// Pixels that took samples.
    pixels: u64,
    samples: u64,
}

/// Up to [`PACKET_SIZE`] pixel samples whose eye rays are traced together: the pixel and the
/// sample's number for each ray.
#[derive(Default)]
struct Packet {
    samples: ArrayVec<(u32, u32, u32), PACKET_SIZE>,
    rays: ArrayVec<Ray, PACKET_SIZE>,
}

impl Packet {
    /// Traces the packet's rays and writes their colours to the film: a block painted for a
    /// pixel's first sample, otherwise a sample added to the pixel's mean. Empties the packet.
    fn trace(
        &mut self,
        tracer: &Tracer,
        shader: &dyn Shader,
        grid: &PassGrid,
        counts: &mut RayCounts,
    ) {
        let mut colors = [Color::ZERO; PACKET_SIZE];
        let colors = &mut colors[..self.rays.len()];
        shader.shade(tracer, &self.rays, colors, counts);
        for (&(x, y, sample), &color) in self.samples.iter().zip(colors.iter()) {
            if sample == 0 {
                grid.film.fill_block(x, y, grid.step, color);
            } else {
                grid.film.add_sample(x, y, color);
            }
        }
        self.samples.clear();
        self.rays.clear();
    }
}

/// Traces the samples the pass takes in one tile of `grid` (`rows` × `columns` of it), the eye
/// rays in packets of up to [`PACKET_SIZE`], and writes them to the film.
fn trace_tile(
    tracer: &Tracer,
    shader: &dyn Shader,
    grid: &PassGrid,
    rows: &Range<u32>,
    columns: Range<u32>,
    counts: &mut RayCounts,
) -> Traced {
    let camera = &tracer.scene.camera;
    // The film may be a window of the image: rays and jitter go by the pixel's place in it.
    let size = grid.film.image_size();
    let (left, top) = grid.film.origin();
    let mut packet = Packet::default();
    let mut traced = Traced::default();
    for row in rows.clone() {
        for column in columns.clone() {
            let (x, y) = (column * grid.step, row * grid.step);
            let samples = grid.samples_at(x, y);
            traced.pixels += u64::from(!samples.is_empty());
            traced.samples += u64::from(samples.len() as u32);
            for k in samples {
                if packet.rays.is_full() {
                    packet.trace(tracer, shader, grid, counts);
                }
                let pixel = (left + x, top + y);
                let offset = if k == 0 {
                    PIXEL_CENTRE
                } else {
                    jitter(pixel.0, pixel.1, k)
                };
                packet.rays.push(camera.eye_ray(pixel, offset, size));
                packet.samples.push((x, y, k));
            }
        }
    }
    if !packet.rays.is_empty() {
        packet.trace(tracer, shader, grid, counts);
    }
    traced
}

/// Renders the whole shaded image in one go (no progressive display), returning its pixels.
pub fn render_image(tracer: &Tracer) -> (Vec<Color>, RenderStats) {
    render_image_with(tracer, &Shaded)
}

/// [`render_image`] of what `shader` shows.
pub fn render_image_with(tracer: &Tracer, shader: &dyn Shader) -> (Vec<Color>, RenderStats) {
    let settings = &tracer.scene.settings;
    let film = Film::new(settings.width, settings.height);
    let control = RenderControl::default();
    let stats = render(tracer, shader, &film, &control, |_| {}).unwrap_or_else(|Cancelled| {
        unreachable!("nobody else holds this render's control, so it cannot be cancelled")
    });
    (film.pixels(), stats)
}
