//! Four small polygons tested against one ray at once: [`Polygon::intersect`] with one polygon
//! per SIMD lane. Scenes in NFF are made of such polygons (the SPD mountain's 8,192 triangles,
//! the gears' 9,217 quads); tested one object at a time, each pays a dispatch on its shape and
//! a walk over its edges. A pack holds polygons placed directly in the world with at most
//! [`MAX_PACKED_EDGES`] edges that are not horizontal in their projection. Every step is the
//! single test's arithmetic in the same order, so each lane's answer is exactly
//! [`Polygon::intersect`]'s.

use glam::{BVec4A, Vec4};

use super::{LaneHits, ObjectPack, PACK_SIZE, Polygon};
use crate::ray::Ray;

/// Most edges a packed polygon may have that can cross a horizontal line of its projection:
/// enough for triangles and quads.
pub const MAX_PACKED_EDGES: usize = 4;

/// Up to [`PACK_SIZE`] polygons, coordinate by coordinate (`normal[axis][lane]`), each with a
/// number for the caller (the BVH keeps primitive ids there). Unused lanes have a NaN normal,
/// which no ray hits, and unused edges are horizontal at height 0, which no point crosses.
/// 464 bytes.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
pub struct PolygonPack {
    normal: [[f32; PACK_SIZE]; 3],
    plane_offset: [f32; PACK_SIZE],
    /// The world axis (0, 1 or 2, as a float) that each coordinate of the projection keeps.
    kept_axes: [[f32; PACK_SIZE]; 2],
    projected_min: [[f32; PACK_SIZE]; 2],
    projected_max: [[f32; PACK_SIZE]; 2],
    /// Edge `e` of each lane: start x, start y, end y, dx/dy (`edges[e][field][lane]`).
    edges: [[[f32; PACK_SIZE]; 4]; MAX_PACKED_EDGES],
    pub tags: [u32; PACK_SIZE],
}

impl PolygonPack {
    /// Whether `polygon` fits in a lane (it must also be placed directly in the world).
    pub fn fits(polygon: &Polygon) -> bool {
        polygon
            .crossable_edges()
            .is_some_and(|edges| edges.len() <= MAX_PACKED_EDGES)
    }

    /// The pack of `polygons` (at most [`PACK_SIZE`], each one that [`Self::fits`]), each with
    /// its tag.
    pub fn new(polygons: &[(&Polygon, u32)]) -> PolygonPack {
        assert!(polygons.len() <= PACK_SIZE, "a pack holds {PACK_SIZE}");
        let mut pack = PolygonPack {
            normal: [[f32::NAN; PACK_SIZE]; 3],
            plane_offset: [0.0; PACK_SIZE],
            kept_axes: [[0.0; PACK_SIZE]; 2],
            projected_min: [[0.0; PACK_SIZE]; 2],
            projected_max: [[0.0; PACK_SIZE]; 2],
            edges: [[[0.0; PACK_SIZE]; 4]; MAX_PACKED_EDGES],
            tags: [u32::MAX; PACK_SIZE],
        };
        for (lane, &(polygon, tag)) in polygons.iter().enumerate() {
            let edges = polygon
                .crossable_edges()
                .filter(|edges| edges.len() <= MAX_PACKED_EDGES)
                .expect("a packed polygon has few edges");
            for axis in 0..3 {
                pack.normal[axis][lane] = polygon.normal[axis];
            }
            pack.plane_offset[lane] = polygon.plane_offset;
            for c in 0..2 {
                pack.kept_axes[c][lane] = polygon.kept_axes[c] as f32;
                pack.projected_min[c][lane] = polygon.projected_min[c];
                pack.projected_max[c][lane] = polygon.projected_max[c];
            }
            for (e, edge) in edges.iter().enumerate() {
                let fields = [edge.start.x, edge.start.y, edge.end_y, edge.dx_dy];
                for (f, value) in fields.into_iter().enumerate() {
                    pack.edges[e][f][lane] = value;
                }
            }
            pack.tags[lane] = tag;
        }
        pack
    }
}

