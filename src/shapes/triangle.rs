//! Triangles of a mesh, stored in world space in the form the Möller–Trumbore test wants.

use glam::{Vec2, Vec3};

use crate::aabb::Aabb;
use crate::ray::Ray;

/// One triangle `p0, p0 + e1, p0 + e2`, with the mesh and face it came from (for normals, texture
/// coordinates and material). 44 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub p0: Vec3,
    pub e1: Vec3,
    pub e2: Vec3,
    pub mesh: u32,
    pub face: u32,
}

/// Where a ray meets a triangle: `t` and the barycentric coordinates of p1 and p2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    pub t: f32,
    pub bary: Vec2,
}

impl Triangle {
    pub fn new(p: [Vec3; 3], mesh: u32, face: u32) -> Self {
        Triangle {
            p0: p[0],
            e1: p[1] - p[0],
            e2: p[2] - p[0],
            mesh,
            face,
        }
    }

    /// Möller–Trumbore. Edges are inclusive (`b ≥ 0`, `b1 + b2 ≤ 1`), so a ray through the
    /// shared edge of two triangles hits at least one of them: no cracks.
    #[inline(always)]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<TriangleHit> {
        let pvec = ray.dir.cross(self.e2);
        let det = self.e1.dot(pvec);
        if det == 0.0 {
            return None; // ray parallel to the triangle's plane, or degenerate triangle
        }
        let inv_det = 1.0 / det;
        let tvec = ray.origin - self.p0;
        let b1 = tvec.dot(pvec) * inv_det;
        if !(0.0..=1.0).contains(&b1) {
            return None;
        }
        let qvec = tvec.cross(self.e1);
        let b2 = ray.dir.dot(qvec) * inv_det;
        if b2 < 0.0 || b1 + b2 > 1.0 {
            return None;
        }
        let t = self.e2.dot(qvec) * inv_det;
        (t > t_min && t < t_max).then_some(TriangleHit {
            t,
            bary: Vec2::new(b1, b2),
        })
    }

    /// Unit geometric normal, by the right-hand rule on p0, p1, p2 (counter-clockwise = front).
    pub fn normal(&self) -> Vec3 {
        self.e1.cross(self.e2).normalize_or_zero()
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points([self.p0, self.p0 + self.e1, self.p0 + self.e2])
    }

    /// Twice the area; zero for a degenerate triangle.
    pub fn double_area(&self) -> f32 {
        self.e1.cross(self.e2).length()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle() -> Triangle {
        Triangle::new([Vec3::ZERO, Vec3::X, Vec3::Y], 0, 0)
    }

    fn down_at(x: f32, y: f32) -> Ray {
        Ray::new(Vec3::new(x, y, 2.0), Vec3::new(0.0, 0.0, -4.0))
    }

    #[test]
    fn hit_inside() {
        let h = triangle()
            .intersect(&down_at(0.25, 0.5), 0.0, f32::INFINITY)
            .unwrap();
        assert_eq!(
            h,
            TriangleHit {
                t: 0.5,
                bary: Vec2::new(0.25, 0.5)
            }
        );
        assert_eq!(triangle().normal(), Vec3::Z);
        let from_below = Ray::new(Vec3::new(0.1, 0.1, -1.0), Vec3::Z);
        assert_eq!(triangle().intersect(&from_below, 0.0, 5.0).unwrap().t, 1.0);
    }

    #[test]
    fn edges_are_inclusive() {
        for (x, y) in [(0.5, 0.5), (0.5, 0.0), (0.0, 0.5), (0.0, 0.0)] {
            assert!(
                triangle()
                    .intersect(&down_at(x, y), 0.0, f32::INFINITY)
                    .is_some(),
                "({x}, {y})"
            );
        }
    }

    #[test]
    fn misses() {
        for (x, y) in [(0.6, 0.6), (-0.01, 0.5), (0.5, -0.01)] {
            assert_eq!(
                triangle().intersect(&down_at(x, y), 0.0, f32::INFINITY),
                None
            );
        }
        let parallel = Ray::new(Vec3::new(0.2, 0.2, 0.0), Vec3::X);
        assert_eq!(triangle().intersect(&parallel, 0.0, f32::INFINITY), None);
    }

    #[test]
    fn respects_the_t_range() {
        let ray = down_at(0.2, 0.2);
        assert_eq!(triangle().intersect(&ray, 0.0, 0.5), None);
        assert_eq!(triangle().intersect(&ray, 0.5, 1.0), None);
        assert!(triangle().intersect(&ray, 0.4, 0.6).is_some());
    }

    #[test]
    fn bounds_and_area() {
        let t = Triangle::new([Vec3::ZERO, Vec3::new(2.0, 0.0, 1.0), Vec3::Y], 3, 7);
        assert_eq!(t.bounds(), Aabb::new(Vec3::ZERO, Vec3::new(2.0, 1.0, 1.0)));
        assert!((t.double_area() - 5f32.sqrt()).abs() < 1e-6);
        let degenerate = Triangle::new([Vec3::ZERO, Vec3::X, Vec3::X * 2.0], 0, 0);
        assert_eq!(degenerate.double_area(), 0.0);
        assert_eq!(degenerate.normal(), Vec3::ZERO);
    }
}
