//! Walking the BVH: the closest hit along a ray (front-to-back, nearest child first, pruning
//! by the best `t` so far) and every hit on a segment with early exit (shadow rays). At each
//! node the ray is tested against all its (up to eight) children's boxes at once. Each walk is
//! a [`Kernel`], compiled for every instruction set and run on the BVH's ([`super::simd`]).

use std::ops::ControlFlow;

use arrayvec::ArrayVec;

use super::build::MAX_DEPTH;
use super::cost::TraversalCost;
use super::leaf::{closest_in_leaf, each_in_leaf};
use super::ray_box::RayBoxTest;
use super::simd::{Kernel, Lanes, dispatch};
use super::{Bvh, Child, Leaf, WIDTH};
use crate::primitive::{Geometry, Hit};
use crate::ray::Ray;
use crate::shapes::ShearedRay;

/// Most entries the traversal stack can need: each level of the tree leaves at most
/// `WIDTH − 1` siblings waiting.
pub(super) const STACK_SIZE: usize = (WIDTH - 1) * (MAX_DEPTH + 1) + 1;

impl Bvh {
    /// The closest hit of `ray` with `t` in `(t_min, t_max)`. When several primitives are hit
    /// at exactly the same `t` (a ray through the edge two polygons share), the one first in the
    /// scene wins ([`crate::primitive::PrimId::scene_order`]): the answer depends on the scene alone, not on the
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
        let walk = Walk::new(self, geometry, ray, t_min, t_max, cost);
        dispatch(self.simd, ClosestHit(walk))
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
        on_hit: impl FnMut(&Hit) -> ControlFlow<()>,
    ) {
        let walk = Walk::new(self, geometry, ray, t_min, t_max, cost);
        dispatch(self.simd, AnyHit(walk, on_hit));
    }
}

/// One ray's walk through the tree: what both queries share.
struct Walk<'a, C> {
    bvh: &'a Bvh,
    geometry: &'a Geometry,
    ray: &'a Ray,
    t_min: f32,
    t_max: f32,
    cost: &'a mut C,
}

impl<'a, C> Walk<'a, C> {
    fn new(
        bvh: &'a Bvh,
        geometry: &'a Geometry,
        ray: &'a Ray,
        t_min: f32,
        t_max: f32,
        cost: &'a mut C,
    ) -> Self {
        Walk {
            bvh,
            geometry,
            ray,
            t_min,
            t_max,
            cost,
        }
    }
}

/// What a walk does at each leaf it reaches: test the leaf's primitives, shrinking the walk's
/// far limit `t_max` (closest hit) or breaking off the walk (any hit). A trait with inlined
/// methods rather than a closure, so that the leaf tests are compiled into each kernel with its
/// instruction set instead of being called apart.
trait VisitLeaf<C> {
    fn visit(&mut self, leaf: Leaf, t_max: &mut f32, cost: &mut C) -> ControlFlow<()>;
}

/// The closest-hit query as a [`Kernel`].
struct ClosestHit<'a, C>(Walk<'a, C>);

/// The closest hit's leaf tests: the best hit so far.
struct Closest<'a> {
    geometry: &'a Geometry,
    ray: &'a Ray,
    sheared: ShearedRay,
    t_min: f32,
    best: Option<Hit>,
}

impl<C: TraversalCost> VisitLeaf<C> for Closest<'_> {
    #[inline(always)]
    fn visit(&mut self, leaf: Leaf, t_limit: &mut f32, cost: &mut C) -> ControlFlow<()> {
        cost.prims_tested(leaf.tests());
        closest_in_leaf(
            self.geometry,
            leaf,
            self.ray,
            &self.sheared,
            self.t_min,
            t_limit,
            &mut self.best,
        );
        ControlFlow::Continue(())
    }
}

impl<C: TraversalCost> Kernel for ClosestHit<'_, C> {
    type Output = Option<Hit>;

    #[inline(always)]
    fn run<L: Lanes>(self) -> Option<Hit> {
        let w = self.0;
        let mut closest = Closest {
            geometry: w.geometry,
            ray: w.ray,
            sheared: ShearedRay::new(w.ray),
            t_min: w.t_min,
            best: None,
        };
        let mut t_limit = w.t_max;
        let _ = closest.visit(Leaf::Objects(&w.bvh.unbounded), &mut t_limit, w.cost);
        w.bvh
            .walk::<L, C, true>(w.ray, w.t_min, t_limit, w.cost, &mut closest);
        closest.best
    }
}

/// The any-hit query as a [`Kernel`].
struct AnyHit<'a, C, F>(Walk<'a, C>, F);

/// The any-hit search's leaf tests: every hit goes to `on_hit`.
struct Each<'a, F> {
    geometry: &'a Geometry,
    ray: &'a Ray,
    sheared: ShearedRay,
    t_min: f32,
    t_max: f32,
    on_hit: F,
}

impl<C: TraversalCost, F: FnMut(&Hit) -> ControlFlow<()>> VisitLeaf<C> for Each<'_, F> {
    #[inline(always)]
    fn visit(&mut self, leaf: Leaf, _: &mut f32, cost: &mut C) -> ControlFlow<()> {
        cost.prims_tested(leaf.tests());
        let range = (self.t_min, self.t_max);
        each_in_leaf(
            self.geometry,
            leaf,
            self.ray,
            &self.sheared,
            range,
            &mut self.on_hit,
        )
    }
}

impl<C: TraversalCost, F: FnMut(&Hit) -> ControlFlow<()>> Kernel for AnyHit<'_, C, F> {
    type Output = ();

    #[inline(always)]
    fn run<L: Lanes>(self) {
        let AnyHit(w, on_hit) = self;
        let mut each = Each {
            geometry: w.geometry,
            ray: w.ray,
            sheared: ShearedRay::new(w.ray),
            t_min: w.t_min,
            t_max: w.t_max,
            on_hit,
        };
        let mut t_max = w.t_max;
        if each
            .visit(Leaf::Objects(&w.bvh.unbounded), &mut t_max, w.cost)
            .is_break()
        {
            return;
        }
        w.bvh
            .walk::<L, C, false>(w.ray, w.t_min, w.t_max, w.cost, &mut each);
    }
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
    fn walk<L: Lanes, C: TraversalCost, const NEAREST_FIRST: bool>(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        cost: &mut C,
        leaf: &mut impl VisitLeaf<C>,
    ) {
        if self.nodes.is_empty() {
            return;
        }
        // No test of the root's own box: the root's children's boxes lie inside it, so a ray
        // that misses it misses them all, at the cost of one node's test.
        let test = RayBoxTest::new(ray);
        // A finite far limit keeps the unused slots of a node, whose boxes lie at +∞, shut.
        let mut t_max = t_max.min(f32::MAX);
        // Children still to visit, with the distance at which the ray enters them.
        let mut stack: ArrayVec<(Child, f32), STACK_SIZE> = ArrayVec::new();
        let mut next = Child::node(0);
        loop {
            if next.is_leaf() {
                if leaf.visit(next.leaf(self), &mut t_max, cost).is_break() {
                    return;
                }
            } else {
                cost.node_visited();
                let node = &self.nodes[next.first as usize];
                let (t, entered) = test.enter8::<L>(node, t_min, t_max);
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
                if t_enter < t_max {
                    next = child;
                    break;
                }
            }
        }
    }
}
