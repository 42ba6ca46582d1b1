//! Progressive rendering by block size, as in the lecture: trace only the top-left pixel of each
//! `b × b` block and paint the whole block, starting with a coarse `b` and halving it down to 1.
//! Pass `b` traces exactly the pixels whose row and column are multiples of `b` and that no
//! coarser pass traced, so all passes together trace every pixel once. After block size 1,
//! optional passes add one jittered sample per pixel each (anti-aliasing).
//!
//! Each pixel sample is what the caller's [`Shader`] makes of its eye ray: the Whitted colour
//! ([`Shaded`]), or another view of the scene (the inspector's debug views implement
//! [`Shader`] too), refined by the same passes.
//!
//! Passes run on all of rayon's threads, band by band of 8 rows of the pass's grid (8 rows of
//! `b × b` blocks, so 8·b rows of pixels in block pass `b`), each band tile by tile of 8 × 8
//! traced pixels whose eye rays are traced together ([`crate::bvh::packet`]). They report their
//! progress and statistics ([`PassStats`], [`RenderStats`]) as they go, stop at the next
//! band when cancelled from another thread, and wait before the next band, without using the
//! CPU, while paused. Each band marks its rows of the film as changed ([`Film::touch_rows`]).

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::{Duration, Instant};

use arrayvec::ArrayVec;
use rayon::prelude::*;

use crate::bvh::packet::PACKET_SIZE;
use crate::camera::PIXEL_CENTRE;
use crate::color::Color;
use crate::film::Film;
use crate::ray::Ray;
use crate::sampling::jitter;
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
}

/// The passes of a render starting at `block_size` (a power of two) with `samples` per pixel.
pub fn passes(block_size: u32, samples: u32) -> Vec<Pass> {
    let blocks = std::iter::successors(Some(block_size.max(1)), |&b| (b > 1).then_some(b / 2));
    blocks
        .map(Pass::Block)
        .chain((1..samples).map(Pass::Sample))
        .collect()
}

/// What one pass of progressive rendering did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassStats {
    pub pass: Pass,
    /// Pixels traced (not painted) in this pass.
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
    /// Block size of the running pass (1 for sample passes).
    pub block_size: u32,
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
    mut on_pass: impl FnMut(&PassStats),
) -> Result<RenderStats, Cancelled> {
    let settings = &tracer.scene.settings;
    let plan = passes(settings.block_size, settings.samples);
    control.passes.store(plan.len() as u32, Ordering::Relaxed);
    let start = Instant::now();
    let mut stats = RenderStats::default();
    for (i, &pass) in plan.iter().enumerate() {
        control.pass.store(i as u32, Ordering::Relaxed);
        let pass_stats = render_pass(tracer, shader, film, control, pass, settings.block_size)?;
        stats.rays += pass_stats.rays;
        stats.passes.push(pass_stats);
        on_pass(&pass_stats);
    }
    stats.time = start.elapsed();
    control.finished.store(true, Ordering::Relaxed);
    Ok(stats)
}

