//! Four spheres tested against one ray at once: [`Sphere::intersect`] with one sphere per SIMD
//! lane, in the same arithmetic and order, so each lane's answer is exactly the single test's.
//! Scenes of many spheres (the SPD balls and rings) and small clusters of them (the SPD
//! mountain's four glass balls, which most of its rays pass near) save a dispatch per sphere
//! and test the cluster in one go.

use glam::Vec4;

use super::quadratic::sorted_roots4;
use super::{LaneHits, ObjectPack, PACK_SIZE, Sphere};
use crate::ray::Ray;

/// Up to [`PACK_SIZE`] spheres, coordinate by coordinate (`center[axis][lane]`), each with a
/// number for the caller (the BVH keeps primitive ids there). Unused lanes have a NaN centre,
/// which no ray hits. 80 bytes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct SpherePack {
    center: [[f32; PACK_SIZE]; 3],
    radius: [f32; PACK_SIZE],
    pub tags: [u32; PACK_SIZE],
}

impl SpherePack {
    /// The pack of `spheres` (at most [`PACK_SIZE`]), each with its tag.
    pub fn new(spheres: &[(&Sphere, u32)]) -> SpherePack {
        assert!(spheres.len() <= PACK_SIZE, "a pack holds {PACK_SIZE}");
        let mut pack = SpherePack {
            center: [[f32::NAN; PACK_SIZE]; 3],
            radius: [f32::NAN; PACK_SIZE],
            tags: [u32::MAX; PACK_SIZE],
        };
        for (lane, &(sphere, tag)) in spheres.iter().enumerate() {
            for axis in 0..3 {
                pack.center[axis][lane] = sphere.center[axis];
            }
            pack.radius[lane] = sphere.radius;
            pack.tags[lane] = tag;
        }
        pack
    }
}

impl ObjectPack for SpherePack {
    /// Which spheres `ray` hits with `t` in `(t_min, t_max)`, all four at once: each lane's
    /// nearest root in the range.
    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> LaneHits {
        let d = ray.dir.to_array().map(Vec4::splat);
        let oc = [0, 1, 2].map(|k| Vec4::splat(ray.origin[k]) - Vec4::from(self.center[k]));
        let dot = |u: &[Vec4; 3], v: &[Vec4; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        let radius = Vec4::from(self.radius);
        let r2 = radius * radius;
        // As `Sphere::intersect`: the discriminant from the ray's distance to the centre.
        let a = Vec4::splat(ray.dir.length_squared());
        let half_b = dot(&oc, &d);
        let c = dot(&oc, &oc) - r2;
        let along = half_b / a;
        let f = [0, 1, 2].map(|k| oc[k] - along * d[k]);
        let disc = a * (r2 - dot(&f, &f));
        let real = !disc.cmplt(Vec4::ZERO);
        if !real.any() {
            return LaneHits {
                mask: 0,
                t: Vec4::ZERO,
            };
        }
        let (near, far) = sorted_roots4(a, half_b, c, disc);
        // The first root in the range, as `first_root_in`.
        let in_range = |t: Vec4| t.cmpgt(Vec4::splat(t_min)) & t.cmplt(Vec4::splat(t_max));
        let (near_in, far_in) = (in_range(near), in_range(far));
        LaneHits {
            mask: (real & (near_in | far_in)).bitmask(),
            t: Vec4::select(near_in, near, far),
        }
    }

    fn tags(&self) -> &[u32; PACK_SIZE] {
        &self.tags
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::shapes::test_support::{grid_point, lane_ts, t_bits};

    proptest! {
        /// Random spheres against random rays, from outside and inside, some grazing, some far:
        /// each lane answers exactly as `Sphere::intersect`.
        #[test]
        fn each_lane_answers_as_the_single_sphere_test(
            spheres in proptest::collection::vec(
                ((-64i32..64, -64i32..64, -64i32..64), 1u32..64),
                1..=PACK_SIZE,
            ),
            origin in (-256i32..256, -256i32..256, -256i32..256),
            aim in (0usize..4, -64i32..64, -64i32..64, -64i32..64),
            t_min in proptest::option::of(0u32..16),
            t_max in proptest::option::of(1u32..64),
        ) {
            let spheres: Vec<Sphere> = spheres
                .iter()
                .map(|&(c, r)| Sphere::new(grid_point(c, 1.0 / 16.0), r as f32 / 16.0).unwrap())
                .collect();
            let tagged: Vec<(&Sphere, u32)> = spheres.iter().zip(10..).collect();
            let pack = SpherePack::new(&tagged);
            let origin = grid_point(origin, 1.0 / 16.0);
            // Towards a point near one of the spheres (grazing hits and near misses included).
            let (k, x, y, z) = aim;
            let target = spheres[k % spheres.len()].center + grid_point((x, y, z), 1.0 / 32.0);
            let ray = Ray::new(origin, target - origin);
            let t_min = t_min.map_or(1e-4, |t| t as f32 / 16.0);
            let t_max = t_max.map_or(f32::INFINITY, |t| t as f32 / 16.0);
            let hits = pack.intersect(&ray, t_min, t_max);
            let singles = spheres.iter().map(|s| t_bits(s.intersect(&ray, t_min, t_max)));
            prop_assert_eq!(lane_ts(&hits, spheres.len()), singles.collect::<Vec<_>>());
        }
    }
}
