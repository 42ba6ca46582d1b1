//! What `raylab bench --first-hit raster` measures of the eye rays' first hits, besides the
//! render: the item buffer's raster pass with its read-back, and the first hits of every pixel
//! centre found with and without the item buffer: BVH nodes visited per eye ray (each ray walked
//! alone) and the time of the whole image's first hits (8 × 8 packets, as the renderer finds
//! them, on all threads).

use std::time::{Duration, Instant};

use arrayvec::ArrayVec;
use raylab::bvh::cost::BvhCost;
use raylab::bvh::packet::PACKET_SIZE;
use raylab::camera::PIXEL_CENTRE;
use raylab::item_buffer::{Item, ItemBuffer, far_limit};
use raylab::ray::Ray;
use raylab::stats::RayCounts;
use raylab::whitted::{EYE_RAY_T_MIN, Tracer};
use rayon::prelude::*;

use super::median;

/// The eye rays' first hits with the rays alone and with the item buffer (times are medians
/// over the repeats).
pub struct FirstHitBench {
    /// The raster pass and its read-back.
    pub raster: Duration,
    /// Eye rays, and of them those whose first hit was found within their item.
    pub eye_rays: u64,
    pub from_item_buffer: u64,
    /// BVH nodes visited and primitives tested per eye ray: rays alone, and from the item
    /// buffer.
    pub cost_rays: (f64, f64),
    pub cost_raster: (f64, f64),
    /// Every pixel centre's first hit: rays alone, and from the item buffer.
    pub first_hits_rays: Duration,
    pub first_hits_raster: Duration,
}

/// Draws `tracer`'s item buffer with `draw` and times the first hits with and without it,
/// `repeat` times each, on the current thread pool.
pub fn bench_first_hits(
    tracer: &Tracer,
    draw: &mut (dyn FnMut() -> Result<ItemBuffer, String> + Send),
    repeat: usize,
) -> Result<FirstHitBench, String> {
    let scene = tracer.scene;
    let size = (scene.settings.width, scene.settings.height);
    let mut raster_times = Vec::new();
    let mut items = None;
    for _ in 0..repeat {
        let started = Instant::now();
        items = Some(draw()?);
        raster_times.push(started.elapsed());
    }
    let items = items.ok_or("--repeat must be at least 1")?;
    let (mut rays_times, mut raster_first_hits) = (Vec::new(), Vec::new());
    let mut counts = RayCounts::default();
    for _ in 0..repeat {
        rays_times.push(image_first_hits(tracer, None).0);
        let (time, with_items) = image_first_hits(tracer, Some(&items));
        raster_first_hits.push(time);
        counts = with_items;
    }
    let bench = FirstHitBench {
        raster: median(raster_times),
        eye_rays: u64::from(size.0) * u64::from(size.1),
        from_item_buffer: counts.from_item_buffer,
        cost_rays: cost_per_eye_ray(tracer, None),
        cost_raster: cost_per_eye_ray(tracer, Some(&items)),
        first_hits_rays: median(rays_times),
        first_hits_raster: median(raster_first_hits),
    };
    Ok(bench)
}

/// The eye ray through the centre of pixel (x, y) of `tracer`'s image.
fn eye_ray(tracer: &Tracer, x: u32, y: u32) -> Ray {
    let settings = &tracer.scene.settings;
    let size = (settings.width, settings.height);
    tracer.scene.camera.eye_ray((x, y), PIXEL_CENTRE, size)
}

/// The time to find every pixel centre's first hit, 8 × 8 pixels a packet on all threads, with
/// `items` or without, and the rays counted.
fn image_first_hits(tracer: &Tracer, items: Option<&ItemBuffer>) -> (Duration, RayCounts) {
    let settings = &tracer.scene.settings;
    let (width, height) = (settings.width, settings.height);
    let started = Instant::now();
    let counts = (0..height.div_ceil(8))
        .into_par_iter()
        .map(|band| {
            let mut counts = RayCounts::default();
            let mut hits = [None; PACKET_SIZE];
            for left in (0..width).step_by(8) {
                let pixels = (band * 8..(band * 8 + 8).min(height))
                    .flat_map(|y| (left..(left + 8).min(width)).map(move |x| (x, y)));
                let mut rays: ArrayVec<Ray, PACKET_SIZE> = ArrayVec::new();
                let mut tile_items: ArrayVec<Option<Item>, PACKET_SIZE> = ArrayVec::new();
                for (x, y) in pixels {
                    rays.push(eye_ray(tracer, x, y));
                    tile_items.push(items.and_then(|items| items.at(x, y)));
                }
                let hits = &mut hits[..rays.len()];
                tracer.first_hits(&rays, &tile_items, hits, &mut counts);
            }
            counts
        })
        .reduce(RayCounts::default, |mut a, b| {
            a += b;
            a
        });
    (started.elapsed(), counts)
}

/// BVH nodes visited and primitives tested per eye ray through the pixel centres, each walked
/// alone, as far as its item where it has one and the ray meets it (the test of the item's
/// primitive counted too).
fn cost_per_eye_ray(tracer: &Tracer, items: Option<&ItemBuffer>) -> (f64, f64) {
    let settings = &tracer.scene.settings;
    let (width, height) = (settings.width, settings.height);
    let geometry = &tracer.scene.geometry;
    let cost = (0..height)
        .into_par_iter()
        .map(|y| {
            let mut cost = BvhCost::default();
            for x in 0..width {
                let ray = eye_ray(tracer, x, y);
                let item: Option<Item> = items.and_then(|items| items.at(x, y));
                let limit = far_limit(geometry, item, &ray, EYE_RAY_T_MIN);
                cost.prims += u64::from(item.is_some());
                let bvh = tracer.bvh;
                if bvh
                    .closest_hit_counted(geometry, &ray, EYE_RAY_T_MIN, limit, &mut cost)
                    .is_none()
                    && limit.is_finite()
                {
                    bvh.closest_hit_counted(
                        geometry,
                        &ray,
                        EYE_RAY_T_MIN,
                        f32::INFINITY,
                        &mut cost,
                    );
                }
            }
            (cost.nodes, cost.prims)
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    let rays = f64::from(width) * f64::from(height);
    (cost.0 as f64 / rays, cost.1 as f64 / rays)
}
