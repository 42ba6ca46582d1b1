//! Spheres, given by centre and radius.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::quadratic::first_root_in;
use super::{LocalSurface, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
}

impl Sphere {
    /// A sphere; the radius must be a positive number.
    pub fn new(center: Vec3, radius: f32) -> Result<Sphere, String> {
        if !center.is_finite() {
            return Err(format!("sphere centre must be finite, got {center}"));
        }
        if radius.is_finite() && radius > 0.0 {
            Ok(Sphere { center, radius })
        } else {
            Err(format!(
                "sphere radius must be a positive number, got {radius}"
            ))
        }
    }

    /// Solves `|o + d·t − c|² = r²`. The discriminant is computed as `r² − |f|²` with
    /// `f = oc − (oc·d / d·d)·d` (Ray Tracing Gems, ch. 7), which stays accurate for spheres far
    /// from the ray origin.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let oc = ray.origin - self.center;
        let a = ray.dir.length_squared();
        let half_b = oc.dot(ray.dir);
        let c = oc.length_squared() - self.radius * self.radius;
        let f = oc - (half_b / a) * ray.dir;
        let disc = a * (self.radius * self.radius - f.length_squared());
        if disc < 0.0 {
            return None;
        }
        let q = -(half_b + disc.sqrt().copysign(half_b));
        let roots = if q == 0.0 {
            (0.0, 0.0)
        } else {
            // Sorted by a comparison, not `min` and `max`, so that `SpherePack` can do the
            // same in SIMD, lane by lane.
            let (t0, t1) = (q / a, c / q);
            if t0 <= t1 { (t0, t1) } else { (t1, t0) }
        };
        let t = first_root_in(roots, t_min, t_max)?;
        Some(ShapeHit { t, part: 0 })
    }

    /// The outward normal at `p`, of unit length on the sphere.
    pub fn normal(&self, p: Vec3) -> Vec3 {
        (p - self.center) / self.radius
    }

    /// Spherical mapping: `u` around the vertical axis, `v` from the south pole (0) to the
    /// north pole (1).
    pub fn surface(&self, p: Vec3, _part: u32) -> LocalSurface {
        let n = self.normal(p);
        LocalSurface {
            normal: n,
            uv: sphere_uv(n.normalize_or(Vec3::Y)),
        }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(
            self.center - Vec3::splat(self.radius),
            self.center + Vec3::splat(self.radius),
        )
    }
}

/// Texture coordinates of a direction `d` from the centre of a sphere (unit length).
pub fn sphere_uv(d: Vec3) -> Vec2 {
    let u = 0.5 + d.x.atan2(d.z) / (2.0 * PI);
    let v = 0.5 + d.y.clamp(-1.0, 1.0).asin() / PI;
    Vec2::new(u, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    const CENTER: Vec3 = Vec3::new(1.0, 2.0, 3.0);

    fn sphere() -> Sphere {
        Sphere {
            center: CENTER,
            radius: 2.0,
        }
    }

    fn hit(ray: &Ray) -> Option<ShapeHit> {
        sphere().intersect(ray, 1e-4, f32::INFINITY)
    }

    #[test]
    fn hit_from_outside() {
        let ray = Ray::new(Vec3::new(1.0, 2.0, 10.0), Vec3::new(0.0, 0.0, -2.0));
        let h = hit(&ray).unwrap();
        assert_eq!(h, ShapeHit { t: 2.5, part: 0 });
        assert_eq!(ray.at(h.t), Vec3::new(1.0, 2.0, 5.0));
        let s = sphere().surface(ray.at(h.t), h.part);
        assert_eq!(s.normal, Vec3::Z);
        assert_eq!(s.uv, Vec2::new(0.5, 0.5));
    }

    #[test]
    fn oblique_hit_lies_on_the_sphere() {
        let ray = Ray::new(Vec3::new(-4.0, 5.0, 1.0), Vec3::new(1.0, -0.5, 0.4));
        let h = hit(&ray).unwrap();
        let p = ray.at(h.t);
        assert!(((p - CENTER).length() - 2.0).abs() < 1e-5, "{p}");
        let n = sphere().surface(p, h.part).normal;
        assert!((n.length() - 1.0).abs() < 1e-5);
        assert!(n.dot(p - CENTER) > 0.0);
    }

    #[test]
    fn ray_from_inside_hits_the_exit() {
        let ray = Ray::new(CENTER, Vec3::new(0.0, 4.0, 0.0));
        assert_eq!(hit(&ray), Some(ShapeHit { t: 0.5, part: 0 }));
        let from_surface = Ray::new(CENTER + Vec3::Y * 2.0, Vec3::new(0.3, 1.0, 0.0));
        assert_eq!(hit(&from_surface), None);
    }

    #[test]
    fn tangent_and_missing_rays() {
        let tangent = Ray::new(Vec3::new(-5.0, 4.0, 3.0), Vec3::X);
        let h = hit(&tangent).unwrap();
        assert!((h.t - 6.0).abs() < 1e-3, "{h:?}");
        assert!(sphere().surface(tangent.at(h.t), 0).normal.is_finite());
        assert_eq!(hit(&Ray::new(Vec3::new(-5.0, 4.01, 3.0), Vec3::X)), None);
        assert_eq!(hit(&Ray::new(Vec3::new(-5.0, 2.0, 3.0), -Vec3::X)), None);
    }

    #[test]
    fn respects_the_t_range() {
        let ray = Ray::new(Vec3::new(-5.0, 2.0, 3.0), Vec3::X);
        assert_eq!(sphere().intersect(&ray, 0.0, 4.0), None);
        assert_eq!(
            sphere().intersect(&ray, 4.0, 10.0),
            Some(ShapeHit { t: 8.0, part: 0 })
        );
        assert_eq!(sphere().intersect(&ray, 8.0, 10.0), None);
    }

    #[test]
    fn stretched_sphere_in_the_world() {
        // The unit sphere stretched to 2 along y and moved to (0, 0, 5).
        let unit = Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        };
        let steps = [
            TransformStep::Scale(Vec3::new(1.0, 2.0, 1.0)),
            TransformStep::Translate(Vec3::new(0.0, 0.0, 5.0)),
        ];
        let ray = Ray::new(Vec3::new(0.0, 10.0, 5.0), -Vec3::Y);
        let (h, s) = hit_in_world(Shape::Sphere(unit), &steps, &ray).unwrap();
        assert!((h.t - 8.0).abs() < 1e-5);
        assert_near(s.point, Vec3::new(0.0, 2.0, 5.0), 1e-5);
        assert_near(s.object_point, Vec3::Y, 1e-5);
        assert_near(s.normal, Vec3::Y, 1e-5);
    }
}
