//! What the shape tests share: placing a shape in the world through a transform, and comparing
//! vectors with a tolerance.

use glam::Vec3;

use super::Shape;
use crate::primitive::{Geometry, Hit, Object, PrimId, SurfacePoint};
use crate::ray::Ray;
use crate::transform::{Transform, TransformStep};

/// The hit of `ray` with `shape` placed by `steps`, and the world-space surface there, found the
/// way the tracer finds them.
pub fn hit_in_world(
    shape: Shape,
    steps: &[TransformStep],
    ray: &Ray,
) -> Option<(Hit, SurfacePoint)> {
    let geometry = Geometry {
        objects: vec![Object {
            shape,
            transform: Some(Transform::from_steps(steps).expect("valid transform")),
            material: 0,
        }],
        ..Geometry::default()
    };
    let hit = geometry.intersect(PrimId::object(0), ray, 1e-4, f32::INFINITY)?;
    Some((hit, geometry.surface(ray, &hit)))
}

#[track_caller]
pub fn assert_near(actual: Vec3, expected: Vec3, tolerance: f32) {
    assert!(
        actual.abs_diff_eq(expected, tolerance),
        "{actual} is not within {tolerance} of {expected}"
    );
}
