//! Axis-aligned ellipsoids, hit as a unit sphere in a space scaled by their radii.

use glam::Vec3;

use super::quadratic::{first_root_in, solve_quadratic};
use super::sphere::sphere_uv;
use super::{LocalSurface, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;

/// The ellipsoid `Σ ((p − center) / radii)² = 1`, its axes along x, y and z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ellipsoid {
    pub(crate) center: Vec3,
    radii: Vec3,
    pub(crate) inv_radii: Vec3,
}

impl Ellipsoid {
    pub fn new(center: Vec3, radii: Vec3) -> Result<Ellipsoid, String> {
        if !center.is_finite() {
            return Err(format!("ellipsoid centre must be finite, got {center}"));
        }
        if !radii.is_finite() || radii.cmple(Vec3::ZERO).any() {
            return Err(format!("ellipsoid radii must be positive, got {radii}"));
        }
        let inv_radii = radii.recip();
        if !inv_radii.is_finite() {
            return Err(format!(
                "ellipsoid radii are too small to work with: {radii}"
            ));
        }
        Ok(Ellipsoid {
            center,
            radii,
            inv_radii,
        })
    }

    /// Scales the ray by `1 / radii` about the centre, which turns the ellipsoid into the unit
    /// sphere and keeps `t`, and solves `|o + d·s|² = 1` there, from the point `o` of the ray
    /// nearest the centre (`s = t − shift`): the coefficients then stay small, and so do their
    /// rounding errors, however far away the ray starts.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let origin = (ray.origin - self.center) * self.inv_radii;
        let d = ray.dir * self.inv_radii;
        let shift = -origin.dot(d) / d.length_squared();
        if !shift.is_finite() {
            return None; // no direction
        }
        let o = origin + d * shift;
        let (s0, s1) = solve_quadratic(d.length_squared(), o.dot(d), o.length_squared() - 1.0)?;
        let t = first_root_in((s0 + shift, s1 + shift), t_min, t_max)?;
        Some(ShapeHit { t, part: 0 })
    }

    /// The normal is the gradient `(p − c) / r²`; texture coordinates are the sphere's, taken
    /// at the matching point of the unit sphere.
    pub fn surface(&self, p: Vec3, _part: u32) -> LocalSurface {
        let on_unit_sphere = (p - self.center) * self.inv_radii;
        LocalSurface {
            normal: on_unit_sphere * self.inv_radii,
            uv: sphere_uv(on_unit_sphere.normalize_or(Vec3::Y)),
        }
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.center - self.radii, self.center + self.radii)
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    const CENTER: Vec3 = Vec3::new(1.0, 2.0, 3.0);

    fn ellipsoid() -> Ellipsoid {
        Ellipsoid::new(CENTER, Vec3::new(2.0, 1.0, 0.5)).unwrap()
    }

    /// The implicit function: 0 on the surface, negative inside.
    fn implicit(e: &Ellipsoid, p: Vec3) -> f32 {
        ((p - e.center) / e.radii).length_squared() - 1.0
    }

    fn hit(ray: &Ray) -> Option<ShapeHit> {
        ellipsoid().intersect(ray, 1e-4, f32::INFINITY)
    }

    #[test]
    fn hits_along_each_axis() {
        let cases = [
            (
                Vec3::new(1.0, 2.0, 10.0),
                Vec3::new(0.0, 0.0, -1.0),
                6.5,
                Vec3::Z,
            ),
            (
                Vec3::new(-5.0, 2.0, 3.0),
                Vec3::new(2.0, 0.0, 0.0),
                2.0,
                -Vec3::X,
            ),
            (
                Vec3::new(1.0, 5.0, 3.0),
                Vec3::new(0.0, -0.5, 0.0),
                4.0,
                Vec3::Y,
            ),
        ];
        for (origin, dir, t, normal) in cases {
            let ray = Ray::new(origin, dir);
            let h = hit(&ray).unwrap();
            assert!((h.t - t).abs() < 1e-5, "{h:?} for {ray:?}");
            let p = ray.at(h.t);
            assert!(implicit(&ellipsoid(), p).abs() < 1e-5, "{p}");
            assert_near(
                ellipsoid().surface(p, h.part).normal.normalize(),
                normal,
                1e-5,
            );
        }
    }

    #[test]
    fn oblique_normal_is_the_gradient() {
        // The unit-sphere point (1, 1, 0)/√2 maps to c + (2, 1, 0)/√2, where the gradient
        // (p − c)/r² is (1/√2)(1/2, 1, 0) ∝ (1, 2, 0).
        let p = CENTER + Vec3::new(2.0, 1.0, 0.0) / 2f32.sqrt();
        let n = ellipsoid().surface(p, 0).normal.normalize();
        assert_near(n, Vec3::new(1.0, 2.0, 0.0) / 5f32.sqrt(), 1e-6);
        let ray = Ray::new(p + n * 3.0, -n);
        let h = hit(&ray).unwrap();
        assert!((h.t - 3.0).abs() < 1e-5);
    }

    #[test]
    fn ray_from_inside_hits_the_exit() {
        let ray = Ray::new(CENTER, Vec3::new(0.0, 2.0, 0.0));
        let h = hit(&ray).unwrap();
        assert!((h.t - 0.5).abs() < 1e-6);
        let n = ellipsoid().surface(ray.at(h.t), h.part).normal;
        assert!(n.dot(ray.at(h.t) - CENTER) > 0.0);
        // From a point on the surface, outward: no hit; inward: the far side.
        let top = CENTER + Vec3::Y;
        assert_eq!(hit(&Ray::new(top, Vec3::new(0.1, 1.0, 0.0))), None);
        let h = hit(&Ray::new(top, -Vec3::Y)).unwrap();
        assert!((h.t - 2.0).abs() < 1e-5);
    }

    #[test]
    fn tangent_and_missing_rays() {
        let tangent = Ray::new(Vec3::new(-5.0, 3.0, 3.0), Vec3::X);
        let h = hit(&tangent).unwrap();
        assert!((h.t - 6.0).abs() < 1e-3, "{h:?}");
        assert!(
            ellipsoid()
                .surface(tangent.at(h.t), h.part)
                .normal
                .is_finite()
        );
        let above = Ray::new(Vec3::new(-5.0, 3.001, 3.0), Vec3::X);
        let away = Ray::new(Vec3::new(-5.0, 2.0, 3.0), -Vec3::X);
        assert_eq!(hit(&above), None);
        assert_eq!(hit(&away), None);
    }

    #[test]
    fn respects_the_t_range() {
        let e = ellipsoid();
        let ray = Ray::new(Vec3::new(-5.0, 2.0, 3.0), Vec3::X);
        assert_eq!(e.intersect(&ray, 0.0, 4.0), None);
        let h = e.intersect(&ray, 4.0, 10.0).unwrap();
        assert!((h.t - 8.0).abs() < 1e-5);
        assert_eq!(e.intersect(&ray, 8.0, 10.0), None);
    }

    #[test]
    fn texture_coordinates_follow_the_sphere() {
        let e = ellipsoid();
        assert!((e.surface(CENTER + Vec3::Y, 0).uv.y - 1.0).abs() < 1e-6);
        assert!(e.surface(CENTER - Vec3::Y, 0).uv.y.abs() < 1e-6);
        let front = e.surface(CENTER + Vec3::Z * 0.5, 0).uv;
        assert_near(front.extend(0.0), Vec2::new(0.5, 0.5).extend(0.0), 1e-6);
    }

    #[test]
    fn rejects_bad_radii() {
        assert_eq!(
            Ellipsoid::new(Vec3::ZERO, Vec3::new(1.0, -1.0, 1.0)).unwrap_err(),
            "ellipsoid radii must be positive, got [1, -1, 1]"
        );
        assert!(Ellipsoid::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0)).is_err());
        assert!(Ellipsoid::new(Vec3::splat(f32::NAN), Vec3::ONE).is_err());
        assert!(Ellipsoid::new(Vec3::ZERO, Vec3::new(1.0, 1e-39, 1.0)).is_err());
    }

    #[test]
    fn transformed_ellipsoid_in_the_world() {
        // Radii (1, 2, 3) turned 90° about x (+z → −y), moved to z = −10: it reaches 3 along y.
        let e = Ellipsoid::new(Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0)).unwrap();
        let steps = [
            TransformStep::Rotate {
                axis: Vec3::X,
                degrees: 90.0,
            },
            TransformStep::Translate(Vec3::new(0.0, 0.0, -10.0)),
        ];
        let ray = Ray::new(Vec3::new(0.0, 10.0, -10.0), -Vec3::Y);
        let (h, s) = hit_in_world(Shape::Ellipsoid(e), &steps, &ray).unwrap();
        assert!((h.t - 7.0).abs() < 1e-5);
        assert_near(s.point, Vec3::new(0.0, 3.0, -10.0), 1e-5);
        assert_near(s.object_point, Vec3::new(0.0, 0.0, -3.0), 1e-5);
        assert_near(s.normal, Vec3::Y, 1e-5);
    }
}
