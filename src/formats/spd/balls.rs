//! balls, the "sphereflake": a sphere with nine spheres of a third its radius around it, each
//! of those with nine more, down to the size factor's depth (Σ 9ⁿ spheres for n = 0..=SF), on
//! a square floor, lit by three lights. Almost no background; many shadow rays.

use glam::{DMat3, DVec3};

use super::conventions::{Surface, axis_rotation, document};
use crate::formats::nff::{Item, NffDocument};

/// Each child's radius relative to its parent's.
const CHILD_SCALE: f64 = 1.0 / 3.0;

pub(super) fn balls(size: u32) -> NffDocument {
    let mut doc = document(
        [2.1, 1.3, 1.7],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        0.01,
        &[[4.0, 3.0, 2.0], [1.0, -4.0, 4.0], [-3.0, 1.0, 5.0]],
    );
    let floor = Surface {
        ior: 1.0,
        ..Surface::matte([1.0, 0.75, 0.33], 0.8)
    };
    doc.items.push(floor.fill());
    let (x, y, z) = (12.0, 12.0, -0.5);
    doc.items.push(Item::Polygon(vec![
        DVec3::new(x, y, z),
        DVec3::new(-x, y, z),
        DVec3::new(-x, -y, z),
        DVec3::new(x, -y, z),
    ]));
    doc.items.push(
        Surface {
            color: [1.0, 0.9, 0.7],
            kd: 0.5,
            ks: 0.5,
            highlight_half_angle: 37.0,
            transmittance: 0.0,
            ior: 1.0,
        }
        .fill(),
    );
    let children = child_directions();
    flake(&mut doc.items, &children, size, DVec3::ZERO, 0.5, DVec3::Z);
    doc
}

/// The directions from a sphere (standing on +Z) to its nine children: three around its
/// "equator"-ish top and two rings of three below, as in SPD.
fn child_directions() -> [DVec3; 9] {
    let d = 1.0 / 2f64.sqrt();
    let tilt = axis_rotation(DVec3::new(1.0, -1.0, 0.0), (2.0 / 6f64.sqrt()).asin());
    let trio = [
        DVec3::new(d, d, 0.0),
        DVec3::new(d, 0.0, -d),
        DVec3::new(0.0, d, -d),
    ]
    .map(|v| tilt * v);
    std::array::from_fn(|i| {
        let turn = DMat3::from_rotation_z((i / 3) as f64 * std::f64::consts::TAU / 3.0);
        turn * trio[i % 3]
    })
}

/// Adds the sphere at `center` and, `depth` levels deep, its children, which grow in the
/// direction `up` (a unit vector) from it.
fn flake(
    items: &mut Vec<Item>,
    children: &[DVec3; 9],
    depth: u32,
    center: DVec3,
    radius: f64,
    up: DVec3,
) {
    items.push(Item::Sphere { center, radius });
    if depth == 0 {
        return;
    }
    // Turn the children, laid out around +Z, to stand around `up`.
    let turn = if up.z >= 0.9999 {
        DMat3::IDENTITY
    } else if up.z <= -0.9999 {
        DMat3::from_rotation_y(std::f64::consts::PI)
    } else {
        axis_rotation(DVec3::Z.cross(up), up.z.acos())
    };
    let distance = radius * (1.0 + CHILD_SCALE);
    for &direction in children {
        let child = turn * direction * distance + center;
        let child_up = (child - center) / distance;
        flake(
            items,
            children,
            depth - 1,
            child,
            radius * CHILD_SCALE,
            child_up,
        );
    }
}
