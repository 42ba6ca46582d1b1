//! Axis-aligned boxes, hit by the slab test; each face is a part of its own with its own
//! texture coordinates.

use glam::{Vec2, Vec3};

use super::{LocalSurface, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;

/// The box `[min, max]`. Its faces are the parts `2·axis` (the `min` side) and `2·axis + 1`
/// (the `max` side): −x, +x, −y, +y, −z, +z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cuboid {
    min: Vec3,
    max: Vec3,
}

impl Cuboid {
    pub fn new(min: Vec3, max: Vec3) -> Result<Cuboid, String> {
        if !min.is_finite() || !max.is_finite() {
            return Err(format!("box corners must be finite, got {min} and {max}"));
        }
        if min.cmpge(max).any() {
            return Err(format!(
                "box min must be below max on every axis, got min {min} and max {max}"
            ));
        }
        if !(max - min).is_finite() {
            return Err(format!("box is too large to work with: {min} to {max}"));
        }
        Ok(Cuboid { min, max })
    }

    /// The slab test, keeping track of which face the ray enters and leaves by. A ray from
    /// inside hits the face it leaves by. It is [`Aabb::slabs`] written out axis by axis, so
    /// that an axis the ray runs parallel to is skipped before any division: calling `slabs`
    /// and then picking the faces made box-only scenes 7% slower (`raylab bench`, 400 boxes).
    /// `tests` checks that both agree.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let mut enter = (f32::NEG_INFINITY, 0);
        let mut exit = (f32::INFINITY, 0);
        for axis in 0..3 {
            let (origin, dir) = (ray.origin[axis], ray.dir[axis]);
            let (low, high) = (self.min[axis], self.max[axis]);
            if dir == 0.0 {
                if origin < low || origin > high {
                    return None; // parallel to this slab and outside it
                }
                continue;
            }
            let inv_dir = 1.0 / dir;
            let (t_low, t_high) = ((low - origin) * inv_dir, (high - origin) * inv_dir);
            let face = 2 * axis as u32;
            let (t_in, face_in, t_out, face_out) = if dir > 0.0 {
                (t_low, face, t_high, face + 1)
            } else {
                (t_high, face + 1, t_low, face)
            };
            if t_in > enter.0 {
                enter = (t_in, face_in);
            }
            if t_out < exit.0 {
                exit = (t_out, face_out);
            }
        }
        if enter.0 > exit.0 {
            return None;
        }
        [enter, exit]
            .into_iter()
            .find(|&(t, _)| t > t_min && t < t_max)
            .map(|(t, part)| ShapeHit { t, part })
    }

    /// Each face maps to `[0, 1]²` the right way round seen from outside: `v` runs up (+y) on the
    /// side faces; on the top `u` runs along +x and `v` along −z, on the bottom along +x and +z.
    pub fn surface(&self, p: Vec3, part: u32) -> LocalSurface {
        let f = ((p - self.min) / (self.max - self.min)).clamp(Vec3::ZERO, Vec3::ONE);
        let (normal, uv) = match part {
            0 => (-Vec3::X, Vec2::new(f.z, f.y)),
            1 => (Vec3::X, Vec2::new(1.0 - f.z, f.y)),
            2 => (-Vec3::Y, Vec2::new(f.x, f.z)),
            3 => (Vec3::Y, Vec2::new(f.x, 1.0 - f.z)),
            4 => (-Vec3::Z, Vec2::new(1.0 - f.x, f.y)),
            _ => (Vec3::Z, Vec2::new(f.x, f.y)),
        };
        LocalSurface { normal, uv }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.min, self.max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    fn cuboid() -> Cuboid {
        Cuboid::new(Vec3::new(-1.0, -2.0, -3.0), Vec3::new(1.0, 2.0, 3.0)).unwrap()
    }

    /// How far `p` is from the box's surface (0 on it).
    fn off_surface(c: &Cuboid, p: Vec3) -> f32 {
        let outside = (c.min - p).max(p - c.max).max(Vec3::ZERO).length();
        let inside = (p - c.min).min(c.max - p).min_element();
        if outside > 0.0 { outside } else { inside }
    }

    /// The written-out slab test enters where the shared one ([`Aabb::entry`]) does, for rays
    /// from outside in every direction, axis-parallel ones included.
    #[test]
    fn enters_where_the_aabb_slab_test_does() {
        let c = cuboid();
        let mut rng = fastrand::Rng::with_seed(12);
        let mut coordinate = |scale: f32| (rng.f32() * 2.0 - 1.0) * scale;
        let (mut hits, mut rays) = (0, 0);
        while rays < 20_000 {
            let origin = Vec3::new(coordinate(4.0), coordinate(6.0), coordinate(8.0));
            if origin.cmpge(c.min).all() && origin.cmple(c.max).all() {
                continue; // from inside, the box is left, not entered
            }
            // Towards a point near the box (within 1.5 times its size), so many rays hit it.
            let target = Vec3::new(coordinate(1.5), coordinate(3.0), coordinate(4.5));
            let mut dir = target - origin;
            if rays % 4 == 0 {
                dir[rays / 4 % 3] = 0.0; // parallel to one pair of faces
            }
            let ray = Ray::new(origin, dir);
            let entry = c.bounds().entry(origin, dir.recip(), 0.0, f32::INFINITY);
            let hit = c.intersect(&ray, 0.0, f32::INFINITY).map(|h| h.t);
            assert_eq!(hit, entry, "ray from {origin} along {dir}");
            hits += usize::from(hit.is_some());
            rays += 1;
        }
        assert!(hits > rays / 4, "only {hits} of {rays} rays hit the box");
    }

    #[test]
    fn hits_each_face_from_outside() {
        let c = cuboid();
        let cases = [
            (Vec3::new(-5.0, 0.5, 1.0), Vec3::X, 0),
            (Vec3::new(5.0, 0.5, 1.0), -Vec3::X, 1),
            (Vec3::new(0.5, -5.0, 1.0), Vec3::Y, 2),
            (Vec3::new(0.5, 5.0, 1.0), -Vec3::Y, 3),
            (Vec3::new(0.5, 1.0, -5.0), Vec3::Z, 4),
            (Vec3::new(0.5, 1.0, 5.0), -Vec3::Z, 5),
        ];
        for (origin, dir, part) in cases {
            let ray = Ray::new(origin, dir * 2.0);
            let hit = c.intersect(&ray, 0.0, f32::INFINITY).unwrap();
            assert_eq!(hit.part, part);
            let p = ray.at(hit.t);
            assert!(off_surface(&c, p) < 1e-6, "{p}");
            let n = c.surface(p, hit.part).normal;
            assert_eq!(n, -dir, "part {part}");
        }
    }

    #[test]
    fn exact_hit_on_the_plus_x_face() {
        let ray = Ray::new(Vec3::new(5.0, 1.0, -1.5), Vec3::new(-2.0, 0.0, 0.0));
        let hit = cuboid().intersect(&ray, 0.0, f32::INFINITY).unwrap();
        assert_eq!(hit, ShapeHit { t: 2.0, part: 1 });
        assert_eq!(ray.at(hit.t), Vec3::new(1.0, 1.0, -1.5));
        let surface = cuboid().surface(ray.at(hit.t), hit.part);
        assert_eq!(surface.normal, Vec3::X);
        // Seen from +x, u runs along −z and v up.
        assert_near(surface.uv.extend(0.0), Vec3::new(0.75, 0.75, 0.0), 1e-6);
    }

    #[test]
    fn texture_coordinates_stay_in_the_unit_square() {
        let c = cuboid();
        for part in 0..6 {
            for p in [c.min, c.max, Vec3::new(1.0, -2.0, 0.0)] {
                let uv = c.surface(p, part).uv;
                assert!(
                    uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all(),
                    "{uv}"
                );
            }
        }
        assert_eq!(
            c.surface(Vec3::new(0.0, 2.0, -3.0), 3).uv,
            Vec2::new(0.5, 1.0)
        );
    }

    #[test]
    fn ray_from_inside_hits_the_exit_face() {
        let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.5, 0.0));
        let hit = cuboid().intersect(&ray, 1e-4, f32::INFINITY).unwrap();
        assert_eq!(hit, ShapeHit { t: 4.0, part: 3 });
        let n = cuboid().surface(ray.at(hit.t), hit.part).normal;
        assert!(n.dot(ray.at(hit.t)) > 0.0);
    }

    #[test]
    fn ray_starting_on_a_face_leaves_by_the_opposite_one() {
        let ray = Ray::new(Vec3::new(-1.0, 0.0, 0.0), Vec3::X);
        let hit = cuboid().intersect(&ray, 1e-4, f32::INFINITY).unwrap();
        assert_eq!(hit, ShapeHit { t: 2.0, part: 1 });
        let outward = Ray::new(Vec3::new(-1.0, 0.0, 0.0), -Vec3::X);
        assert_eq!(cuboid().intersect(&outward, 1e-4, f32::INFINITY), None);
    }

    #[test]
    fn misses() {
        let c = cuboid();
        let beside = Ray::new(Vec3::new(-5.0, 2.5, 0.0), Vec3::X);
        let away = Ray::new(Vec3::new(-5.0, 0.0, 0.0), -Vec3::X);
        let skew = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 0.0));
        for ray in [beside, away, skew] {
            assert_eq!(c.intersect(&ray, 0.0, f32::INFINITY), None, "{ray:?}");
        }
    }

    #[test]
    fn grazing_rays_give_no_nan() {
        let c = cuboid();
        // Along the edge y = 2, z = 3 and along the face y = 2.
        for origin in [Vec3::new(-5.0, 2.0, 3.0), Vec3::new(-5.0, 2.0, 0.0)] {
            let ray = Ray::new(origin, Vec3::X);
            let hit = c.intersect(&ray, 0.0, f32::INFINITY).unwrap();
            assert_eq!(hit, ShapeHit { t: 4.0, part: 0 });
        }
        // Through a corner, diagonally.
        let corner = Ray::new(Vec3::new(2.0, 3.0, 4.0), Vec3::new(-1.0, -1.0, -1.0));
        let hit = c.intersect(&corner, 0.0, f32::INFINITY).unwrap();
        assert_eq!(hit.t, 1.0);
        let near_miss = Ray::new(Vec3::new(-5.0, 2.0 + 1e-5, 0.0), Vec3::X);
        assert_eq!(c.intersect(&near_miss, 0.0, f32::INFINITY), None);
    }

    #[test]
    fn respects_the_t_range() {
        let c = cuboid();
        let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
        assert_eq!(c.intersect(&ray, 0.0, 4.0), None);
        // Past the entry, the exit is next.
        assert_eq!(
            c.intersect(&ray, 4.0, 10.0),
            Some(ShapeHit { t: 6.0, part: 1 })
        );
        assert_eq!(c.intersect(&ray, 6.0, 10.0), None);
    }

    #[test]
    fn rejects_bad_corners() {
        assert_eq!(
            Cuboid::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0)).unwrap_err(),
            "box min must be below max on every axis, got min [0, 0, 0] and max [1, 0, 1]"
        );
        assert!(Cuboid::new(Vec3::ZERO, Vec3::splat(f32::INFINITY)).is_err());
        assert!(Cuboid::new(Vec3::splat(-3e38), Vec3::splat(3e38)).is_err());
    }

    #[test]
    fn transformed_box_in_the_world() {
        // The unit cube stretched to 2 along x, turned 90° about z (x → y), moved up z by 5:
        // x ∈ [−1, 0], y ∈ [0, 2], z ∈ [5, 6]. Its object +x face is the world's top (y = 2).
        let unit = Cuboid::new(Vec3::ZERO, Vec3::ONE).unwrap();
        let steps = [
            TransformStep::Scale(Vec3::new(2.0, 1.0, 1.0)),
            TransformStep::Rotate {
                axis: Vec3::Z,
                degrees: 90.0,
            },
            TransformStep::Translate(Vec3::new(0.0, 0.0, 5.0)),
        ];
        let ray = Ray::new(Vec3::new(-0.5, 10.0, 5.5), Vec3::new(0.0, -1.0, 0.0));
        let (hit, surface) = hit_in_world(Shape::Cuboid(unit), &steps, &ray).unwrap();
        assert!((hit.t - 8.0).abs() < 1e-5);
        assert_eq!(hit.part, 1);
        assert_near(surface.point, Vec3::new(-0.5, 2.0, 5.5), 1e-5);
        assert_near(surface.normal, Vec3::Y, 1e-5);
        assert_near(surface.object_point, Vec3::new(1.0, 0.5, 0.5), 1e-5);
    }
}
