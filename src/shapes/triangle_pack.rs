//! Four triangles tested against one ray at once: the watertight test of [`Triangle`] with one
//! triangle per SIMD lane. The vertices are stored coordinate by coordinate
//! (`p[vertex][axis][lane]`), so each step of the test is one instruction for all four. The
//! arithmetic is the single-triangle test's, in the same order, so each lane's `t` and
//! barycentric coordinates are exactly what [`Triangle::intersect_sheared`] gives; the rare
//! lane that lies on an edge in single precision is handed to that test, which decides it in
//! double precision.

use glam::{Vec2, Vec3, Vec4};

use super::{PACK_SIZE, ShearedRay, Triangle, TriangleHit};

/// Up to [`PACK_SIZE`] triangles, with a number per triangle for the caller (the BVH keeps
/// primitive ids there). Unused lanes have NaN vertices, which no ray hits. 160 bytes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub struct TrianglePack {
    /// Coordinate `axis` of vertex `vertex` of the triangle in lane `lane`:
    /// `p[vertex][axis][lane]`.
    pub p: [[[f32; PACK_SIZE]; 3]; 3],
    pub tags: [u32; PACK_SIZE],
}

/// The lanes of a pack that a ray hits, with what each hit needs.
#[derive(Clone, Copy, Debug)]
pub struct PackHits {
    /// Bit k set where the ray hits triangle k within the `t` range.
    pub mask: u32,
    /// Kept in registers rather than arrays (see [`super::LaneHits::t`]).
    pub t: Vec4,
    /// The edge functions of p1 and p2 (the unnormalised barycentric coordinates) and their
    /// sum with p0's, the determinant.
    v: Vec4,
    w: Vec4,
    det: Vec4,
}

impl PackHits {
    /// The hit in lane `k`, which must be in `mask`.
    #[inline(always)]
    pub fn hit(&self, k: usize) -> TriangleHit {
        TriangleHit {
            t: self.t[k],
            bary: Vec2::new(self.v[k], self.w[k]) / self.det[k],
        }
    }
}

impl TrianglePack {
    /// The pack of `triangles` (at most [`PACK_SIZE`]), each with its tag.
    pub fn new(triangles: &[(Triangle, u32)]) -> TrianglePack {
        assert!(triangles.len() <= PACK_SIZE, "a pack holds {PACK_SIZE}");
        let mut pack = TrianglePack {
            p: [[[f32::NAN; PACK_SIZE]; 3]; 3],
            tags: [u32::MAX; PACK_SIZE],
        };
        for (lane, (triangle, tag)) in triangles.iter().enumerate() {
            for (vertex, p) in [triangle.p0, triangle.p1, triangle.p2].iter().enumerate() {
                for axis in 0..3 {
                    pack.p[vertex][axis][lane] = p[axis];
                }
            }
            pack.tags[lane] = *tag;
        }
        pack
    }

    /// The triangle in lane `lane` (its `face` is not kept: 0).
    pub fn triangle(&self, lane: usize) -> Triangle {
        let vertex = |v: usize| Vec3::from(self.p[v].map(|axis| axis[lane]));
        Triangle::new([vertex(0), vertex(1), vertex(2)], 0)
    }

