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
