//! The CPU sweep of a progressive render: each pass on all of rayon's threads, band by band of
//! 8 rows of the pass's grid (8 rows of `b × b` blocks, so 8·b rows of pixels in block pass `b`),
//! each band tile by tile of 8 × 8 pixels whose eye rays are traced together, up to 64 at a time
//! ([`crate::bvh::packet`]). A band reports its progress and statistics to the render's
//! [`RenderControl`] as it goes, stops when cancelled from another thread, waits before it starts
//! while paused, and marks its rows of the film as changed ([`Film::touch_rows`]). Each pixel
//! sample is what the caller's [`SampleColoring`] makes of its eye ray.

use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};

use arrayvec::ArrayVec;
use rayon::prelude::*;

use super::coloring::{SampleColoring, Shaded};
use super::control::{Cancelled, PassStats, RenderControl, RenderStats, run_plan};
use super::pass::PassStart;
use super::plan::{Pass, PassGrid, passes, sample_ray, unwatched_passes};
use crate::bvh::packet::PACKET_SIZE;
use crate::color::Color;
use crate::film::Film;
use crate::item_buffer::Item;
use crate::ray::Ray;
use crate::stats::RayCounts;
use crate::whitted::Tracer;

/// Traced pixels per side of a tile: a tile's eye rays go through the BVH as one packet of
/// [`PACKET_SIZE`].
const TILE: u32 = 8;
const _: () = assert!((TILE * TILE) as usize == PACKET_SIZE);

/// Renders `tracer`'s scene as `coloring` shows it into `film` (which must have the settings'
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
    coloring: &dyn SampleColoring,
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
    run_passes(tracer, coloring, film, control, &plan, on_pass)
}

/// [`render`] for a film nobody looks at before it is finished (a render to a file): the
/// [`unwatched_passes`], the same film in the end.
pub fn render_unwatched(
    tracer: &Tracer,
    coloring: &dyn SampleColoring,
    film: &Film,
    control: &RenderControl,
) -> Result<RenderStats, Cancelled> {
    let settings = &tracer.scene.settings;
    let plan = unwatched_passes(settings.samples, settings.aa_threshold > 0.0);
    run_passes(tracer, coloring, film, control, &plan, |_| {})
}

/// Runs the passes of `plan` one after another, the block passes starting from the settings'
/// block size, calling `on_pass` after each.
fn run_passes(
    tracer: &Tracer,
    coloring: &dyn SampleColoring,
    film: &Film,
    control: &RenderControl,
    plan: &[Pass],
    on_pass: impl FnMut(&PassStats),
) -> Result<RenderStats, Cancelled> {
    let start_block = tracer.scene.settings.block_size;
    let mut shown = Vec::new();
    run_plan(plan, control, on_pass, |pass| {
        run_pass(
            tracer,
            coloring,
            film,
            control,
            pass,
            start_block,
            &mut shown,
        )
    })
}