/// Runs one pass over the whole image.
pub fn render_pass(
    tracer: &Tracer,
    shader: &dyn Shader,
    film: &Film,
    control: &RenderControl,
    pass: Pass,
    start_block: u32,
) -> Result<PassStats, Cancelled> {
    let started = Instant::now();
    let (width, height) = (film.width(), film.height());
    let step = match pass {
        Pass::Block(b) => b,
        Pass::Sample(_) => 1,
    };
    let rows = height.div_ceil(step);
    control.block_size.store(step, Ordering::Relaxed);
    control.rows.store(rows, Ordering::Relaxed);
    control.rows_done.store(0, Ordering::Relaxed);
    let rays_before = control.rays.get();
    let pixels_before = control.pixels.load(Ordering::Relaxed);
    let grid = PassGrid {
        pass,
        start_block,
        step,
        width,
        height,
    };
    let columns = width.div_ceil(step);
    // Bands of TILE rows of the grid go to the threads; each band is traced tile by tile.
    (0..rows.div_ceil(TILE))
        .into_par_iter()
        .try_for_each(|band| {
            control.wait_while_paused();
            if control.is_cancelled() {
                return Err(Cancelled);
            }
            let band_rows = band * TILE..((band + 1) * TILE).min(rows);
            let mut counts = RayCounts::default();
            let pixels: u64 = (0..columns)
                .step_by(TILE as usize)
                .map(|c| {
                    let tile_columns = c..(c + TILE).min(columns);
                    trace_tile(
                        tracer,
                        shader,
                        film,
                        &grid,
                        &band_rows,
                        tile_columns,
                        &mut counts,
                    )
                })
                .sum();
            control.rays.add(&counts);
            control.pixels.fetch_add(pixels, Ordering::Relaxed);
            control
                .rows_done
                .fetch_add(band_rows.len() as u32, Ordering::Relaxed);
            film.touch_rows(band_rows.start * step..band_rows.end * step);
            Ok(())
        })?;
    let rays = control.rays.get() - rays_before;
    Ok(PassStats {
        pass,
        pixels: control.pixels.load(Ordering::Relaxed) - pixels_before,
        rays,
        time: started.elapsed(),
    })
}

/// The pixels of one pass: a grid of `step`-pixel blocks over the film, of which the pass traces
/// the top-left pixel of each block it has not traced before (or adds a sample to every pixel).
struct PassGrid {
    pass: Pass,
    start_block: u32,
    step: u32,
    width: u32,
    height: u32,
}

impl PassGrid {
    /// The samples the pass takes in `rows` × `columns` of its grid: the pixel (x, y), the offset
    /// of the sample in it, and the sample's number (0 for the pixel's centre).
    fn samples(
        &self,
        rows: &Range<u32>,
        columns: Range<u32>,
    ) -> impl Iterator<Item = (u32, u32, (f32, f32), u32)> {
        let step = self.step;
        rows.clone()
            .flat_map(move |row| {
                columns
                    .clone()
                    .map(move |column| (column * step, row * step))
            })
            .filter_map(|(x, y)| match self.pass {
                Pass::Block(b) if traces_pixel(b, self.start_block, x, y) => {
                    Some((x, y, PIXEL_CENTRE, 0))
                }
                Pass::Block(_) => None,
                Pass::Sample(k) => Some((x, y, jitter(x, y, k), k)),
            })
    }
}

/// Traces the samples of one tile of `grid` (at most [`PACKET_SIZE`]), the eye rays as one
/// packet, and writes them to the film: a block painted, or a sample added to the pixel's mean.
/// Returns how many it traced.
fn trace_tile(
    tracer: &Tracer,
    shader: &dyn Shader,
    film: &Film,
    grid: &PassGrid,
    rows: &Range<u32>,
    columns: Range<u32>,
    counts: &mut RayCounts,
) -> u64 {
    let camera = &tracer.scene.camera;
    let (width, height) = (grid.width, grid.height);
    let mut samples: ArrayVec<(u32, u32, u32), PACKET_SIZE> = ArrayVec::new();
    let mut rays: ArrayVec<Ray, PACKET_SIZE> = ArrayVec::new();
    for (x, y, offset, sample) in grid.samples(rows, columns) {
        rays.push(camera.eye_ray((x, y), offset, (width, height)));
        samples.push((x, y, sample));
    }
    let mut colors = [Color::ZERO; PACKET_SIZE];
    let colors = &mut colors[..rays.len()];
    shader.shade(tracer, &rays, colors, counts);
    for (&(x, y, sample), &color) in samples.iter().zip(colors.iter()) {
        if sample == 0 {
            film.fill_block(x, y, grid.step, color);
        } else {
            let mean = film.get(x, y);
            film.set(x, y, mean + (color - mean) / (sample + 1) as f32);
        }
    }
    rays.len() as u64
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
