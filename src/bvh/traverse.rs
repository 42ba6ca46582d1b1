//! Walking the BVH: the closest hit along a ray (front-to-back, nearest child first, pruning
//! by the best `t` so far) and every hit on a segment with early exit (shadow rays). At each
//! interior node the ray is tested against all its (up to four) children's boxes at once.

use std::ops::ControlFlow;

use glam::{Vec3, Vec4};

use super::build::MAX_DEPTH;
use super::cost::TraversalCost;
use super::{Bvh, Node, WIDTH};
use crate::primitive::{Geometry, Hit, PrimId};
use crate::ray::Ray;
use crate::shapes::ShearedRay;

/// Most entries the traversal stack can need: each level of the tree leaves at most
/// `WIDTH − 1` siblings waiting.
const STACK_SIZE: usize = (WIDTH - 1) * (MAX_DEPTH + 1) + 1;

/// A ray prepared for box tests: its origin and inverse direction, also each component copied
/// into four lanes for testing four boxes at once.
struct RayBoxTest {
    origin: Vec3,
    inv_dir: Vec3,
    origin_lanes: [Vec4; 3],
    inv_dir_lanes: [Vec4; 3],
}

impl RayBoxTest {
    fn new(ray: &Ray) -> Self {
        let inv_dir = ray.dir.recip();
        RayBoxTest {
            origin: ray.origin,
            inv_dir,
            origin_lanes: ray.origin.to_array().map(Vec4::splat),
            inv_dir_lanes: inv_dir.to_array().map(Vec4::splat),
        }
    }

    /// Entry distance into the node's box within `[t_min, t_max]`, or +∞ for a miss (the slab
    /// test: the ray is inside the box where it is inside all three slabs).
    #[inline(always)]
    fn enter(&self, node: &Node, t_min: f32, t_max: f32) -> f32 {
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
    fn enter4(&self, nodes: &[Node], t_min: f32, t_max: f32) -> (Vec4, u32) {
        let (mins, maxs) = boxes_by_axis(nodes);
        let slab = |axis: usize| {
            let (lo, hi) = (mins[axis], maxs[axis]);
            let t0 = (lo - self.origin_lanes[axis]) * self.inv_dir_lanes[axis];
            let t1 = (hi - self.origin_lanes[axis]) * self.inv_dir_lanes[axis];
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

impl Bvh {
    /// The closest hit of `ray` with `t` in `(t_min, t_max)`. When several primitives are hit
    /// at exactly the same `t` (a ray through the edge two polygons share), the one first in the
    /// scene wins ([`PrimId::scene_order`]): the answer depends on the scene alone, not on the
    /// shape of the tree or the order of the walk.
    pub fn closest_hit(
        &self,
        geometry: &Geometry,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
    ) -> Option<Hit> {
        self.closest_hit_counted(geometry, ray, t_min, t_max, &mut ())
    }

    /// [`Self::closest_hit`], telling `cost` of each node visited and primitive tested.
    pub fn closest_hit_counted<C: TraversalCost>(
        &self,
        geometry: &Geometry,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        cost: &mut C,
    ) -> Option<Hit> {
        let sheared = ShearedRay::new(ray);
        let mut best: Option<Hit> = None;
        // Searching up to just past the best hit so far still finds its ties.
        let mut test = |prims: &[PrimId], t_limit: &mut f32, cost: &mut C| {
            cost.prims_tested(prims.len());
            for &id in prims {
                if let Some(hit) = geometry.intersect_prepared(id, ray, &sheared, t_min, *t_limit)
                    && best.is_none_or(|b| hit.t < b.t || id.scene_order() < b.prim.scene_order())
                {
                    *t_limit = hit.t.next_up();
                    best = Some(hit);
                }
            }
            ControlFlow::Continue(())
        };
        let mut t_limit = t_max;
        let _ = test(&self.unbounded, &mut t_limit, cost);
        self.walk(ray, t_min, t_limit, cost, test);
        best
    }

    /// Calls `on_hit` for every primitive that `ray` hits in `(t_min, t_max)` (its nearest hit
    /// there), in no particular order, until `on_hit` breaks. Shadow rays use it: an opaque
    /// blocker ends the search at once.
    pub fn any_hit(
        &self,
        geometry: &Geometry,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        on_hit: impl FnMut(&Hit) -> ControlFlow<()>,
    ) {
        self.any_hit_counted(geometry, ray, t_min, t_max, &mut (), on_hit);
    }

    /// [`Self::any_hit`], telling `cost` of each node visited and primitive tested.
    pub fn any_hit_counted<C: TraversalCost>(
        &self,
        geometry: &Geometry,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        cost: &mut C,
        mut on_hit: impl FnMut(&Hit) -> ControlFlow<()>,
    ) {
        let sheared = ShearedRay::new(ray);
        let mut visit = |prims: &[PrimId], cost: &mut C| {
            cost.prims_tested(prims.len());
            for &id in prims {
                if let Some(hit) = geometry.intersect_prepared(id, ray, &sheared, t_min, t_max) {
                    on_hit(&hit)?;
                }
            }
            ControlFlow::Continue(())
        };
        if visit(&self.unbounded, cost).is_break() {
            return;
        }
        self.walk(ray, t_min, t_max, cost, |prims, _, cost| visit(prims, cost));
    }

    /// Visits the leaves whose boxes `ray` enters, nearest child first. `leaf` may shrink
    /// `t_max` (closest hit) or break (any hit). `cost` hears of each interior node visited.
    #[inline(always)]
    fn walk<C: TraversalCost>(
        &self,
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
        cost: &mut C,
        mut leaf: impl FnMut(&[PrimId], &mut f32, &mut C) -> ControlFlow<()>,
    ) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        let test = RayBoxTest::new(ray);
        if test.enter(root, t_min, t_max) == f32::INFINITY {
            return;
        }
        // Nodes still to visit, with the distance at which the ray enters them.
        let mut stack = [(0u32, 0.0f32); STACK_SIZE];
        let mut top = 0;
        let mut node = root;
        loop {
            if node.is_leaf() {
                let first = node.first as usize;
                let prims = &self.prims[first..first + node.count as usize];
                if leaf(prims, &mut t_max, cost).is_break() {
                    return;
                }
            } else {
                cost.node_visited();
                // Four nodes from the first child on, some perhaps not children: masked out.
                let group = node.first as usize..node.first as usize + WIDTH;
                let (t, entered) = test.enter4(&self.nodes[group], t_min, t_max);
                let entered = entered & ((1 << node.children().len()) - 1);
                let t = t.to_array();
                let first = node.first;
                if entered.count_ones() == 1 {
                    node = &self.nodes[(first + entered.trailing_zeros()) as usize];
                    continue;
                }
                if entered != 0 {
                    // The children the ray enters, farthest first (insertion sort of at most
                    // four), go on the stack; the nearest comes off again at once.
                    let base = top;
                    let mut left = entered;
                    while left != 0 {
                        let k = left.trailing_zeros();
                        left &= left - 1;
                        let mut i = top;
                        while i > base && stack[i - 1].1 < t[k as usize] {
                            stack[i] = stack[i - 1];
                            i -= 1;
                        }
                        stack[i] = (first + k, t[k as usize]);
                        top += 1;
                    }
                    top -= 1;
                    node = &self.nodes[stack[top].0 as usize];
                    continue;
                }
            }
            // Pop the next node still nearer than the best hit so far.
            loop {
                if top == 0 {
                    return;
                }
                top -= 1;
                let (index, t_enter) = stack[top];
                if t_enter < t_max {
                    node = &self.nodes[index as usize];
                    break;
                }
            }
        }
    }
}
