//! What the shape tests share: placing a shape in the world through a transform, comparing
//! vectors with a tolerance, points on a grid, and a pack's lanes as single tests see them.

use glam::Vec3;

use super::{LaneHits, Shape, ShapeHit};
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
    let mut geometry = Geometry::default();
    geometry.objects.push(Object {
        shape,
        transform: Some(Box::new(
            Transform::from_steps(steps).expect("valid transform"),
        )),
        material: 0,
    });
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

/// The point `(x, y, z)·scale`: random coordinates drawn as integers (proptest's `f32` ranges
/// trip a debug assertion on rare seeds).
pub fn grid_point((x, y, z): (i32, i32, i32), scale: f32) -> Vec3 {
    Vec3::new(x as f32, y as f32, z as f32) * scale
}

/// The `t` of each of the first `count` lanes of `hits` as bits, `None` where the lane misses,
/// after checking that the unused lanes miss: what the single tests' answers must equal.
#[track_caller]
pub fn lane_ts(hits: &LaneHits, count: usize) -> Vec<Option<u32>> {
    assert_eq!(hits.mask >> count, 0, "an unused lane hit");
    let lane = |k: usize| (hits.mask >> k & 1 == 1).then_some(hits.t[k].to_bits());
    (0..count).map(lane).collect()
}

/// What [`lane_ts`] compares with: a single test's `t` as bits.
pub fn t_bits(hit: Option<ShapeHit>) -> Option<u32> {
    hit.map(|h| h.t.to_bits())
}
