//! tree: a tree after Aono and Kunii, every branch a cone ending in a sphere and splitting in
//! two, SF levels deep (2^(SF+1) − 1 cones and as many spheres), on a green field, lit by
//! seven lights: mostly shadow rays past thin branches.

use glam::{DAffine3, DVec3};

use super::conventions::{Surface, document};
use crate::formats::nff::{Item, NffDocument};

/// Angle from the parent branch, and contraction of length, of the two child branches.
const BRANCH_ANGLE: [f64; 2] = [40.0, 25.0];
const BRANCH_CONTRACTION: [f64; 2] = [0.65, 0.70];
/// Turn of each child about the parent's axis, in degrees.
const DIVERGENCE: [f64; 2] = [90.0, 140.0 + 90.0];
/// Radius at a branch's tip relative to its base, and of a child's base relative to its parent's.
const DIAMETER_RATIO: f64 = 0.67;
/// Base radius of the trunk relative to its length.
const WIDTH_HEIGHT_RATIO: f64 = 0.15;

pub(super) fn tree(size: u32) -> NffDocument {
    let mut doc = document(
        [4.5, 0.4, 2.0],
        [0.0, 0.0, 1.5],
        [0.0, 0.0, 1.0],
        1.0,
        &[
            [-5.0, 5.0, 50.0],
            [30.0, -30.0, 30.0],
            [-40.0, -30.0, 20.0],
            [10.0, 30.0, 40.0],
            [-30.0, 40.0, 10.0],
            [50.0, 25.0, 20.0],
            [-10.0, -60.0, 30.0],
        ],
    );
    doc.items.push(Surface::matte([0.2, 0.7, 0.2], 1.0).fill());
    doc.items.push(Item::Polygon(vec![
        DVec3::new(50.0, 50.0, 0.0),
        DVec3::new(-50.0, 50.0, 0.0),
        DVec3::new(-50.0, -50.0, 0.0),
        DVec3::new(50.0, -50.0, 0.0),
    ]));
    doc.items.push(Surface::matte([0.55, 0.4, 0.2], 1.0).fill());
    // A child branch in its parent's frame: tipped by the branch angle, turned about the
    // parent's axis, shortened, and moved to the parent's tip.
    let child: [DAffine3; 2] = std::array::from_fn(|i| {
        DAffine3::from_translation(DVec3::Z)
            * DAffine3::from_scale(DVec3::splat(BRANCH_CONTRACTION[i]))
            * DAffine3::from_rotation_z(DIVERGENCE[i].to_radians())
            * DAffine3::from_rotation_x(BRANCH_ANGLE[i].to_radians())
    });
    branch(&mut doc.items, &child, DAffine3::IDENTITY, 1.0, size);
    doc
}

/// The branch that `frame` places along (0, 0, 0)–(0, 0, 1), with base radius
/// `scale · WIDTH_HEIGHT_RATIO`, and `depth` levels of branches above it.
fn branch(items: &mut Vec<Item>, child: &[DAffine3; 2], frame: DAffine3, scale: f64, depth: u32) {
    let base = frame.transform_point3(DVec3::ZERO);
    let apex = frame.transform_point3(DVec3::Z);
    let base_radius = scale * WIDTH_HEIGHT_RATIO;
    let apex_radius = base_radius * DIAMETER_RATIO;
    items.push(Item::Cone {
        base,
        base_radius,
        apex,
        apex_radius,
    });
    items.push(Item::Sphere {
        center: apex,
        radius: apex_radius,
    });
    if depth > 0 {
        for c in child {
            branch(items, child, frame * *c, scale * DIAMETER_RATIO, depth - 1);
        }
    }
}
