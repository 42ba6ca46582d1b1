//! Walking the BVH: the closest hit along a ray (front-to-back, nearest child first, pruning
//! by the best `t` so far) and every hit on a segment with early exit (shadow rays). At each
//! interior node the ray is tested against all its (up to four) children's boxes at once.

use std::ops::ControlFlow;

use arrayvec::ArrayVec;

use super::build::MAX_DEPTH;
use super::cost::TraversalCost;
use super::ray_box::RayBoxTest;
use super::{Bvh, WIDTH};
use crate::primitive::{Geometry, Hit, PrimId};
use crate::ray::Ray;
use crate::shapes::ShearedRay;

/// Most entries the traversal stack can need: each level of the tree leaves at most
/// `WIDTH − 1` siblings waiting.
pub(super) const STACK_SIZE: usize = (WIDTH - 1) * (MAX_DEPTH + 1) + 1;

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
        let mut test = |prims: &[PrimId], t_limit: &mut f32, cost: &mut C| {
            cost.prims_tested(prims.len());
            closest_among(geometry, prims, ray, &sheared, t_min, t_limit, &mut best);
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
        let mut stack: ArrayVec<(u32, f32), STACK_SIZE> = ArrayVec::new();
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
                    let base = stack.len();
                    let mut left = entered;
                    while left != 0 {
                        let k = left.trailing_zeros();
                        left &= left - 1;
                        stack.push((first + k, t[k as usize]));
                        let mut i = stack.len() - 1;
                        while i > base && stack[i - 1].1 < stack[i].1 {
                            stack.swap(i - 1, i);
                            i -= 1;
                        }
                    }
                    if let Some((nearest, _)) = stack.pop() {
                        node = &self.nodes[nearest as usize];
                    }
                    continue;
                }
            }
            // Pop the next node still nearer than the best hit so far.
            loop {
                let Some((index, t_enter)) = stack.pop() else {
                    return;
                };
                if t_enter < t_max {
                    node = &self.nodes[index as usize];
                    break;
                }
            }
        }
    }
}

/// Tests `prims` against `ray` for its closest hit in `(t_min, t_limit)`: a nearer hit (or one
/// at the same `t` from a primitive earlier in the scene) replaces `best`, and `t_limit` shrinks
/// to just past it, so that the search still finds its ties.
#[inline(always)]
pub(super) fn closest_among(
    geometry: &Geometry,
    prims: &[PrimId],
    ray: &Ray,
    sheared: &ShearedRay,
    t_min: f32,
    t_limit: &mut f32,
    best: &mut Option<Hit>,
) {
    for &id in prims {
        if let Some(hit) = geometry.intersect_prepared(id, ray, sheared, t_min, *t_limit)
            && best.is_none_or(|b| hit.t < b.t || id.scene_order() < b.prim.scene_order())
        {
            *t_limit = hit.t.next_up();
            *best = Some(hit);
        }
    }
}
