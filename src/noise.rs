//! Noise for solid textures (Perlin's idea, as Hill & Kelley's chapter 8 builds it): random
//! values fixed at the points of the integer lattice, blended smoothly in between, and
//! turbulence, the sum of noise at doubling frequencies. Carved out of space like the solid
//! checkerboard, so a marble object looks cut from one block.

use glam::Vec3;

use crate::sampling::hash;

/// The random value in [0, 1) fixed at lattice point (i, j, k).
fn lattice(i: i32, j: i32, k: i32) -> f32 {
    let h = hash(i as u32 ^ hash(j as u32 ^ hash(k as u32)));
    (h >> 8) as f32 / (1u32 << 24) as f32
}

/// Noise at `p`, in [0, 1): the values at the eight corners of p's lattice cell, blended with
/// smoothstep weights, so it is smooth across cell faces.
pub fn noise(p: Vec3) -> f32 {
    let cell = p.floor();
    let f = p - cell;
    let w = f * f * (3.0 - 2.0 * f);
    let (i, j, k) = (cell.x as i32, cell.y as i32, cell.z as i32);
    let mut sum = 0.0;
    for corner in 0..8 {
        let (di, dj, dk) = (corner & 1, (corner >> 1) & 1, corner >> 2);
        let along = |d: i32, w: f32| if d == 1 { w } else { 1.0 - w };
        let weight = along(di, w.x) * along(dj, w.y) * along(dk, w.z);
        sum += weight * lattice(i + di, j + dj, k + dk);
    }
    sum
}

/// Turbulence at `p`: noise at frequency `scale`, twice it and four times it, each octave half
/// as strong as the one before (½, ¼, ⅛), in [0, ⅞).
pub fn turbulence(scale: f32, p: Vec3) -> f32 {
    0.5 * noise(scale * p) + 0.25 * noise(2.0 * scale * p) + 0.125 * noise(4.0 * scale * p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_takes_the_lattice_values_at_lattice_points() {
        for (i, j, k) in [(0, 0, 0), (3, -2, 7), (-5, -5, -5)] {
            let p = Vec3::new(i as f32, j as f32, k as f32);
            assert_eq!(noise(p), lattice(i, j, k));
        }
    }

    #[test]
    fn noise_is_smooth_and_bounded_but_not_constant() {
        let mut values = Vec::new();
        for n in 0..2000 {
            let p = Vec3::new(n as f32 * 0.0137, n as f32 * 0.0071 - 3.0, 1.5);
            let a = noise(p);
            let b = noise(p + Vec3::splat(1e-3));
            assert!((0.0..1.0).contains(&a), "{a} at {p}");
            // The blend's slope is at most 1.5 per unit per axis.
            assert!((a - b).abs() < 5e-3, "{a} {b} at {p}");
            values.push(a);
        }
        let (lo, hi) = values
            .iter()
            .fold((1.0f32, 0.0f32), |(lo, hi), &v| (lo.min(v), hi.max(v)));
        assert!(hi - lo > 0.5, "noise spans only {lo}..{hi}");
    }

    #[test]
    fn turbulence_stays_below_seven_eighths() {
        for n in 0..500 {
            let p = Vec3::new(n as f32 * 0.37, -(n as f32) * 0.11, n as f32 * 0.05);
            let t = turbulence(5.0, p);
            assert!((0.0..0.875).contains(&t), "{t}");
        }
    }
}