/// Runs one pass over the whole image (an anti-aliasing round compares the pixels as the film
/// has them now).
pub fn render_pass(
    tracer: &Tracer,
    coloring: &dyn SampleColoring,
    film: &Film,
    control: &RenderControl,
    pass: Pass,
    start_block: u32,
) -> Result<PassStats, Cancelled> {
    run_pass(
        tracer,
        coloring,
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
    coloring: &dyn SampleColoring,
    film: &Film,
    control: &RenderControl,
    pass: Pass,
    start_block: u32,
    shown: &mut Vec<[u8; 3]>,
) -> Result<PassStats, Cancelled> {
    let threshold = tracer.scene.settings.aa_threshold;
    let start = PassStart::new(pass, film, shown, (start_block, threshold), control);
    let (grid, rows, columns, step) = (&start.grid, start.rows, start.columns, pass.step());
    let pixels = AtomicU64::new(0);
    // Bands of TILE rows of the grid go to the threads; each band is traced tile by tile. Each
    // band is a job of its own that an idle thread can take: left to itself, rayon would hand a
    // thread runs of up to a quarter of the bands, and the other would wait at the end of the
    // pass for the rest of the run it cannot take.
    (0..rows.div_ceil(TILE))
        .into_par_iter()
        .with_max_len(1)
        .try_for_each(|band| {
            control.wait_for_band()?;
            let band_rows = band * TILE..((band + 1) * TILE).min(rows);
            let mut counts = RayCounts::default();
            let mut traced = Traced::default();
            for c in (0..columns).step_by(TILE as usize) {
                let tile_columns = c..(c + TILE).min(columns);
                let tile = trace_tile(
                    tracer,
                    coloring,
                    grid,
                    &band_rows,
                    tile_columns,
                    &mut counts,
                );
                traced.pixels += tile.pixels;
                traced.samples += tile.samples;
            }
            control.band_done(band_rows.len() as u32, traced.samples, &counts);
            pixels.fetch_add(traced.pixels, Ordering::Relaxed);
            film.touch_rows(band_rows.start * step..band_rows.end * step);
            Ok(())
        })?;
    Ok(start.finish(control, pixels.into_inner()))
}

/// What a tile (or a band) traced.
#[derive(Clone, Copy, Debug, Default)]
struct Traced {
    /// Pixels that took samples.
    pixels: u64,
    samples: u64,
}

/// Up to [`PACKET_SIZE`] pixel samples whose eye rays are traced together: the pixel, the
/// sample's number and its item for each ray.
#[derive(Default)]
struct Packet {
    samples: ArrayVec<(u32, u32, u32), PACKET_SIZE>,
    rays: ArrayVec<Ray, PACKET_SIZE>,
    items: ArrayVec<Option<Item>, PACKET_SIZE>,
}

impl Packet {
    /// Traces the packet's rays and writes their colours to the film: a block painted for a
    /// pixel's first sample, otherwise a sample added to the pixel's mean. Empties the packet.
    fn trace(
        &mut self,
        tracer: &Tracer,
        coloring: &dyn SampleColoring,
        grid: &PassGrid,
        counts: &mut RayCounts,
    ) {
        let mut colors = [Color::ZERO; PACKET_SIZE];
        let colors = &mut colors[..self.rays.len()];
        coloring.shade(tracer, &self.rays, &self.items, colors, counts);
        for (&(x, y, sample), &color) in self.samples.iter().zip(colors.iter()) {
            if sample == 0 {
                grid.film.fill_block(x, y, grid.step, color);
            } else {
                grid.film.add_sample(x, y, color);
            }
        }
        self.samples.clear();
        self.rays.clear();
        self.items.clear();
    }
}

/// Traces the samples the pass takes in one tile of `grid` (`rows` × `columns` of it), the eye
/// rays in packets of up to [`PACKET_SIZE`], and writes them to the film.
fn trace_tile(
    tracer: &Tracer,
    coloring: &dyn SampleColoring,
    grid: &PassGrid,
    rows: &Range<u32>,
    columns: Range<u32>,
    counts: &mut RayCounts,
) -> Traced {
    let camera = &tracer.scene.camera;
    // The film may be a window of the image: rays and jitter go by the pixel's place in it.
    let size = grid.film.image_size();
    let (left, top) = grid.film.origin();
    let film_size = (grid.film.width(), grid.film.height());
    let item_buffer = tracer
        .item_buffer
        .filter(|buffer| buffer.fits(size, (left, top), film_size));
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
                    packet.trace(tracer, coloring, grid, counts);
                }
                packet.rays.push(sample_ray(camera, grid.film, (x, y), k));
                packet.samples.push((x, y, k));
                packet
                    .items
                    .push(item_buffer.and_then(|buffer| buffer.at(x, y)));
            }
        }
    }
    if !packet.rays.is_empty() {
        packet.trace(tracer, coloring, grid, counts);
    }
    traced
}

/// Renders the whole shaded image in one go (no progressive display), returning its pixels.
pub fn render_image(tracer: &Tracer) -> (Vec<Color>, RenderStats) {
    render_image_with(tracer, &Shaded)
}

/// [`render_image`] of what `coloring` shows.
pub fn render_image_with(
    tracer: &Tracer,
    coloring: &dyn SampleColoring,
) -> (Vec<Color>, RenderStats) {
    let (film, stats) = render_film_with(tracer, coloring);
    (film.pixels(), stats)
}

/// [`render_image`] into a film, which is returned: no copy of its pixels is made.
pub fn render_film(tracer: &Tracer) -> (Film, RenderStats) {
    render_film_with(tracer, &Shaded)
}

fn render_film_with(tracer: &Tracer, coloring: &dyn SampleColoring) -> (Film, RenderStats) {
    let settings = &tracer.scene.settings;
    let film = Film::new(settings.width, settings.height);
    let control = RenderControl::default();
    let stats = render(tracer, coloring, &film, &control, |_| {}).unwrap_or_else(|Cancelled| {
        unreachable!("nobody else holds this render's control, so it cannot be cancelled")
    });
    (film, stats)
}
