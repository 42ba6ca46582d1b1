//! What the benchmarks share: a small deterministic random generator, and ray sets.

#![allow(dead_code)] // each benchmark uses a different part

use glam::Vec3;
use raylab::ray::Ray;
use raylab::scene::Scene;

/// A linear congruential generator: the same numbers on every machine, so every run measures
/// the same work.
pub struct Rng(pub u64);

impl Rng {
    /// A number in [0, 1).
    pub fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    pub fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * (hi - lo) + Vec3::splat(lo)
    }

    /// A direction spread evenly over the sphere.
    pub fn direction(&mut self) -> Vec3 {
        loop {
            let v = self.vec(-1.0, 1.0);
            if v.length_squared() <= 1.0 && v.length_squared() > 1e-6 {
                return v.normalize();
            }
        }
    }
}

/// The scene's eye rays through a `size × size` grid of pixel centres: coherent rays.
pub fn camera_rays(scene: &Scene, size: u32) -> Vec<Ray> {
    (0..size * size)
        .map(|i| {
            let (x, y) = (i % size, i / size);
            scene
                .camera
                .ray((size - y) as f32 - 0.5, x as f32 + 0.5, size, size)
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
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let p = lo + (hi - lo) * Vec3::new(rng.next(), rng.next(), rng.next());
            Ray::new(p, rng.direction())
        })
        .collect()
}