    /// Which triangles `ray` hits with `t` in `(t_min, t_max)`, all four at once.
    #[inline(always)]
    pub fn intersect(&self, ray: &ShearedRay, t_min: f32, t_max: f32) -> PackHits {
        let [kx, ky, kz] = ray.axes;
        let s = ray.shear;
        // A vertex relative to the ray origin, in the permuted axes, then sheared.
        let local = |vertex: &[[f32; PACK_SIZE]; 3]| {
            let coordinate = |k: usize| Vec4::from_array(vertex[k]) - Vec4::splat(ray.origin[k]);
            let (x, y, z) = (coordinate(kx), coordinate(ky), coordinate(kz));
            (x - Vec4::splat(s.x) * z, y - Vec4::splat(s.y) * z, z)
        };
        let ((ax, ay, az), (bx, by, bz), (cx, cy, cz)) =
            (local(&self.p[0]), local(&self.p[1]), local(&self.p[2]));
        // Edge functions: each is twice the signed area seen from the ray.
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let zero = Vec4::ZERO;
        let on_edge = (u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero)).bitmask();
        let outside = (u.cmplt(zero) | v.cmplt(zero) | w.cmplt(zero))
            & (u.cmpgt(zero) | v.cmpgt(zero) | w.cmpgt(zero));
        let det = u + v + w;
        let t_scaled = Vec4::splat(s.z) * (u * az + v * bz + w * cz);
        let t = t_scaled / det;
        let hit =
            !outside & det.cmpne(zero) & t.cmpgt(Vec4::splat(t_min)) & t.cmplt(Vec4::splat(t_max));
        let mut hits = PackHits {
            mask: hit.bitmask() & !on_edge,
            t,
            v,
            w,
            det,
        };
        if on_edge != 0 {
            self.decide_edges(ray, t_min, t_max, on_edge, &mut hits);
        }
        hits
    }

    /// The lanes `on_edge`, where an edge function is exactly zero in single precision,
    /// decided one by one by [`Triangle::intersect_sheared`].
    #[cold]
    #[inline(never)]
    fn decide_edges(
        &self,
        ray: &ShearedRay,
        t_min: f32,
        t_max: f32,
        on_edge: u32,
        hits: &mut PackHits,
    ) {
        for k in (0..PACK_SIZE).filter(|k| on_edge >> k & 1 == 1) {
            if let Some(hit) = self.triangle(k).intersect_sheared(ray, t_min, t_max) {
                hits.mask |= 1 << k;
                hits.t[k] = hit.t;
                // Barycentric coordinates that divide back to the single test's exactly.
                (hits.v[k], hits.w[k], hits.det[k]) = (hit.bary.x, hit.bary.y, 1.0);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::Ray;
    use crate::sampling::random;

    /// Four triangles sharing edges and a vertex, one of them degenerate.
    fn fan() -> [Triangle; 4] {
        let (o, x, y, xy) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
        [
            Triangle::new([o, x, y], 0),
            Triangle::new([x, xy, y], 1),
            Triangle::new([o, y, Vec3::new(-1.0, 0.5, 0.3)], 2),
            Triangle::new([o, x, x * 2.0], 3),
        ]
    }

    fn assert_same_as_one_by_one(triangles: &[Triangle], ray: &Ray, t_max: f32) -> u32 {
        let tagged: Vec<(Triangle, u32)> = triangles.iter().map(|&t| (t, t.face)).collect();
        let pack = TrianglePack::new(&tagged);
        let sheared = ShearedRay::new(ray);
        let hits = pack.intersect(&sheared, 0.0, t_max);
        for k in 0..PACK_SIZE {
            let one = triangles
                .get(k)
                .and_then(|t| t.intersect_sheared(&sheared, 0.0, t_max));
            let packed = (hits.mask >> k & 1 == 1).then(|| hits.hit(k));
            assert_eq!(packed, one, "lane {k}, {ray:?}");
        }
        hits.mask
    }

    #[test]
    fn four_at_once_is_exactly_one_at_a_time() {
        let mut hit = 0;
        for i in 0..20_000 {
            let in_range = |dim: u32| -1.0 + 3.0 * random(i, dim);
            let origin = Vec3::new(in_range(0), in_range(1), 2.0);
            let target = Vec3::new(in_range(2), in_range(3), 0.0);
            let ray = Ray::new(origin, target - origin);
            hit += assert_same_as_one_by_one(&fan(), &ray, f32::INFINITY).count_ones();
        }
        assert!(hit > 2000, "{hit} hits");
    }

    #[test]
    fn edges_vertices_and_partial_packs() {
        // Straight down through the shared edge, the shared vertex and a corner.
        for (x, y) in [(0.5, 0.5), (0.0, 0.0), (1.0, 0.0), (0.0, 0.25), (0.25, 0.0)] {
            let ray = Ray::new(Vec3::new(x, y, 2.0), -Vec3::Z);
            let mask = assert_same_as_one_by_one(&fan(), &ray, f32::INFINITY);
            assert_ne!(mask, 0, "({x}, {y}) is on the fan");
            assert_same_as_one_by_one(&fan()[..1], &ray, f32::INFINITY);
            assert_eq!(assert_same_as_one_by_one(&fan(), &ray, 1.5), 0);
        }
        assert_eq!(
            assert_same_as_one_by_one(&[], &Ray::new(Vec3::Z, -Vec3::Z), 9.0),
            0
        );
    }
}
