//! What the benchmarks share: the tests' seeded random numbers (the same every run, so every run
//! measures the same work), and ray sets.

#![allow(dead_code)] // each benchmark uses a different part

use glam::Vec3;
use raylab::camera::PIXEL_CENTRE;
use raylab::ray::Ray;
use raylab::scene::Scene;

#[path = "../../tests/common/random.rs"]
pub mod random;

use random::{Rng, direction};

/// The scene's eye rays through a `size × size` grid of pixel centres: coherent rays.
pub fn camera_rays(scene: &Scene, size: u32) -> Vec<Ray> {
    (0..size * size)
        .map(|i| {
            let (x, y) = (i % size, i / size);
            scene.camera.eye_ray((x, y), PIXEL_CENTRE, (size, size))
        })
        .collect()
}

/// `rays` of a `size × size` grid in row order, reordered tile by tile (8 × 8 tiles, each in
/// row order): the order in which a packet tracer takes them.
pub fn in_tiles(rays: &[Ray], size: u32) -> Vec<Ray> {
    let size = size as usize;
    let mut tiled = Vec::with_capacity(rays.len());
    for tile_y in (0..size).step_by(8) {
        for tile_x in (0..size).step_by(8) {
            for y in tile_y..(tile_y + 8).min(size) {
                let row = y * size;
                tiled.extend_from_slice(&rays[row + tile_x..row + (tile_x + 8).min(size)]);
            }
        }
    }
    tiled
}

/// `n` rays from random points in the box `[lo, hi]` in random directions: incoherent rays.
pub fn random_rays(n: usize, lo: Vec3, hi: Vec3, seed: u64) -> Vec<Ray> {
    let mut rng = Rng::with_seed(seed);
    (0..n)
        .map(|_| {
            let p = lo + (hi - lo) * Vec3::new(rng.f32(), rng.f32(), rng.f32());
            Ray::new(p, direction(&mut rng))
        })
        .collect()
}
