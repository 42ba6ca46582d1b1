//! Infinite planes, given by a point and a normal. They have no bounding box, so the BVH keeps
//! them in a list of their own.

use glam::{Vec2, Vec3};

use super::{Crossings, LocalSurface, ShapeHit};
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
    /// As a CSG operand the plane is the half-space behind it (the side its normal points
    /// away from), as in POV-Ray: the ray is inside from where it crosses the plane going
    /// backwards, or up to where it crosses going forwards; everywhere or nowhere when it runs
    /// parallel.
    pub fn crossings(&self, ray: &Ray) -> Crossings {
        let denom = self.normal.dot(ray.dir);
        let height = self.normal.dot(ray.origin - self.point);
        let t = -height / denom;
        let (enter, exit) = if !t.is_finite() {
            if height < 0.0 {
                (f32::NEG_INFINITY, f32::INFINITY)
            } else {
                return Crossings::new();
            }
        } else if denom < 0.0 {
            (t, f32::INFINITY)
        } else {
            (f32::NEG_INFINITY, t)
        };
        [enter, exit]
            .into_iter()
            .map(|t| ShapeHit { t, part: 0 })
            .collect()
    }

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    /// The plane y = 1, facing up.
    fn floor() -> Plane {
        Plane {
            point: Vec3::Y,
            normal: Vec3::Y,
        }
    }

    #[test]
    fn hit_from_either_side() {
        let down = Ray::new(Vec3::new(2.0, 5.0, 3.0), Vec3::new(0.0, -2.0, 0.0));
        let h = floor().intersect(&down, 0.0, f32::INFINITY).unwrap();
        assert_eq!(h, ShapeHit { t: 2.0, part: 0 });
        assert_eq!(down.at(h.t), Vec3::new(2.0, 1.0, 3.0));
        let s = floor().surface(down.at(h.t), h.part);
        assert_eq!(s.normal, Vec3::Y);
        // u along +x, v along −z.
        assert_near(s.uv.extend(0.0), Vec3::new(2.0, -3.0, 0.0), 1e-6);
        let up = Ray::new(Vec3::new(0.0, -1.0, 0.0), Vec3::new(1.0, 4.0, 0.0));
        assert_eq!(floor().intersect(&up, 0.0, f32::INFINITY).unwrap().t, 0.5);
    }

    #[test]
    fn misses_parallel_and_receding_rays() {
        let parallel = Ray::new(Vec3::new(0.0, 2.0, 0.0), Vec3::X);
        let receding = Ray::new(Vec3::new(0.0, 2.0, 0.0), Vec3::Y);
        let in_plane = Ray::new(Vec3::Y, Vec3::Z);
        for ray in [parallel, receding, in_plane] {
            assert_eq!(
                floor().intersect(&ray, 1e-4, f32::INFINITY),
                None,
                "{ray:?}"
            );
        }
    }

    #[test]
    fn respects_the_t_range() {
        let down = Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y);
        assert_eq!(floor().intersect(&down, 0.0, 4.0), None);
        assert_eq!(floor().intersect(&down, 4.0, 10.0), None);
        assert!(floor().intersect(&down, 3.9, 4.1).is_some());
    }

    #[test]
    fn tangent_axes_are_orthonormal_and_span_the_plane() {
        for n in [
            Vec3::Y,
            -Vec3::Y,
            Vec3::X,
            Vec3::new(1.0, 2.0, -3.0).normalize(),
        ] {
            let (s, t) = tangent_axes(n);
            assert!((s.length() - 1.0).abs() < 1e-6 && (t.length() - 1.0).abs() < 1e-6);
            assert!(s.dot(t).abs() < 1e-6 && s.dot(n).abs() < 1e-6 && t.dot(n).abs() < 1e-6);
        }
    }

    #[test]
    fn turned_plane_in_the_world() {
        // The floor turned 90° about z (+y → −x): the plane x = −1 facing −x.
        let steps = [TransformStep::Rotate {
            axis: Vec3::Z,
            degrees: 90.0,
        }];
        let ray = Ray::new(Vec3::new(5.0, 0.5, 0.0), -Vec3::X);
        let (h, s) = hit_in_world(Shape::Plane(floor()), &steps, &ray).unwrap();
        assert!((h.t - 6.0).abs() < 1e-5);
        assert_near(s.point, Vec3::new(-1.0, 0.5, 0.0), 1e-5);
        assert_near(s.normal, -Vec3::X, 1e-5);
    }
}
