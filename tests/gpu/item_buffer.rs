//! The item buffer (the lecture's modified Z-buffer) against the rays, on every shipped scene
//! and the SPD scenes at 160 × 120: the raster pass names the rays' first hits but within one
//! pixel of a silhouette, and the CPU tracer fed by it makes the rays' image bit for bit, with
//! anti-aliasing off and on. These tests need a GPU adapter: without one they fail, saying what
//! to install (Mesa's lavapipe will do).

use std::sync::Arc;

use crate::gpu;
use raylab::camera::PIXEL_CENTRE;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::item_raster::CpuItems;
use raylab::item_buffer::ItemBuffer;
use raylab::primitive::Hit;
use raylab::progressive::render_image;
use raylab::render::{Assembled, assemble};
use raylab::whitted::EYE_RAY_T_MIN;

const SIZE: (u32, u32) = (160, 120);

/// The item buffer of `assembled`'s whole image.
fn item_buffer(gpu: &Arc<GpuDevice>, assembled: &Assembled) -> ItemBuffer {
    let scene = &assembled.scene;
    let raster = CpuItems::new(Arc::clone(gpu), assembled).unwrap();
    let size = (scene.settings.width, scene.settings.height);
    raster.draw(scene, ((0, 0), size)).unwrap()
}

/// Every shipped scene and SPD scene at [`SIZE`], assembled.
fn scenes() -> Vec<(String, Assembled)> {
    crate::common::shipped_and_spd_scenes()
        .into_iter()
        .map(|(name, mut scene)| {
            (scene.settings.width, scene.settings.height) = SIZE;
            (name, assemble(scene).unwrap())
        })
        .collect()
}

/// The id the object view shows for each pixel's first hit as the rays find it in the BVH
/// (`None`: the ray misses), row by row. The raster pass knows nothing of textures, so the hit
/// is the first surface, cut away by its texture's alpha or not, as the BVH's search finds it.
fn ray_ids(assembled: &Assembled) -> Vec<Option<u32>> {
    let (bvh, scene) = (&assembled.bvh, &assembled.scene);
    let (width, height) = SIZE;
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|pixel| {
            let ray = scene.camera.eye_ray(pixel, PIXEL_CENTRE, SIZE);
            let hit = bvh.closest_hit(&scene.geometry, &ray, EYE_RAY_T_MIN, f32::INFINITY)?;
            Some(scene.geometry.part_id(&hit))
        })
        .collect()
}

/// Whether pixel `i` of `ids` lies within one pixel of a silhouette: a neighbour (of eight)
/// shows another id.
fn at_silhouette(ids: &[Option<u32>], i: usize) -> bool {
    let (width, height) = (SIZE.0 as i64, SIZE.1 as i64);
    let (x, y) = (i as i64 % width, i as i64 / width);
    (-1..=1).any(|dy| {
        (-1..=1).any(|dx| {
            let (nx, ny) = (x + dx, y + dy);
            (0..width).contains(&nx)
                && (0..height).contains(&ny)
                && ids[(ny * width + nx) as usize] != ids[i]
        })
    })
}

/// At most this share of the pixels at silhouettes may name another first hit than the rays.
const SILHOUETTE_SHARE: f64 = 0.05;

#[test]
fn the_item_buffer_names_the_rays_first_hits_but_within_a_pixel_of_a_silhouette() {
    let gpu = gpu();
    let mut failures = Vec::new();
    for (name, assembled) in scenes() {
        let buffer = item_buffer(&gpu, &assembled);
        let geometry = &assembled.scene.geometry;
        let raster_ids: Vec<Option<u32>> = buffer
            .items()
            .iter()
            .map(|item| {
                item.map(|item| {
                    let hit = Hit {
                        t: item.t,
                        prim: item.prim,
                        part: item.part,
                        bary: Default::default(),
                    };
                    geometry.part_id(&hit)
                })
            })
            .collect();
        let rays = ray_ids(&assembled);
        let silhouette = (0..rays.len()).filter(|&i| at_silhouette(&rays, i)).count();
        let differ: Vec<usize> = (0..rays.len())
            .filter(|&i| raster_ids[i] != rays[i])
            .collect();
        let inside: Vec<usize> = differ
            .iter()
            .copied()
            .filter(|&i| !at_silhouette(&rays, i))
            .collect();
        let share = differ.len() as f64 / silhouette.max(1) as f64;
        eprintln!(
            "{name}: {} of {} pixels differ, all within a pixel of the {silhouette} at silhouettes \
             but {} ({:.2} %)",
            differ.len(),
            rays.len(),
            inside.len(),
            share * 100.0
        );
        if !inside.is_empty() || share > SILHOUETTE_SHARE {
            let first = inside.first().or(differ.first()).copied().unwrap_or(0);
            failures.push(format!(
                "{name}: {} pixels differ away from silhouettes, {} in all ({:.2} % of the \
                 silhouettes' pixels); e.g. pixel ({}, {}): raster {:?}, rays {:?}",
                inside.len(),
                differ.len(),
                share * 100.0,
                first % SIZE.0 as usize,
                first / SIZE.0 as usize,
                raster_ids[first],
                rays[first]
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Renders every scene, `adjust`ed, with first hits from the rays and from the item buffer, and
/// checks that the images are the same bit for bit and that at least `used` of the eye rays
/// that hit something found their first hit within their pixel's item.
fn raster_first_hits_match_the_rays(used: f64, adjust: impl Fn(&mut Assembled)) {
    let gpu = gpu();
    let mut failures = Vec::new();
    for (name, mut assembled) in scenes() {
        adjust(&mut assembled);
        let buffer = item_buffer(&gpu, &assembled);
        let (rays, _) = render_image(&assembled.tracer());
        let tracer = assembled.tracer().with_item_buffer(Some(&buffer));
        let (from_items, stats) = render_image(&tracer);
        let differ = rays
            .iter()
            .zip(&from_items)
            .filter(|(a, b)| a.to_array().map(f32::to_bits) != b.to_array().map(f32::to_bits))
            .count();
        let r = &stats.rays;
        eprintln!(
            "{name}: {differ} pixels differ; {} of {} eye rays from the item buffer ({} hit)",
            r.from_item_buffer, r.primary, r.primary_hits
        );
        if differ > 0 {
            failures.push(format!("{name}: {differ} pixels differ"));
        }
        if (r.from_item_buffer as f64) < used * r.primary_hits as f64 {
            failures.push(format!(
                "{name}: only {} of {} eye rays that hit came from the item buffer",
                r.from_item_buffer, r.primary_hits
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn raster_first_hits_give_the_rays_image_bit_for_bit() {
    // Every pixel's one eye ray passes through its centre, where the raster pass looked.
    raster_first_hits_match_the_rays(0.99, |assembled| {
        assembled.scene.settings.samples = 1;
    });
}

#[test]
fn raster_first_hits_give_the_rays_image_bit_for_bit_with_anti_aliasing() {
    // The jittered samples lie at the pixels along edges, where their own ray often misses
    // their pixel's item.
    raster_first_hits_match_the_rays(0.5, |assembled| {
        let settings = &mut assembled.scene.settings;
        (settings.samples, settings.aa_threshold) = (8, 0.03);
    });
}
