//! What the Whitted tracer tells an observer while it builds a ray tree: each ray it starts, what
//! the ray hit, its shadow rays, its local colour, the branches it cut and the colour it
//! returned. The tracer is generic over the observer; the renderer's observer is `()`, whose
//! methods are empty and `#[inline(always)]`, so the normal path compiles to the tracer without
//! any of this. The inspector's observer ([`super::recorder`]) records the tree; the debug views'
//! observers count depth, rays and BVH cost.
//!
//! The observer is also the traversal's [`TraversalCost`], so one value sees every BVH walk of
//! the tree.

use glam::Vec3;

use super::ray_tree::{RayKind, StopReason};
use crate::bvh::cost::TraversalCost;
use crate::color::Color;
use crate::primitive::{Hit, SurfacePoint};
use crate::ray::Ray;

/// A shadow ray as the tracer traced it.
#[derive(Clone, Copy, Debug)]
pub struct ShadowEvent<'a> {
    pub light: usize,
    pub ray: &'a Ray,
    pub distance: f32,
    /// The primitives the ray met before the search ended, in no particular order, each with
    /// its tint (`transparency × colour`); filled only when [`TreeObserver::RECORDS_BLOCKERS`].
    pub blockers: &'a [(Hit, Color)],
    /// The light that arrived.
    pub arrived: Color,
}

/// Hears the ray tree as it is traced, depth first: `ray`, then `hit` or `miss`, the shadow
/// rays, `local`, the children (each its own `ray` … `done`) or `cut`s, then `done`.
#[allow(unused_variables)]
pub trait TreeObserver: TraversalCost {
    /// Whether shadow rays must report every blocker (the shadow cache must be off then).
    const RECORDS_BLOCKERS: bool = false;
    /// Whether shadow rays may try the thread's last blocker first ([`crate::shadow_cache`]).
    /// The answer is the same either way, but what the search meets and costs then depends on
    /// the pixels traced before on the thread; observers that report those turn it off.
    const USES_SHADOW_CACHE: bool = true;

    /// A ray starts. `scale` is what its colour is multiplied by in its parent's colour (one
    /// for the eye ray).
    #[inline(always)]
    fn ray(&mut self, kind: RayKind, depth: u32, ray: &Ray, weight: f32, scale: Color) {}
    /// The ray hit `surface`; `normal` is the shading normal turned to face the ray.
    #[inline(always)]
    fn hit(&mut self, hit: &Hit, surface: &SurfacePoint, normal: Vec3, entering: bool) {}
    /// The ray left the scene and returns the background.
    #[inline(always)]
    fn miss(&mut self, background: Color) {}
    #[inline(always)]
    fn shadow(&mut self, shadow: ShadowEvent) {}
    /// The local (ambient, diffuse and specular) colour at the hit.
    #[inline(always)]
    fn local(&mut self, color: Color) {}
    /// The branch ends here for `reason` (the depth limit).
    #[inline(always)]
    fn stop(&mut self, reason: StopReason) {}
    /// A child ray of kind `branch` with `weight` was not traced, for `reason`.
    #[inline(always)]
    fn cut(&mut self, branch: RayKind, reason: StopReason, weight: f32) {}
    /// The ray returns `color` to its parent.
    #[inline(always)]
    fn done(&mut self, color: Color) {}
}

/// Observes nothing: the renderer's tracer.
impl TreeObserver for () {}
