//! The ray–box test of the traversal: the slab test for one box, and for a node's four child
//! boxes at once, one per SIMD lane.

use glam::{Vec3, Vec4};

use super::Node;
use crate::ray::Ray;

/// A ray prepared for box tests: its origin and inverse direction. 24 bytes, so that a packet's
/// 64 of them stay small.
pub(super) struct RayBoxTest {
    origin: Vec3,
    inv_dir: Vec3,
}

impl RayBoxTest {
    pub(super) fn new(ray: &Ray) -> Self {
        let inv_dir = ray.dir.recip();
        RayBoxTest {
            origin: ray.origin,
            inv_dir,
        }
    }

    /// Entry distance into the node's box within `[t_min, t_max]`, or +∞ for a miss (the slab
    /// test: the ray is inside the box where it is inside all three slabs).
    #[inline(always)]
    pub(super) fn enter(&self, node: &Node, t_min: f32, t_max: f32) -> f32 {
        let t0 = (Vec3::from(node.min) - self.origin) * self.inv_dir;
        let t1 = (Vec3::from(node.max) - self.origin) * self.inv_dir;
        let near = t0.min(t1).max_element().max(t_min);
        let far = t0.max(t1).min_element().min(t_max);
        if near <= far { near } else { f32::INFINITY }
    }

    /// [`Self::enter`] for four boxes at once, one per SIMD lane, with the same arithmetic in
    /// the same order, so each lane's answer is exactly the one-box answer: the entry
    /// distances, and a bit mask of the boxes entered (bit k for box k).
    #[inline(always)]
    pub(super) fn enter4(&self, nodes: &[Node], t_min: f32, t_max: f32) -> (Vec4, u32) {
        let (mins, maxs) = boxes_by_axis(nodes);
        let slab = |axis: usize| {
            let (lo, hi) = (mins[axis], maxs[axis]);
            // The ray's component copied into all four lanes.
            let (origin, inv_dir) = (
                Vec4::splat(self.origin[axis]),
                Vec4::splat(self.inv_dir[axis]),
            );
            let t0 = (lo - origin) * inv_dir;
            let t1 = (hi - origin) * inv_dir;
            (t0.min(t1), t0.max(t1))
        };
        let ((near_x, far_x), (near_y, far_y), (near_z, far_z)) = (slab(0), slab(1), slab(2));
        let near = near_x.max(near_y).max(near_z).max(Vec4::splat(t_min));
        let far = far_x.min(far_y).min(far_z).min(Vec4::splat(t_max));
        (near, near.cmple(far).bitmask())
    }
}

/// The boxes of four nodes rearranged for [`RayBoxTest::enter4`]: their min and max x in one
/// vector, y in another, z in a third. Each node's `min, first` and `max, count` are 16 bytes
/// each, loaded whole; two 4×4 transposes (the fourth row, `first` and `count`, is dropped) put
/// the components in place.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn boxes_by_axis(nodes: &[Node]) -> ([Vec4; 3], [Vec4; 3]) {
    use std::arch::x86_64::{
        __m128, _mm_movehl_ps, _mm_movelh_ps, _mm_unpackhi_ps, _mm_unpacklo_ps,
    };
    let transpose = |rows: [__m128; 4]| {
        // SAFETY: these shuffles need SSE, which every x86_64 processor has.
        unsafe {
            let xy01 = _mm_unpacklo_ps(rows[0], rows[1]);
            let xy23 = _mm_unpacklo_ps(rows[2], rows[3]);
            let zw01 = _mm_unpackhi_ps(rows[0], rows[1]);
            let zw23 = _mm_unpackhi_ps(rows[2], rows[3]);
            [
                Vec4::from(_mm_movelh_ps(xy01, xy23)),
                Vec4::from(_mm_movehl_ps(xy23, xy01)),
                Vec4::from(_mm_movelh_ps(zw01, zw23)),
            ]
        }
    };
    let low = |n: &Node| {
        __m128::from(Vec4::new(
            n.min[0],
            n.min[1],
            n.min[2],
            f32::from_bits(n.first),
        ))
    };
    let high = |n: &Node| {
        __m128::from(Vec4::new(
            n.max[0],
            n.max[1],
            n.max[2],
            f32::from_bits(n.count),
        ))
    };
    let n = [&nodes[0], &nodes[1], &nodes[2], &nodes[3]];
    (transpose(n.map(low)), transpose(n.map(high)))
}

/// The boxes of four nodes rearranged for [`RayBoxTest::enter4`], gathered component by
/// component where there is no x86 shuffle to do it.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn boxes_by_axis(nodes: &[Node]) -> ([Vec4; 3], [Vec4; 3]) {
    let n = [&nodes[0], &nodes[1], &nodes[2], &nodes[3]];
    let lanes = |axis: usize, corner: fn(&Node) -> [f32; 3]| {
        Vec4::from_array(n.map(|node| corner(node)[axis]))
    };
    (
        [0, 1, 2].map(|axis| lanes(axis, |node| node.min)),
        [0, 1, 2].map(|axis| lanes(axis, |node| node.max)),
    )
}
