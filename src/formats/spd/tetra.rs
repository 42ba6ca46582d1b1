//! tetra: Sierpinski's tetrahedron, a tetrahedron made of four half-size ones, recursively, SF
//! levels deep (4^SF triangles), lit by one light. Around 80 % of the image is background.

use glam::DVec3;

use super::conventions::{Surface, document};
use crate::formats::nff::{Item, NffDocument};

pub(super) fn tetra(size: u32) -> NffDocument {
    let mut doc = document(
        [1.022846, -3.177154, -2.174512],
        [-0.004103, -0.004103, 0.216539],
        [-0.816497, -0.816497, 0.816497],
        1.0,
        &[[2.0, -18.0, -5.0]],
    );
    doc.items.push(Surface::matte([1.0, 0.2, 0.2], 1.0).fill());
    tetrahedron(&mut doc.items, size, DVec3::ZERO, 1.0);
    doc
}

/// The four corners of the cube of half side `half` about `center` whose coordinates'
/// signs multiply to +1: a regular tetrahedron.
fn corners(center: DVec3, half: f64) -> [DVec3; 4] {
    [
        DVec3::new(-1.0, -1.0, 1.0),
        DVec3::new(-1.0, 1.0, -1.0),
        DVec3::new(1.0, -1.0, -1.0),
        DVec3::new(1.0, 1.0, 1.0),
    ]
    .map(|sign| center + sign * half)
}

/// The tetrahedron in the cube of half side `half` about `center`, `depth` levels deep.
fn tetrahedron(items: &mut Vec<Item>, depth: u32, center: DVec3, half: f64) {
    if depth <= 1 {
        let corner = corners(center, half);
        // Each face counter-clockwise seen from outside.
        for face in 0..4 {
            let mut order = [face, face + 1, face + 2].map(|k| k % 4);
            if face % 2 == 1 {
                order.swap(0, 2);
            }
            items.push(Item::Polygon(order.map(|k| corner[k]).to_vec()));
        }
    } else {
        for sub_center in corners(center, half / 2.0) {
            tetrahedron(items, depth - 1, sub_center, half / 2.0);
        }
    }
}
