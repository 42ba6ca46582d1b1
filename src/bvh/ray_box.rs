//! The ray–box test of the traversal: the slab test ([`Aabb::entry`]) for one box, and the
//! same test for a node's four child boxes at once, one per SIMD lane.

use glam::{Vec3, Vec4};

use super::Node;
use crate::aabb::Aabb;
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

    /// Entry distance into the node's box within `[t_min, t_max]`, or +∞ for a miss: the slab
    /// test of [`Aabb::entry`].
    #[inline(always)]
    pub(super) fn enter(&self, node: &Node, t_min: f32, t_max: f32) -> f32 {
        Aabb::new(node.min.into(), node.max.into())
            .entry(self.origin, self.inv_dir, t_min, t_max)
            .unwrap_or(f32::INFINITY)
    }

    /// [`Self::enter`] for four boxes at once, one per SIMD lane, with the same arithmetic in
    /// the same order, so each lane's answer is exactly the one-box answer: the entry
    /// distances, and a bit mask of the boxes entered (bit k for box k). It is written out
    /// rather than built on [`Aabb::slabs`] because it runs the other way round: that goes
    /// through one box's three axes, this through one axis of four boxes at a time (the hot
    /// loop of the traversal, where the four boxes' coordinates are rearranged into lanes once).
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn four_boxes_at_once_answer_as_one_box_at_a_time() {
        let node = |min: [f32; 3], max: [f32; 3]| Node {
            min,
            first: 0,
            max,
            count: 1,
        };
        let nodes = [
            node([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
            node([2.0, -1.0, 0.0], [3.0, 0.0, 1.0]),
            node([-1.0, -1.0, -1.0], [-0.5, 5.0, 2.0]),
            node([0.0, 1.0, 0.0], [1.0, 2.0, 1.0]),
        ];
        let rays = [
            Ray::new(Vec3::new(-5.0, 0.5, 0.5), Vec3::X),
            // From inside the first box, up into the fourth.
            Ray::new(Vec3::splat(0.5), Vec3::Y),
            Ray::new(Vec3::new(2.5, -5.0, 0.5), Vec3::Y),
            Ray::new(Vec3::splat(-5.0), Vec3::ONE),
            // In the plane y = 0 of the first two boxes' faces.
            Ray::new(Vec3::new(-5.0, 0.0, 0.5), Vec3::X),
            Ray::new(Vec3::new(0.5, 1.5, 5.0), -Vec3::Z),
            Ray::new(Vec3::new(9.0, 9.0, 9.0), Vec3::X),
        ];
        let mut entered = 0;
        for ray in rays {
            let test = RayBoxTest::new(&ray);
            let (t, mask) = test.enter4(&nodes, 0.0, 100.0);
            for (k, node) in nodes.iter().enumerate() {
                let one = test.enter(node, 0.0, 100.0);
                let hit = one != f32::INFINITY;
                assert_eq!(mask >> k & 1 == 1, hit, "box {k}, {ray:?}");
                if hit {
                    assert_eq!(t[k].to_bits(), one.to_bits(), "box {k}, {ray:?}");
                    entered += 1;
                }
            }
        }
        assert!(entered >= 6, "the rays enter boxes: {entered}");
    }
}
