//! Triangles of a mesh, stored in world space, and the watertight ray–triangle test of Woop,
//! Benthin and Wald (JCGT 2013): rays through the shared edge or vertex of two triangles never
//! slip between them.

use glam::{DVec3, Vec2, Vec3};

use crate::aabb::Aabb;
use crate::ray::Ray;

/// One triangle with the face of its mesh it came from (for normals and texture coordinates;
/// [`crate::primitive::Geometry`] knows which mesh). 40 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    pub p0: Vec3,
    pub p1: Vec3,
    pub p2: Vec3,
    pub face: u32,
}

/// Where a ray meets a triangle: `t` and the barycentric coordinates of p1 and p2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    pub t: f32,
    pub bary: Vec2,
}

/// A ray prepared once for many triangle tests: the axes permuted so that the direction's
/// largest component is z, and the shear that turns the direction into +z. In that space the
/// test is 2D and every edge function is computed the same way for both triangles sharing it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShearedRay {
    pub(super) origin: Vec3,
    /// The permuted axes (x, y, z).
    pub(super) axes: [usize; 3],
    /// `(dx/dz, dy/dz, 1/dz)` in permuted axes: a point's sheared (x, y) is
    /// `(x − shear.x·z, y − shear.y·z)`, which puts the ray on the z axis.
    pub(super) shear: Vec3,
}

impl ShearedRay {
    pub fn new(ray: &Ray) -> Self {
        let d = ray.dir;
        let kz = d.abs().max_position();
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky); // keep the winding
        }
        ShearedRay {
            origin: ray.origin,
            axes: [kx, ky, kz],
            shear: Vec3::new(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]),
        }
    }

    /// A vertex relative to the ray origin, permuted: (x, y) before the shear, and z.
    #[inline(always)]
    fn local(&self, p: Vec3) -> Vec3 {
        let a = p - self.origin;
        let [kx, ky, kz] = self.axes;
        Vec3::new(a[kx], a[ky], a[kz])
    }
}

impl Triangle {
    pub fn new(p: [Vec3; 3], face: u32) -> Self {
        Triangle {
            p0: p[0],
            p1: p[1],
            p2: p[2],
            face,
        }
    }

    /// The watertight test for a single ray.
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<TriangleHit> {
        self.intersect_sheared(&ShearedRay::new(ray), t_min, t_max)
    }

    /// The watertight test with the ray's preparation done once outside. Edges and vertices are
    /// inclusive: a ray through a shared edge hits at least one of the triangles.
    #[inline(always)]
    pub fn intersect_sheared(
        &self,
        ray: &ShearedRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<TriangleHit> {
        let (a, b, c) = (ray.local(self.p0), ray.local(self.p1), ray.local(self.p2));
        let s = ray.shear;
        let (ax, ay) = (a.x - s.x * a.z, a.y - s.y * a.z);
        let (bx, by) = (b.x - s.x * b.z, b.y - s.y * b.z);
        let (cx, cy) = (c.x - s.x * c.z, c.y - s.y * c.z);
        // Edge functions: each is twice the signed area seen from the ray.
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || v == 0.0 || w == 0.0 {
            // On an edge in single precision: decide in double, as both neighbours will.
            let edge = |px: f32, py: f32, qx: f32, qy: f32| {
                (px as f64 * qy as f64 - py as f64 * qx as f64) as f32
            };
            u = edge(cx, cy, bx, by);
            v = edge(ax, ay, cx, cy);
            w = edge(bx, by, ax, ay);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None; // seen edge-on, or a degenerate triangle
        }
        let t_scaled = s.z * (u * a.z + v * b.z + w * c.z);
        let t = t_scaled / det;
        if !(t > t_min && t < t_max) {
            return None;
        }
        Some(TriangleHit {
            t,
            bary: Vec2::new(v, w) / det,
        })
    }

    /// Unit geometric normal, by the right-hand rule on p0, p1, p2 (counter-clockwise = front).
    pub fn normal(&self) -> Vec3 {
        (self.p1 - self.p0)
            .cross(self.p2 - self.p0)
            .normalize_or_zero()
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points([self.p0, self.p1, self.p2])
    }

    /// Twice the area, computed in double precision; zero for a degenerate triangle.
    pub fn double_area(&self) -> f32 {
        let (p0, p1, p2) = (self.p0.as_dvec3(), self.p1.as_dvec3(), self.p2.as_dvec3());
        let n: DVec3 = (p1 - p0).cross(p2 - p0);
        n.length() as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn triangle() -> Triangle {
        Triangle::new([Vec3::ZERO, Vec3::X, Vec3::Y], 0)
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
        let t = Triangle::new([Vec3::ZERO, Vec3::new(2.0, 0.0, 1.0), Vec3::Y], 7);
        assert_eq!(t.bounds(), Aabb::new(Vec3::ZERO, Vec3::new(2.0, 1.0, 1.0)));
        assert!((t.double_area() - 5f32.sqrt()).abs() < 1e-6);
        let degenerate = Triangle::new([Vec3::ZERO, Vec3::X, Vec3::X * 2.0], 0);
        assert_eq!(degenerate.double_area(), 0.0);
        assert_eq!(degenerate.normal(), Vec3::ZERO);
    }
}
