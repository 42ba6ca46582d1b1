//! rings: a pyramid of objects, SF layers deep, seen from its tip; each object is six
//! pentagonal rings (of cylinders joined by spheres) through the edge midpoints of a
//! dodecahedron, 30 cylinders and 30 spheres. A wall behind catches the shadows of three lights.

use std::f64::consts::{PI, TAU};

use glam::{DMat3, DVec3};

use super::conventions::{Surface, document};
use crate::formats::nff::{Item, NffDocument};

/// Radius of the cylinders and spheres.
const RADIUS: f64 = 0.07412;

/// The rings' colours: red, green, blue and their complements.
const RING_COLORS: [[f64; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
];

pub(super) fn rings(size: u32) -> NffDocument {
    // Layers are this far apart, so that the 45° view just takes in the pyramid.
    let spread = 1.0 / (PI / 8.0).sin();
    let from = [-1.0, -spread, 0.5];
    let mut doc = document(
        from,
        [from[0], from[1] + 1.0, from[2]],
        [0.0, 0.0, 1.0],
        1.0,
        &[
            [3.0, -spread, 3.0],
            [-4.0, -spread, 1.0],
            [2.0, -spread, -4.0],
        ],
    );
    doc.items.push(Surface::matte([1.0, 1.0, 1.0], 1.0).fill());
    // The wall just fills the 45° view, plus 1 %.
    let wall_y = spread * f64::from(size + 1);
    let half = 1.01 * (wall_y - from[1]) * (PI / 8.0).tan();
    let corner = |sx: f64, sz: f64| DVec3::new(sx * half + from[0], wall_y, sz * half + from[2]);
    doc.items.push(Item::Polygon(vec![
        corner(1.0, 1.0),
        corner(-1.0, 1.0),
        corner(-1.0, -1.0),
        corner(1.0, -1.0),
    ]));

    let dodecahedron = ring_points();
    for layer in 0..size {
        let layer_f = f64::from(layer);
        for iz in 0..=layer {
            for ix in 0..=layer {
                let offset = DVec3::new(
                    2.0 * f64::from(ix) - layer_f,
                    spread * (layer_f + 1.0),
                    2.0 * f64::from(iz) - layer_f,
                );
                object(&mut doc.items, &dodecahedron, offset);
            }
        }
    }
    doc
}

/// One object: six rings of five cylinders, a sphere at every joint.
fn object(items: &mut Vec<Item>, points: &[DVec3; 30], offset: DVec3) {
    for (i, &point) in points.iter().enumerate() {
        let previous = if i % 5 == 0 {
            items.push(ring_surface(i / 5).fill());
            i + 4
        } else {
            i - 1
        };
        let base = point + offset;
        items.push(Item::Cone {
            base,
            base_radius: RADIUS,
            apex: points[previous] + offset,
            apex_radius: RADIUS,
        });
        items.push(Item::Sphere {
            center: base,
            radius: RADIUS,
        });
    }
}

fn ring_surface(ring: usize) -> Surface {
    Surface {
        color: RING_COLORS[ring],
        kd: 0.5,
        ks: 0.2,
        highlight_half_angle: 37.0,
        transmittance: 0.0,
        ior: 0.0,
    }
}

/// The corners of the six pentagons, five by five, scaled so the rings fit in a unit sphere: one
/// pentagon in the XY plane, the other five tipped over by the dodecahedron's dihedral angle
/// and spread around the Z axis.
fn ring_points() -> [DVec3; 30] {
    let scale = 1.0 / (1.0 + RADIUS);
    let first: [DVec3; 5] = std::array::from_fn(|k| {
        let angle = k as f64 * TAU / 5.0;
        DVec3::new(scale * angle.cos(), scale * angle.sin(), 0.0)
    });
    let tip = DMat3::from_rotation_x(2.0 * ((PI / 3.0).cos() / (PI / 5.0).sin()).acos());
    std::array::from_fn(|i| {
        let (pentagon, k) = (i / 5, i % 5);
        if pentagon == 0 {
            first[k]
        } else {
            let around = PI * (2.0 * (pentagon - 1) as f64 + 1.0) / 5.0;
            DMat3::from_rotation_z(around) * (tip * first[k])
        }
    })
}
