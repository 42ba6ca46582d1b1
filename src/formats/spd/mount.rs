//! mount: a fractal mountain (Carpenter's midpoint displacement on a square grid, 2·4^SF
//! triangles) with a pyramid of four glass spheres (T 0.9, IOR 1.5) in front of it, lit by one
//! light. It keeps SPD's original hash for the random displacements, repetitive as it is,
//! because the published statistics were made with it.

use std::f64::consts::TAU;

use glam::{DMat3, DVec3};

use super::conventions::{Surface, axis_rotation, document};
use crate::formats::nff::{Item, NffDocument};

/// Fractal dimension of the surface, between 2 and 3: how rough it is.
const FRACTAL_DIMENSION: f64 = 2.2;
/// Which mountain: an offset to every random seed.
const MOUNTAIN_NO: u64 = 21;
/// The mountain covers the square from (−1, −1) to (1, 1).
const CORNER: f64 = -1.0;
const WIDTH: f64 = 2.0;
/// How much more a square's middle may rise than its edges' midpoints: SPD's √2, written with
/// eight digits (the exact constant would change the mountain's last digits).
#[allow(clippy::approx_constant)]
const MIDDLE_RISE: f64 = 1.4142136;

pub(super) fn mount(size: u32) -> NffDocument {
    let mut doc = document(
        [-1.6, 1.6, 1.7],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        0.01,
        &[[-100.0, -100.0, 100.0]],
    );
    let glass = Surface {
        color: [1.0, 1.0, 1.0],
        kd: 0.1,
        ks: 0.1,
        highlight_half_angle: 6.7,
        transmittance: 0.9,
        ior: 1.5,
    };
    doc.items.push(glass.fill());
    spheres(&mut doc.items, DVec3::new(-0.8, 0.8, 1.0), 0.17);
    doc.items
        .push(Surface::matte([0.5, 0.45, 0.35], 1.0).fill());
    let ratio = 2.0 / (2f64.ln() / (FRACTAL_DIMENSION - 1.0)).exp();
    let mountain = Mountain {
        size,
        cells: 1u64 << size,
        roughness: (ratio * ratio - 1.0).sqrt(),
    };
    mountain.grow(&mut doc.items, mountain.cells, [0, 0], [0.0; 4]);
    doc
}

/// Four touching spheres of `radius`: three around `base`, one on top.
fn spheres(items: &mut Vec<Item>, base: DVec3, radius: f64) {
    let top = DVec3::new(0.0, 0.0, radius * 1.5f64.sqrt());
    items.push(Item::Sphere {
        center: base + top,
        radius,
    });
    let tilted = axis_rotation(DVec3::new(1.0, 1.0, 0.0), (-1.0f64 / 3.0).acos()) * top;
    for i in 0..3 {
        let center = base + DMat3::from_rotation_z(f64::from(i) * TAU / 3.0) * tilted;
        items.push(Item::Sphere { center, radius });
    }
}

struct Mountain {
    size: u32,
    /// Grid cells along a side: 2^size.
    cells: u64,
    /// How much a midpoint may rise relative to the length of its square's side.
    roughness: f64,
}

impl Mountain {
    /// The square of `width` cells with lower left corner `corner` (in cells), its corners at
    /// heights `z` (lower left, lower right, upper right, upper left): split into four until the
    /// squares are one cell wide, then written as two triangles each.
    fn grow(&self, items: &mut Vec<Item>, width: u64, corner: [u64; 2], z: [f64; 4]) {
        let [x, y] = corner;
        let [ll, lr, ur, ul] = z;
        if width == 1 {
            let at = |cx: u64, cy: u64, z: f64| {
                let scale = WIDTH / self.cells as f64;
                DVec3::new(CORNER + cx as f64 * scale, CORNER + cy as f64 * scale, z)
            };
            let square = [
                at(x, y, ll),
                at(x + 1, y, lr),
                at(x + 1, y + 1, ur),
                at(x, y + 1, ul),
            ];
            items.push(Item::Polygon(vec![square[0], square[1], square[2]]));
            items.push(Item::Polygon(vec![square[2], square[3], square[0]]));
            return;
        }
        let half = width / 2;
        let rise = half as f64 * WIDTH / self.cells as f64 * self.roughness;
        let displace = |cx: u64, cy: u64| rise * gauss_rand(MOUNTAIN_NO + hash(cx, cy, self.size));
        let lower = (ll + lr) / 2.0 + displace(x + half, y);
        let right = (lr + ur) / 2.0 + displace(x + width, y + half);
        let upper = (ur + ul) / 2.0 + displace(x + half, y + width);
        let left = (ul + ll) / 2.0 + displace(x, y + half);
        let middle = (ll + lr + ur + ul) / 4.0 + MIDDLE_RISE * displace(x + half, y + half);
        self.grow(items, half, [x, y], [ll, lower, middle, left]);
        self.grow(items, half, [x + half, y], [lower, lr, right, middle]);
        self.grow(
            items,
            half,
            [x + half, y + half],
            [middle, right, ur, upper],
        );
        self.grow(items, half, [x, y + half], [left, middle, upper, ul]);
    }
}

/// SPD's original seed for the grid point (a, b) at size factor c. Past size 7 its shifts go
/// negative; they are taken modulo 64, as an x86-64 build of the original does.
fn hash(a: u64, b: u64, c: u32) -> u64 {
    let shl = |v: u64, by: i64| v.wrapping_shl(by.rem_euclid(64) as u32);
    let c = i64::from(c);
    (shl(a, 23 - c)
        .wrapping_add(shl(b, 15 - c))
        .wrapping_add(shl(a, 7 - c)))
        & 0xffff
}

/// SPD's portable Gaussian random number for a seed: a normal deviate by the polar method,
/// from a small linear congruential generator (after Numerical Recipes' GASDEV).
fn gauss_rand(seed: u64) -> f64 {
    const M: u64 = 134_456;
    const A: u64 = 8121;
    const C: u64 = 28_411;
    let mut ix2 = seed;
    loop {
        let ix1 = (C + ix2 * A) % M;
        ix2 = (C + ix1 * A) % M;
        let v1 = ix1 as f64 * 2.0 / M as f64 - 1.0;
        let v2 = ix2 as f64 * 2.0 / M as f64 - 1.0;
        let r = v1 * v1 + v2 * v2;
        if r < 1.0 && r > 0.0 {
            return v1 * (-2.0 * r.ln() / r).sqrt();
        }
    }
}
