//! Rays through the shared edge of two triangles hit at least one of them: a mesh has no cracks.

use glam::Vec3;
use proptest::prelude::*;
use raylab::ray::Ray;
use raylab::shapes::Triangle;

/// A number in `[low, high)` on a grid of 2²⁴ steps. Proptest's own `f32` ranges can trip a
/// debug assertion in its sampler on some seeds (proptest 1.12, `float_samplers.rs`), so the
/// numbers come from integers.
fn number(low: f32, high: f32) -> impl Strategy<Value = f32> {
    const STEPS: u32 = 1 << 24;
    (0..STEPS).prop_map(move |i| low + (high - low) * (i as f32 / STEPS as f32))
}

fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(number(-range, range)).prop_map(Vec3::from)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 20000,
        max_global_rejects: 20000,
        ..ProptestConfig::default()
    })]
    #[test]
    fn no_ray_slips_through_a_shared_edge(
        a in vec3(10.0),
        c in vec3(10.0),
        side in vec3(5.0),
        fold in vec3(2.0),
        (u1, u2, s) in (number(0.0, 1.0), number(0.0, 1.0), number(0.01, 0.99)),
        origin in vec3(30.0),
    ) {
        // Triangles (a, b, c) and (a, c, d) share the edge a–c, with b and d on either side of
        // it, wound the same way, folded a little out of one plane.
        let edge = c - a;
        let b = a + edge * u1 + side;
        let d = a + edge * u2 - side + fold;
        let t1 = Triangle::new([a, b, c], 0);
        let t2 = Triangle::new([a, c, d], 1);
        prop_assume!(t1.double_area() > 1e-2 && t2.double_area() > 1e-2);
        // The ray aims at the edge, not at its ends: within a rounding error of a vertex it may
        // pass beside the vertex, where the triangles around it that these two leave out would
        // be (s = 2·10⁻⁶ on a ray from 30 units away did).
        prop_assume!(edge.length() > 0.1);
        let ray = Ray::new(origin, a + edge * s - origin);
        // The ray sees both from the same side (else the edge is a silhouette, and a ray beside
        // it rightly misses both) and not edge-on.
        let (c1, c2) = (ray.dir.normalize().dot(t1.normal()), ray.dir.normalize().dot(t2.normal()));
        prop_assume!(c1.abs() > 0.05 && c2.abs() > 0.05 && c1.signum() == c2.signum());
        let hit = t1.intersect(&ray, 0.0, f32::INFINITY).is_some()
            || t2.intersect(&ray, 0.0, f32::INFINITY).is_some();
        prop_assert!(hit, "slipped through at s = {s}");
    }
}
