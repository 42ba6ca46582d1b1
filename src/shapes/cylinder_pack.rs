//! Four open tapered cylinders tested against one ray at once: the side test of
//! [`TaperedCylinder::intersect`] with one cylinder per SIMD lane, in the same arithmetic and
//! order, so each lane's answer is exactly the single test's. NFF's cones and cylinders are
//! open, placed directly in the world, and come by the thousand (the SPD rings' 4,200).

use glam::Vec4;

use super::quadratic::sorted_roots4;
use super::{LaneHits, ObjectPack, PACK_SIZE, TaperedCylinder};
use crate::ray::Ray;

/// Up to [`PACK_SIZE`] open tapered cylinders, coordinate by coordinate (`base[axis][lane]`),
/// each with a number for the caller (the BVH keeps primitive ids there). Unused lanes have a
/// NaN frame, which no ray hits. 272 bytes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct CylinderPack {
    base: [[f32; PACK_SIZE]; 3],
    /// The local frame: `frame[0]` and `frame[1]` across the axis, `frame[2]` along it.
    frame: [[[f32; PACK_SIZE]; 3]; 3],
    height: [f32; PACK_SIZE],
    base_radius: [f32; PACK_SIZE],
    slope: [f32; PACK_SIZE],
    pub tags: [u32; PACK_SIZE],
}

impl CylinderPack {
    /// Whether `cylinder` fits in a lane: it is open (it must also be placed directly in the
    /// world).
    pub fn fits(cylinder: &TaperedCylinder) -> bool {
        !cylinder.is_capped()
    }

    /// The pack of `cylinders` (at most [`PACK_SIZE`], each one that [`Self::fits`]), each
    /// with its tag.
    pub fn new(cylinders: &[(&TaperedCylinder, u32)]) -> CylinderPack {
        assert!(cylinders.len() <= PACK_SIZE, "a pack holds {PACK_SIZE}");
        let mut pack = CylinderPack {
            base: [[0.0; PACK_SIZE]; 3],
            frame: [[[f32::NAN; PACK_SIZE]; 3]; 3],
            height: [0.0; PACK_SIZE],
            base_radius: [0.0; PACK_SIZE],
            slope: [0.0; PACK_SIZE],
            tags: [u32::MAX; PACK_SIZE],
        };
        for (lane, &(cylinder, tag)) in cylinders.iter().enumerate() {
            assert!(Self::fits(cylinder), "a packed cylinder is open");
            let frame = [cylinder.frame_x, cylinder.frame_y, cylinder.axis];
            for axis in 0..3 {
                pack.base[axis][lane] = cylinder.base[axis];
                for (f, vector) in frame.iter().enumerate() {
                    pack.frame[f][axis][lane] = vector[axis];
                }
            }
            pack.height[lane] = cylinder.height;
            pack.base_radius[lane] = cylinder.base_radius;
            pack.slope[lane] = cylinder.slope;
            pack.tags[lane] = tag;
        }
        pack
    }
}

