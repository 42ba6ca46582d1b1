//! What the Whitted tracer tells an observer while it builds a ray tree: each ray it starts
//! ([`RayKind`]), what the ray hit, its shadow rays ([`ShadowEvent`]), the terms of its local
//! colour ([`LocalTerms`], [`LightTerms`]), its local colour, the
//! branches it cut and why ([`StopReason`]) and the colour it returned. The tracer is generic
//! over the observer; the renderer's observer is `()`, whose methods are empty and
//! `#[inline(always)]`, so the normal path compiles to the tracer without any of this. The
//! inspector's observer ([`crate::inspect::trace_ray_tree`]) records the tree; the debug views'
//! observers count depth, rays and BVH cost.
//!
//! The observer is also the traversal's [`TraversalCost`], so one value sees every BVH walk of
//! the tree.

use glam::Vec3;
use serde::Serialize;

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

/// The terms of the shading model at a hit that do not depend on the lights.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalTerms {
    /// The light the surface gives off of itself.
    pub emission: Color,
    /// The ambient term: `ambient × colour × the scene's ambient light`.
    pub ambient: Color,
}

/// What one light adds to the local colour at a hit: `arrived × (diffuse + specular)`, where
/// the two terms are the surface's reflectance towards the eye for this light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightTerms {
    pub light: usize,
    /// Lambert's term: `diffuse × cos θ × colour`.
    pub diffuse: Color,
    /// Phong's term: `specular × cos^shininess φ × specular colour`.
    pub specular: Color,
    /// The light that reaches the surface with no shadowing (its colour, after any fog).
    pub unshadowed: Color,
    /// The light that arrived: `unshadowed` times what the shadow ray let through.
    pub arrived: Color,
}

/// Hears the ray tree as it is traced, depth first: `ray`, then `hit` or `miss`, the shadow
/// rays and the local terms, `local`, the children (each its own `ray` … `done`) or `cut`s, then `done`.
#[allow(unused_variables)]
pub trait TreeObserver: TraversalCost {
    /// Whether shadow rays must report every blocker (the shadow cache must be off then).
    const RECORDS_BLOCKERS: bool = false;
    /// Whether shadow rays may try the thread's last blocker first (the shadow cache, see
    /// [`crate::whitted`]).
    /// The answer is the same either way, but what the search meets and costs then depends on
    /// the pixels traced before on the thread; observers that report those turn it off.
    const USES_SHADOW_CACHE: bool = true;
    /// Whether the observer hears [`Self::light`] for lights whose shadow ray is blocked too
    /// (what they would have added).
    const RECORDS_TERMS: bool = false;
    /// Whether [`Self::hit`] needs the surface's texture coordinates even where no texture
    /// does (they cost trigonometry on curved shapes).
    const WANTS_UV: bool = false;

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
    /// The emission and ambient terms at the hit.
    #[inline(always)]
    fn local_terms(&mut self, terms: LocalTerms) {}
    /// A light in front of the surface adds `terms.arrived × (terms.diffuse + terms.specular)`
    /// (heard for blocked lights only when [`Self::RECORDS_TERMS`]).
    #[inline(always)]
    fn light(&mut self, terms: LightTerms) {}
    /// The local (ambient, diffuse and specular) colour at the hit.
    #[inline(always)]
    fn local(&mut self, color: Color) {}
    /// The branch ends here for `reason` (the depth limit).
    #[inline(always)]
    fn stop(&mut self, reason: StopReason) {}
    /// A child ray of kind `branch` with `weight` was not traced, for `reason`.
    #[inline(always)]
    fn cut(&mut self, branch: RayKind, reason: StopReason, weight: f32) {}
    /// The diffuse hit gathered `irradiance` from the caustic photon map (only with caustics
    /// on); the local colour includes it.
    #[inline(always)]
    fn caustic(&mut self, irradiance: Color) {}
    /// The ray ran through fog, or through the medium inside an object: its colour was
    /// multiplied by `transmittance` and gained `in_scattered`, the light the medium scattered
    /// into it. Heard just before `done`, only for rays where there is fog or a medium.
    #[inline(always)]
    fn fog(&mut self, transmittance: f32, in_scattered: Color) {}
    /// The ray returns `color` to its parent.
    #[inline(always)]
    fn done(&mut self, color: Color) {}
}

/// Observes nothing: the renderer's tracer.
impl TreeObserver for () {}

/// Why a ray was traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RayKind {
    Eye,
    Reflected,
    Transmitted,
}

impl RayKind {
    /// The kind as a word: "eye", "reflected" or "transmitted".
    pub fn name(self) -> &'static str {
        match self {
            RayKind::Eye => "eye",
            RayKind::Reflected => "reflected",
            RayKind::Transmitted => "transmitted",
        }
    }
}

/// Why a branch of the tree ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The ray left the scene.
    Miss,
    /// The ray is at `max_depth`: its reflected and transmitted rays are not traced.
    MaxDepth,
    /// The child's weight is below `min_weight` (adaptive depth control).
    MinWeight,
    /// Past the critical angle: no transmitted ray (its share goes to the reflected one).
    TotalInternalReflection,
    /// Reflected or transmitted rays are switched off in the settings.
    Disabled,
    /// The eye ray's tree has used up its [`crate::whitted::RAY_BUDGET`].
    RayBudget,
}