impl ObjectPack for PolygonPack {
    /// Which polygons `ray` hits with `t` in `(t_min, t_max)`, all four at once.
    #[inline(always)]
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> LaneHits {
        let o = ray.origin.to_array().map(Vec4::splat);
        let d = ray.dir.to_array().map(Vec4::splat);
        let n = self.normal.map(Vec4::from);
        // The plane: as `Polygon::intersect`, dot products summed x, y, z.
        let denom = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
        let t = (Vec4::from(self.plane_offset) - (n[0] * o[0] + n[1] * o[1] + n[2] * o[2])) / denom;
        let in_range =
            denom.cmpne(Vec4::ZERO) & t.cmpgt(Vec4::splat(t_min)) & t.cmplt(Vec4::splat(t_max));
        if !in_range.any() {
            return LaneHits { mask: 0, t };
        }
        // The hit point, projected onto the two axes each polygon keeps.
        let p = [0, 1, 2].map(|k| o[k] + d[k] * t);
        let project = |c: usize| {
            let axis = Vec4::from(self.kept_axes[c]);
            let from_y_or_z = Vec4::select(axis.cmpeq(Vec4::ONE), p[1], p[2]);
            Vec4::select(axis.cmpeq(Vec4::ZERO), p[0], from_y_or_z)
        };
        let (qx, qy) = (project(0), project(1));
        let outside_box = qx.cmplt(Vec4::from(self.projected_min[0]))
            | qy.cmplt(Vec4::from(self.projected_min[1]))
            | qx.cmpgt(Vec4::from(self.projected_max[0]))
            | qy.cmpgt(Vec4::from(self.projected_max[1]));
        let candidates = in_range & !outside_box;
        if !candidates.any() {
            return LaneHits { mask: 0, t };
        }
        // The crossing number, as `ProjectedEdge::crossed_from`.
        let mut inside = BVec4A::splat(false);
        for edge in &self.edges {
            let [start_x, start_y, end_y, dx_dy] = edge.map(Vec4::from);
            let straddles = start_y.cmpgt(qy) ^ end_y.cmpgt(qy);
            let right_of_q = qx.cmplt(start_x + (qy - start_y) * dx_dy);
            inside ^= straddles & right_of_q;
        }
        LaneHits {
            mask: (candidates & inside).bitmask(),
            t,
        }
    }

    fn tags(&self) -> &[u32; PACK_SIZE] {
        &self.tags
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::*;
    use crate::shapes::test_support::{lane_ts, t_bits};

    /// A polygon from integer corners on a grid of 1/64, offset and turned by `tilt` so that
    /// its plane is oblique.
    fn polygon(corners: &[(i32, i32)], tilt: i32, lift: i32) -> Option<Polygon> {
        let vertices = corners
            .iter()
            .map(|&(x, y)| {
                let (x, y) = (x as f32 / 64.0, y as f32 / 64.0);
                Vec3::new(x, y, lift as f32 / 16.0 + tilt as f32 / 64.0 * (x - y))
            })
            .collect();
        Polygon::new(vertices).ok()
    }

    #[test]
    fn polygons_with_up_to_four_slanted_edges_fit() {
        let grid = |corners: &[(i32, i32)]| {
            let corners: Vec<_> = corners.iter().map(|&(x, y)| (x * 16, y * 16)).collect();
            polygon(&corners, 3, 0).unwrap()
        };
        let triangle = grid(&[(0, 0), (4, 0), (0, 4)]);
        let quad = grid(&[(0, 0), (4, 1), (5, 4), (1, 3)]);
        // Two of its six edges are horizontal in the projection: no line crosses them.
        let flat_hexagon = grid(&[(2, 0), (4, 0), (6, 2), (4, 4), (2, 4), (0, 2)]);
        let hexagon = grid(&[(0, 1), (2, 0), (4, 1), (5, 3), (3, 4), (1, 3)]);
        assert!(PolygonPack::fits(&triangle));
        assert!(PolygonPack::fits(&quad));
        assert!(PolygonPack::fits(&flat_hexagon));
        assert!(!PolygonPack::fits(&hexagon));
    }

    proptest! {
        /// Random triangles and quads, some concave, in tilted planes, against random rays,
        /// many through vertices: each lane answers exactly as `Polygon::intersect`.
        #[test]
        fn each_lane_answers_as_the_single_polygon_test(
            shapes in proptest::collection::vec(
                (proptest::collection::vec((-64i32..64, -64i32..64), 3..=4), -64i32..64, -4i32..4),
                1..=PACK_SIZE,
            ),
            origin in (-128i32..128, -128i32..128, -128i32..128),
            target in (-80i32..80, -80i32..80, -64i32..64),
            through_vertex in proptest::option::of((0usize..4, 0usize..4)),
            t_max in proptest::option::of(1u32..64),
        ) {
            let polygons: Vec<Polygon> = shapes
                .iter()
                .filter_map(|(corners, tilt, lift)| polygon(corners, *tilt, *lift))
                .filter(PolygonPack::fits)
                .collect();
            prop_assume!(!polygons.is_empty());
            let tagged: Vec<(&Polygon, u32)> =
                polygons.iter().zip(10..).collect();
            let pack = PolygonPack::new(&tagged);
            let origin = Vec3::new(origin.0 as f32, origin.1 as f32, origin.2 as f32) / 16.0;
            let mut target = Vec3::new(target.0 as f32, target.1 as f32, target.2 as f32) / 64.0;
            if let Some((p, c)) = through_vertex {
                let (corners, tilt, lift) = &shapes[p % shapes.len()];
                let (x, y) = corners[c % corners.len()];
                let (x, y) = (x as f32 / 64.0, y as f32 / 64.0);
                target = Vec3::new(x, y, *lift as f32 / 16.0 + *tilt as f32 / 64.0 * (x - y));
            }
            let ray = Ray::new(origin, target - origin);
            let t_max = t_max.map_or(f32::INFINITY, |t| t as f32 / 16.0);
            let hits = pack.intersect(&ray, 1e-4, t_max);
            let singles = polygons.iter().map(|p| t_bits(p.intersect(&ray, 1e-4, t_max)));
            prop_assert_eq!(lane_ts(&hits, polygons.len()), singles.collect::<Vec<_>>());
        }
    }
}
