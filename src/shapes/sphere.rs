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
            let (t0, t1) = (q / a, c / q);
            (t0.min(t1), t0.max(t1))
        };
        let t = first_root_in(roots, t_min, t_max)?;
        Some(ShapeHit { t, part: 0 })
    }

    /// Spherical mapping: `u` around the vertical axis, `v` from the south pole (0) to the
    /// north pole (1).
    pub fn surface(&self, p: Vec3, _part: u32) -> LocalSurface {
        let n = (p - self.center) / self.radius;
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