impl ObjectPack for CylinderPack {
    /// Which cylinders `ray` hits with `t` in `(t_min, t_max)`, all four at once.
    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> LaneHits {
        let dot = |u: [Vec4; 3], v: [Vec4; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        let frame = self.frame.map(|f| f.map(Vec4::from));
        let dir = ray.dir.to_array().map(Vec4::splat);
        let rel = [0, 1, 2].map(|k| Vec4::splat(ray.origin[k]) - Vec4::from(self.base[k]));
        // The ray in each cylinder's frame, as `TaperedCylinder::intersect` puts it.
        let d = frame.map(|f| dot(dir, f));
        let origin = frame.map(|f| dot(rel, f));
        let height = Vec4::from(self.height);
        let middle = [Vec4::ZERO, Vec4::ZERO, Vec4::splat(0.5) * height];
        let to_middle = [0, 1, 2].map(|k| middle[k] - origin[k]);
        let shift = dot(to_middle, d) / dot(d, d);
        let o = [0, 1, 2].map(|k| origin[k] + d[k] * shift);
        let slope = Vec4::from(self.slope);
        let radius_at_o = Vec4::from(self.base_radius) + slope * o[2];
        let a = (d[0] * d[0] + d[1] * d[1]) - slope * slope * d[2] * d[2];
        let half_b = (o[0] * d[0] + o[1] * d[1]) - slope * radius_at_o * d[2];
        let c = (o[0] * o[0] + o[1] * o[1]) - radius_at_o * radius_at_o;
        // `solve_quadratic`, both of its cases in every lane, the right one kept.
        let linear = a.cmpeq(Vec4::ZERO);
        let disc = half_b * half_b - a * c;
        let has_roots = linear & half_b.cmpne(Vec4::ZERO) | !linear & !disc.cmplt(Vec4::ZERO);
        let has_roots = shift.is_finite_mask() & has_roots;
        // A ray misses all four cylinders of most packs it reaches: that is told before the
        // divisions.
        if !has_roots.any() {
            return LaneHits {
                mask: 0,
                t: Vec4::ZERO,
            };
        }
        let t_linear = -c / (Vec4::splat(2.0) * half_b);
        let (near, far) = sorted_roots4(a, half_b, c, disc);
        let (near, far) = (
            Vec4::select(linear, t_linear, near),
            Vec4::select(linear, t_linear, far),
        );
        // `first_root_between_ends`: the first root in range whose point lies between the ends.
        let accept = |s: Vec4| {
            let t = s + shift;
            let z = o[2] + d[2] * s;
            let ok = t.cmpgt(Vec4::splat(t_min))
                & t.cmplt(Vec4::splat(t_max))
                & z.cmpge(Vec4::ZERO)
                & z.cmple(height);
            (t, ok)
        };
        let ((t_near, near_ok), (t_far, far_ok)) = (accept(near), accept(far));
        let found = has_roots & (near_ok | far_ok);
        LaneHits {
            mask: found.bitmask(),
            t: Vec4::select(near_ok, t_near, t_far),
        }
    }

    fn tags(&self) -> &[u32; PACK_SIZE] {
        &self.tags
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::*;
    use crate::shapes::test_support::{grid_point, lane_ts, t_bits};

    #[test]
    fn rays_parallel_to_a_cone_side_take_the_linear_case_in_each_lane() {
        // Cones along z whose radius shrinks by 1 per unit of height: a ray of direction
        // (±1, 0, 1) or (0, ±1, 1) runs parallel to a line of the side, where the quadratic's
        // leading coefficient is exactly 0.
        let cones: Vec<TaperedCylinder> = (0..4)
            .map(|k| {
                let base = Vec3::new(k as f32 * 0.25, 0.0, 0.0);
                TaperedCylinder::new(base, base + Vec3::Z * 2.0, 2.0, 0.0, false).unwrap()
            })
            .collect();
        let tagged: Vec<(&TaperedCylinder, u32)> = cones.iter().zip(0..).collect();
        let pack = CylinderPack::new(&tagged);
        let mut hits = 0;
        for i in -40..40 {
            for dir in [Vec3::new(1.0, 0.0, 1.0), Vec3::new(0.0, -1.0, 1.0)] {
                let origin = Vec3::new(i as f32 / 8.0, i as f32 / 16.0, -3.0) - dir;
                let ray = Ray::new(origin, dir);
                let packed = pack.intersect(&ray, 1e-4, f32::INFINITY);
                let singles: Vec<_> = cones
                    .iter()
                    .map(|cone| t_bits(cone.intersect(&ray, 1e-4, f32::INFINITY)))
                    .collect();
                assert_eq!(lane_ts(&packed, cones.len()), singles, "ray {ray:?}");
                hits += singles.iter().flatten().count();
            }
        }
        assert!(hits > 50, "{hits} hits");
    }

    proptest! {
        /// Random cylinders and cones (apex included) against random rays, from outside and
        /// inside, some along the axis, some grazing: each lane answers exactly as
        /// `TaperedCylinder::intersect`.
        #[test]
        fn each_lane_answers_as_the_single_cylinder_test(
            cylinders in proptest::collection::vec(
                ((-64i32..64, -64i32..64, -64i32..64), (-64i32..64, -64i32..64, -64i32..64),
                 0u32..32, 0u32..32),
                1..=PACK_SIZE,
            ),
            origin in (-256i32..256, -256i32..256, -256i32..256),
            aim in (0usize..4, -32i32..32, -32i32..32, -32i32..32),
            along_axis in any::<bool>(),
            t_max in proptest::option::of(1u32..64),
        ) {
            let cylinders: Vec<TaperedCylinder> = cylinders
                .iter()
                .filter_map(|&(base, top, r0, r1)| {
                    let (base, top) = (grid_point(base, 1.0 / 16.0), grid_point(top, 1.0 / 16.0));
                    TaperedCylinder::new(base, top, r0 as f32 / 16.0, r1 as f32 / 16.0, false).ok()
                })
                .collect();
            prop_assume!(!cylinders.is_empty());
            let tagged: Vec<(&TaperedCylinder, u32)> = cylinders.iter().zip(10..).collect();
            let pack = CylinderPack::new(&tagged);
            let (k, x, y, z) = aim;
            let aimed = &cylinders[k % cylinders.len()];
            let mut origin = grid_point(origin, 1.0 / 16.0);
            let target = aimed.base + grid_point((x, y, z), 1.0 / 32.0);
            if along_axis {
                // Along the axis: `a` is 0 for a cylinder, the linear case.
                origin = target - aimed.axis * 10.0;
            }
            let ray = Ray::new(origin, target - origin);
            let t_max = t_max.map_or(f32::INFINITY, |t| t as f32 / 16.0);
            let hits = pack.intersect(&ray, 1e-4, t_max);
            let singles = cylinders.iter().map(|c| t_bits(c.intersect(&ray, 1e-4, t_max)));
            prop_assert_eq!(lane_ts(&hits, cylinders.len()), singles.collect::<Vec<_>>());
        }
    }
}
