//! gears: SF³ meshed gears in a cube, each two concave 144-vertex faces joined by 144 quads,
//! on a reflective floor, lit by five lights. Every fifth gear or so is transparent (T 0.8,
//! IOR 1.1); the big concave faces test the polygon inside-outside test.

use std::f64::consts::{PI, TAU};

use glam::{DMat3, DVec3};

use super::conventions::{Surface, document};
use crate::formats::nff::{Item, NffDocument};

const TEETH: usize = 36;
/// Outer radius of the teeth relative to the gear's full radius: a little short, so meshing
/// gears never touch.
const OUTER_EDGE_RATIO: f64 = 0.995;
/// Radius of the tooth roots relative to the gear's full radius.
const INNER_EDGE_RATIO: f64 = 0.9;
const EDGE_DIFF: f64 = 1.0 - INNER_EDGE_RATIO;
/// Greatest thickness of a gear.
const DEPTH_RATIO: f64 = 0.1;

pub(super) fn gears(size: u32) -> NffDocument {
    let mut doc = document(
        [-1.1, -2.1, 2.6],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        1.0,
        &[
            [2.0, 4.0, 4.0],
            [-2.0, 4.0, 3.0],
            [2.0, -2.5, 2.5],
            [-1.0, -4.0, 2.0],
            // Just behind the eye.
            [-1.111, -2.121, 2.626],
        ],
    );
    let floor = Surface {
        color: [1.0, 0.85, 0.7],
        kd: 0.3,
        ks: 0.6,
        highlight_half_angle: 37.0,
        transmittance: 0.0,
        ior: 0.0,
    };
    doc.items.push(floor.fill());
    doc.items.push(Item::Polygon(vec![
        DVec3::new(2.0, 2.0, 0.0),
        DVec3::new(-2.0, 2.0, 0.0),
        DVec3::new(-2.0, -2.0, 0.0),
        DVec3::new(2.0, -2.0, 0.0),
    ]));

    let n = f64::from(size);
    let radius = 1.0 / (n - (n - 1.0) * EDGE_DIFF / 2.0);
    let first = DVec3::new(-1.0 + radius, -1.0 + radius, 1.0);
    let step = DVec3::new(
        radius * (2.0 - EDGE_DIFF),
        radius * (2.0 - EDGE_DIFF),
        -1.0 / n,
    );
    let thickness = DEPTH_RATIO.min(1.0 / (2.0 * n));
    for iz in 0..size {
        for iy in 0..size {
            for ix in 0..size {
                let center = first + DVec3::new(ix as f64, iy as f64, iz as f64) * step;
                doc.items.push(gear_surface(ix, iy, iz).fill());
                // Neighbours are turned half a tooth against each other so that they mesh.
                let turn = PI * f64::from((ix + iy + iz) % 2) / TEETH as f64;
                gear(
                    &mut doc.items,
                    center,
                    turn,
                    OUTER_EDGE_RATIO * radius,
                    INNER_EDGE_RATIO * radius,
                    thickness,
                );
            }
        }
    }
    doc
}

/// A pseudo-random colour, brightest channel 1; gears with (4x + 2y + z) divisible by 5 are
/// transparent.
fn gear_surface(ix: u32, iy: u32, iz: u32) -> Surface {
    let channel = |k: u32, ratio: f64| 0.01 + (f64::from(k) * ratio).fract();
    let color = DVec3::new(
        channel(ix * 3 + iy * 2 + iz + 1, 5.0 / 7.0),
        channel(iy * 3 + iz * 2 + ix + 1, 3.0 / 7.0),
        channel(iz * 3 + ix * 2 + iy + 1, 2.0 / 7.0),
    );
    let color = (color / color.max_element()).to_array();
    if (ix * 4 + iy * 2 + iz).is_multiple_of(5) {
        Surface {
            color,
            kd: 0.2,
            ks: 0.0,
            highlight_half_angle: 0.0,
            transmittance: 0.8,
            ior: 1.1,
        }
    } else {
        Surface::matte(color, 1.0)
    }
}

/// One gear: its top face (at `center`), the sides of its teeth, its bottom face.
fn gear(items: &mut Vec<Item>, center: DVec3, turn: f64, outer: f64, inner: f64, thickness: f64) {
    let tooth_angle = TAU / TEETH as f64;
    let outline = |depth: f64, direction: f64| -> Vec<DVec3> {
        (0..TEETH)
            .flat_map(|t| {
                let angle = turn + direction * TAU * t as f64 / TEETH as f64;
                let tooth = direction * tooth_angle;
                [
                    (angle - 0.19 * tooth, outer),
                    (angle + 0.19 * tooth, outer),
                    (angle + 0.3 * tooth, inner),
                    (angle + 0.7 * tooth, inner),
                ]
            })
            .map(|(angle, r)| center + DMat3::from_rotation_z(angle) * DVec3::new(r, 0.0, -depth))
            .collect()
    };
    // The top runs counter-clockwise seen from above, the bottom clockwise: both face out.
    let top = outline(0.0, 1.0);
    let down = DVec3::new(0.0, 0.0, thickness);
    let sides: Vec<Item> = (0..top.len())
        .map(|i| {
            let (a, b) = (top[i], top[(i + 1) % top.len()]);
            Item::Polygon(vec![a, a - down, b - down, b])
        })
        .collect();
    items.push(Item::Polygon(top));
    items.extend(sides);
    items.push(Item::Polygon(outline(thickness, -1.0)));
}
