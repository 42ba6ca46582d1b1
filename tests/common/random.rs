//! Seeded random numbers for the tests and the benchmarks (which include this file too): the
//! `fastrand` crate's generator, always made from a seed so that a run can be repeated, and the
//! points and directions drawn from it.

use glam::Vec3;

pub use fastrand::Rng;

/// A number in `[lo, hi)`.
pub fn in_range(rng: &mut Rng, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * rng.f32()
}

/// A point in the cube `[lo, hi)³`.
pub fn in_cube(rng: &mut Rng, lo: f32, hi: f32) -> Vec3 {
    Vec3::new(
        in_range(rng, lo, hi),
        in_range(rng, lo, hi),
        in_range(rng, lo, hi),
    )
}

/// A unit direction spread evenly over the sphere.
pub fn direction(rng: &mut Rng) -> Vec3 {
    loop {
        let v = in_cube(rng, -1.0, 1.0);
        if v.length_squared() <= 1.0 && v.length_squared() > 1e-6 {
            return v.normalize();
        }
    }
}
