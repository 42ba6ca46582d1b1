//! Walking the BVH: the closest hit along a ray (front-to-back, nearest child first, pruning
//! by the best `t` so far) and every hit on a segment with early exit (shadow rays). At each
//! node the ray is tested against all its (up to eight) children's boxes at once. Each walk is
//! a [`Kernel`], compiled for every instruction set and run on the BVH's ([`super::simd`]).

use std::ops::ControlFlow;

use super::cost::TraversalCost;
use super::instances::{closest_in_instances, each_in_instances};
use super::leaf::{closest_in_leaf, each_in_leaf};
use super::ray_box::RayBoxTest;
use super::simd::{Kernel, Lanes, dispatch};
use super::walk::VisitLeaf;
use super::{Bvh, Leaf, Reached};
use crate::primitive::{Geometry, Hit};
use crate::ray::Ray;
use crate::shapes::ShearedRay;

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

/// The closest-hit query as a [`Kernel`].
struct ClosestHit<'a, C>(Walk<'a, C>);

/// The closest hit's leaf tests: the best hit so far.
struct Closest<'a> {
    geometry: &'a Geometry,
    models: &'a [Bvh],
    ray: &'a Ray,
    sheared: ShearedRay,
    t_min: f32,
    best: Option<Hit>,
}

impl<C: TraversalCost> VisitLeaf<C> for Closest<'_> {
    #[inline(always)]
    fn visit<L: Lanes>(
        &mut self,
        reached: Reached,
        t_limit: &mut f32,
        cost: &mut C,
    ) -> ControlFlow<()> {
        let (geometry, ray, sheared) = (self.geometry, self.ray, &self.sheared);
        match reached {
            Reached::Prims(leaf) => {
                cost.prims_tested(leaf.tests());
                closest_in_leaf(
                    geometry,
                    leaf,
                    ray,
                    sheared,
                    self.t_min,
                    t_limit,
                    &mut self.best,
                );
            }
            Reached::Instances(ids) => closest_in_instances::<L, C>(
                geometry,
                self.models,
                ids,
                ray,
                sheared,
                self.t_min,
                t_limit,
                &mut self.best,
                cost,
            ),
        }
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
            models: &w.bvh.models,
            ray: w.ray,
            sheared: ShearedRay::new(w.ray),
            t_min: w.t_min,
            best: None,
        };
        let mut t_limit = w.t_max;
        let unbounded = Reached::Prims(Leaf::Objects(&w.bvh.unbounded));
        let _ = closest.visit::<L>(unbounded, &mut t_limit, w.cost);
        let test = RayBoxTest::new(w.ray);
        w.bvh
            .walk::<L, C, true>(&test, w.t_min, &mut t_limit, w.cost, &mut closest);
        closest.best
    }
}

/// The any-hit query as a [`Kernel`].
struct AnyHit<'a, C, F>(Walk<'a, C>, F);

/// The any-hit search's leaf tests: every hit goes to `on_hit`.
struct Each<'a, F> {
    geometry: &'a Geometry,
    models: &'a [Bvh],
    ray: &'a Ray,
    sheared: ShearedRay,
    t_min: f32,
    t_max: f32,
    on_hit: F,
}

impl<C: TraversalCost, F: FnMut(&Hit) -> ControlFlow<()>> VisitLeaf<C> for Each<'_, F> {
    #[inline(always)]
    fn visit<L: Lanes>(&mut self, reached: Reached, _: &mut f32, cost: &mut C) -> ControlFlow<()> {
        let (geometry, ray, sheared) = (self.geometry, self.ray, &self.sheared);
        let range = (self.t_min, self.t_max);
        match reached {
            Reached::Prims(leaf) => {
                cost.prims_tested(leaf.tests());
                each_in_leaf(geometry, leaf, ray, sheared, range, &mut self.on_hit)
            }
            Reached::Instances(ids) => {
                let on_hit = &mut self.on_hit;
                let models = self.models;
                each_in_instances::<L, C>(geometry, models, ids, ray, sheared, range, on_hit, cost)
            }
        }
    }
}

impl<C: TraversalCost, F: FnMut(&Hit) -> ControlFlow<()>> Kernel for AnyHit<'_, C, F> {
    type Output = ();

    #[inline(always)]
    fn run<L: Lanes>(self) {
        let AnyHit(w, on_hit) = self;
        let mut each = Each {
            geometry: w.geometry,
            models: &w.bvh.models,
            ray: w.ray,
            sheared: ShearedRay::new(w.ray),
            t_min: w.t_min,
            t_max: w.t_max,
            on_hit,
        };
        let mut t_max = w.t_max;
        let unbounded = Reached::Prims(Leaf::Objects(&w.bvh.unbounded));
        if each.visit::<L>(unbounded, &mut t_max, w.cost).is_break() {
            return;
        }
        let test = RayBoxTest::new(w.ray);
        w.bvh
            .walk::<L, C, false>(&test, w.t_min, &mut t_max, w.cost, &mut each);
    }
}
