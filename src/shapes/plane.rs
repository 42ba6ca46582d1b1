//! Infinite planes, given by a point and a normal. They have no bounding box, so the BVH keeps
//! them in a list of their own.

use glam::{Vec2, Vec3};

use super::{LocalSurface, ShapeHit};
use crate::ray::Ray;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub point: Vec3,
    /// Unit normal: the side it points to is the plane's front.
    pub normal: Vec3,
}

impl Plane {
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let denom = self.normal.dot(ray.dir);
        if denom == 0.0 {
            return None; // parallel to the plane
        }
        let t = self.normal.dot(self.point - ray.origin) / denom;
        (t > t_min && t < t_max).then_some(ShapeHit { t, part: 0 })
    }

    /// Planar mapping: distances along two axes lying in the plane, one unit of texture space
    /// per unit of length.
    pub fn surface(&self, p: Vec3, _part: u32) -> LocalSurface {
        let (s, t) = tangent_axes(self.normal);
        let d = p - self.point;
        LocalSurface {
            normal: self.normal,
            uv: Vec2::new(d.dot(s), d.dot(t)),
        }
    }
}

/// Two unit axes that span the plane orthogonal to the unit vector `n`. For a horizontal plane
/// (n = +Y) they are +X and −Z, so texture `u` runs along x and `v` along −z.
pub fn tangent_axes(n: Vec3) -> (Vec3, Vec3) {
    let helper = if n.y.abs() < 0.999 { Vec3::Y } else { Vec3::Z };
    let s = helper.cross(n).normalize();
    let s = if n.y.abs() >= 0.999 {
        -s * n.y.signum()
    } else {
        s
    };
    let t = n.cross(s);
    (s, t)
}
