//! Walking the BVH: the closest hit along a ray (front-to-back, nearest child first, pruning
//! by the best `t` so far) and every hit on a segment with early exit (shadow rays).

use std::ops::ControlFlow;

use glam::Vec3;

use super::build::MAX_DEPTH;
use super::{Bvh, Node};
use crate::primitive::{Geometry, Hit, PrimId};
use crate::ray::Ray;
use crate::shapes::ShearedRay;

/// A ray prepared for box tests.
struct RayBoxTest {
    origin: Vec3,
    inv_dir: Vec3,
}

impl RayBoxTest {
    fn new(ray: &Ray) -> Self {
        RayBoxTest {
            origin: ray.origin,
            inv_dir: ray.dir.recip(),
        }
    }

    /// Entry distance into the node's box within `[t_min, t_max]`, or +∞ for a miss.
    #[inline(always)]
    fn enter(&self, node: &Node, t_min: f32, t_max: f32) -> f32 {
        let t0 = (Vec3::from(node.min) - self.origin) * self.inv_dir;
        let t1 = (Vec3::from(node.max) - self.origin) * self.inv_dir;
        let near = t0.min(t1).max_element().max(t_min);
        let far = t0.max(t1).min_element().min(t_max);
        if near <= far { near } else { f32::INFINITY }
    }
}

impl Bvh {
    /// The closest hit of `ray` with `t` in `(t_min, t_max)`.
    pub fn closest_hit(
        &self,
        geometry: &Geometry,
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
    ) -> Option<Hit> {
        let sheared = ShearedRay::new(ray);
        let mut best = None;
        for &id in &self.unbounded {
            if let Some(hit) = geometry.intersect_prepared(id, ray, &sheared, t_min, t_max) {
                t_max = hit.t;
                best = Some(hit);
            }
        }
        self.walk(ray, t_min, t_max, |prims, t_max| {
            for &id in prims {
                if let Some(hit) = geometry.intersect_prepared(id, ray, &sheared, t_min, *t_max) {
                    *t_max = hit.t;
                    best = Some(hit);
                }
            }
            ControlFlow::Continue(())
        });
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
        mut on_hit: impl FnMut(&Hit) -> ControlFlow<()>,
    ) {
        let sheared = ShearedRay::new(ray);
        let mut visit = |prims: &[PrimId]| {
            for &id in prims {
                if let Some(hit) = geometry.intersect_prepared(id, ray, &sheared, t_min, t_max) {
                    on_hit(&hit)?;
                }
            }
            ControlFlow::Continue(())
        };
        if visit(&self.unbounded).is_break() {
            return;
        }
        self.walk(ray, t_min, t_max, |prims, _| visit(prims));
    }

    /// Visits the leaves whose boxes `ray` enters, nearest child first. `leaf` may shrink
    /// `t_max` (closest hit) or break (any hit).
    #[inline(always)]
    fn walk(
        &self,
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
        mut leaf: impl FnMut(&[PrimId], &mut f32) -> ControlFlow<()>,
    ) {
        let Some(root) = self.nodes.first() else {
            return;
        };
        let test = RayBoxTest::new(ray);
        if test.enter(root, t_min, t_max) == f32::INFINITY {
            return;
        }
        let mut stack = [(0u32, 0.0f32); MAX_DEPTH + 4];
        let mut top = 0;
        let mut node = root;
        loop {
            if node.is_leaf() {
                let first = node.first as usize;
                let prims = &self.prims[first..first + node.count as usize];
                if leaf(prims, &mut t_max).is_break() {
                    return;
                }
            } else {
                let first = node.first as usize;
                let (a, b) = (&self.nodes[first], &self.nodes[first + 1]);
                let (mut ta, mut tb) = (test.enter(a, t_min, t_max), test.enter(b, t_min, t_max));
                let (mut near, mut far) = (first as u32, first as u32 + 1);
                if tb < ta {
                    std::mem::swap(&mut ta, &mut tb);
                    std::mem::swap(&mut near, &mut far);
                }
                if ta != f32::INFINITY {
                    if tb != f32::INFINITY {
                        stack[top] = (far, tb);
                        top += 1;
                    }
                    node = &self.nodes[near as usize];
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
