//! The walk down the tree that every single-ray query takes: from the root, the children whose
//! boxes the ray enters, nearest first or in slot order, pruned by the far limit, which the
//! leaves' tests may shrink. What happens at a leaf is the query's ([`VisitLeaf`]). The scene's
//! tree and the models' trees are walked alike.

use std::ops::ControlFlow;

use arrayvec::ArrayVec;

use super::build::MAX_DEPTH;
use super::cost::TraversalCost;
use super::ray_box::RayBoxTest;
use super::simd::Lanes;
use super::{Bvh, Child, Reached, WIDTH};

/// Most entries the traversal stack can need: each level of the tree leaves at most
/// `WIDTH − 1` siblings waiting.
pub(super) const STACK_SIZE: usize = (WIDTH - 1) * (MAX_DEPTH + 1) + 1;

/// What a walk does at each leaf it reaches: test the leaf's primitives, shrinking the walk's
/// far limit `t_max` (closest hit) or breaking off the walk (any hit). A trait with inlined
/// methods rather than a closure, so that the leaf tests are compiled into each kernel with its
/// instruction set instead of being called apart.
pub(super) trait VisitLeaf<C> {
    fn visit<L: Lanes>(&mut self, leaf: Reached, t_max: &mut f32, cost: &mut C) -> ControlFlow<()>;
}

impl Bvh {
    /// Visits the leaves whose boxes `ray` enters: nearest child first when `NEAREST_FIRST`,
    /// else in the order of the node's slots. `leaf` may shrink `t_max` (closest hit) or break
    /// (any hit). `cost` hears of each interior node visited.
    ///
    /// The order pays only where a hit prunes the rest of the walk, which the closest hit's
    /// does; an any-hit search that finds nothing visits every entered box in any order, so it
    /// spends nothing on sorting (as Embree's occlusion walk does).
    #[inline(always)]
    pub(super) fn walk<L: Lanes, C: TraversalCost, const NEAREST_FIRST: bool>(
        &self,
        test: &RayBoxTest,
        t_min: f32,
        t_max: &mut f32,
        cost: &mut C,
        leaf: &mut impl VisitLeaf<C>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        // No test of the root's own box: the root's children's boxes lie inside it, so a ray
        // that misses it misses them all, at the cost of one node's test.
        // A finite far limit keeps the unused slots of a node, whose boxes lie at +∞, shut.
        *t_max = t_max.min(f32::MAX);
        // Children still to visit, with the distance at which the ray enters them.
        let mut stack: ArrayVec<(Child, f32), STACK_SIZE> = ArrayVec::new();
        let mut next = Child::node(0);
        loop {
            if next.is_leaf() {
                if leaf.visit::<L>(next.leaf(self), t_max, cost).is_break() {
                    return;
                }
            } else {
                cost.node_visited();
                let node = &self.nodes[next.first as usize];
                let (t, entered) = test.enter8::<L>(node, t_min, *t_max);
                let child = |k: u32| Child {
                    first: node.first[k as usize],
                    count: node.count[k as usize],
                };
                if entered.count_ones() == 1 {
                    next = child(entered.trailing_zeros());
                    continue;
                }
                if entered != 0 && !NEAREST_FIRST {
                    // The lowest slot is visited next; the others wait on the stack.
                    next = child(entered.trailing_zeros());
                    let mut left = entered & (entered - 1);
                    while left != 0 {
                        let k = left.trailing_zeros();
                        left &= left - 1;
                        stack.push((child(k), t[k as usize]));
                    }
                    continue;
                }
                if entered != 0 {
                    // The children the ray enters, farthest first (insertion sort of at most
                    // eight), go on the stack; the nearest comes off again at once.
                    let base = stack.len();
                    let mut left = entered;
                    while left != 0 {
                        let k = left.trailing_zeros();
                        left &= left - 1;
                        stack.push((child(k), t[k as usize]));
                        let mut i = stack.len() - 1;
                        while i > base && stack[i - 1].1 < stack[i].1 {
                            stack.swap(i - 1, i);
                            i -= 1;
                        }
                    }
                    if let Some((nearest, _)) = stack.pop() {
                        next = nearest;
                    }
                    continue;
                }
            }
            // Pop the next child still nearer than the best hit so far.
            loop {
                let Some((child, t_enter)) = stack.pop() else {
                    return;
                };
                if t_enter < *t_max {
                    next = child;
                    break;
                }
            }
        }
    }
}
