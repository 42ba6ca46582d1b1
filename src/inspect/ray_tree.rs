//! The ray tree of one pixel as plain data: one [`RayNode`] per ray traced (eye, reflected,
//! transmitted), with what it hit, its shadow rays, the colours it gathered and where its branch
//! stopped. [`super::trace_ray_tree`] builds it; the CLI prints it ([`RayTree::to_text`] or
//! JSON) and the viewer shows it.

use glam::{Vec2, Vec3};
use serde::Serialize;

use crate::color::Color;
use crate::whitted::{RayKind, StopReason};

/// An object a shadow ray passed through or was stopped by.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Blocker {
    /// [`crate::primitive::Geometry::object_id`] of what was hit.
    pub object: u32,
    pub label: String,
    /// Distance from the shadow ray's origin.
    pub t: f32,
    /// The share of the light left after this blocker (and the nearer ones): zero once opaque.
    pub transmittance_after: [f32; 3],
}

/// A shadow ray from a hit point towards a light.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ShadowRay {
    /// Index of the light in the scene.
    pub light: usize,
    pub origin: Vec3,
    /// Unit direction towards the light.
    pub dir: Vec3,
    /// Distance to the light, infinite for a directional light.
    pub distance: f32,
    /// What the ray met on its way, nearest first (the search stops at an opaque blocker).
    pub blockers: Vec<Blocker>,
    /// No light arrived.
    pub blocked: bool,
    /// The light that arrived: the light's colour times the blockers' tints.
    pub light_color: Color,
}

/// One light's share of a hit's local colour: its diffuse (Lambert) and specular (Phong)
/// terms, as added and as they would be with no shadowing.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightShare {
    /// Index of the light in the scene.
    pub light: usize,
    /// The diffuse light it added: the light that arrived times Lambert's term.
    pub diffuse: Color,
    /// The specular light it added: the light that arrived times Phong's term.
    pub specular: Color,
    /// The diffuse light with the light's whole colour, as if its shadow ray were clear.
    pub unshadowed_diffuse: Color,
    /// The specular light with the light's whole colour.
    pub unshadowed_specular: Color,
}

/// What a ray hit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NodeHit {
    pub object: u32,
    /// E.g. "sphere #2" or "mesh #0, triangle 812".
    pub label: String,
    pub material: u32,
    pub material_name: String,
    /// Distance from the ray's origin to the hit (the ray's `dir` is a unit vector).
    pub t: f32,
    pub point: Vec3,
    /// Unit shading normal, turned to face the ray.
    pub normal: Vec3,
    pub uv: Vec2,
    /// The ray came from the front side of the surface (into the object, for a solid).
    pub entering: bool,
    /// The light the surface gives off of itself, part of the local colour.
    pub emission: Color,
    /// The ambient term of the local colour.
    pub ambient: Color,
}

/// What the fog did to a ray on its way back to its parent (only in scenes with fog).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct NodeFog {
    /// The share of the ray's colour (its local colour and its children's) that the fog lets
    /// through: `exp(−σ·d)` over the length `d` it runs in the fog.
    pub transmittance: f32,
    /// The light the fog scattered into the ray on the way.
    pub in_scattered: Color,
}

/// A child ray that was not traced, and why.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Cut {
    pub branch: RayKind,
    pub reason: StopReason,
    /// The weight the child would have carried.
    pub weight: f32,
}

/// One ray of the tree.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RayNode {
    pub kind: RayKind,
    /// The eye ray is depth 1.
    pub depth: u32,
    pub origin: Vec3,
    pub dir: Vec3,
    /// The weight this ray carries (adaptive depth control compares it with `min_weight`).
    pub weight: f32,
    /// What this ray's colour is multiplied by on its way to the pixel: the product of the
    /// reflection coefficients `kr` and tinted transmission coefficients `kt·colour` above it,
    /// and in fog the transmittances of the fog along it and the rays above it.
    pub factor: Color,
    /// `None`: the ray missed (`stop` is `Miss`, `local_color` the background).
    pub hit: Option<NodeHit>,
    pub shadows: Vec<ShadowRay>,
    /// Each light in front of the surface, with its diffuse and specular terms.
    pub lights: Vec<LightShare>,
    /// Ambient, diffuse and specular light at the hit (or the background).
    pub local_color: Color,
    /// The colour this ray returns to its parent: local colour plus its children's, weighted.
    pub color: Color,
    /// `factor × local_color`, plus in fog the in-scattered light times the factor before the
    /// ray's own fog: this node's own share of the pixel.
    pub contribution: Color,
    /// What the fog did to the ray; `None` in clear air.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fog: Option<NodeFog>,
    /// The irradiance the caustic photons bring to the hit (with caustics on, at a diffuse
    /// surface); the local colour holds its diffuse share.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub caustic: Option<Color>,
    /// Set where the branch ended at this ray: `Miss`, or `MaxDepth` at a reflective or
    /// transparent surface.
    pub stop: Option<StopReason>,
    /// The child rays that were not traced.
    pub cuts: Vec<Cut>,
    /// Indices into [`RayTree::nodes`].
    pub children: Vec<usize>,
    pub parent: Option<usize>,
}

/// The ray tree of one pixel, as the renderer traces it (one sample, at the pixel centre).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RayTree {
    /// (x, y), y from the top of the image.
    pub pixel: (u32, u32),
    /// `nodes[0]` is the eye ray; children follow their parents.
    pub nodes: Vec<RayNode>,
    /// The pixel's colour: what the renderer writes there at one sample per pixel.
    pub color: Color,
    /// Where the eye ray's first hit came from, when the tracer has an item buffer; `None`: the
    /// ray searched the BVH, as without one.
    pub first_hit: Option<FirstHitSource>,
}

/// Where an eye ray's first hit came from in a render with an item buffer
/// ([`crate::item_buffer`]): the hit is the same either way.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case", tag = "from")]
pub enum FirstHitSource {
    /// Found by the walk up to the pixel's item (`item` names it), at `t`.
    ItemBuffer { item: String, t: f32 },
    /// The item buffer holds nothing at this pixel: the ray searched in full.
    NoItem,
    /// The ray misses the pixel's item, `item` (or finds nothing up to it): it searched in
    /// full.
    ItemMissed { item: String },
}

impl RayNode {
    /// How much of `term`, a part of this ray's local colour, reaches the pixel: times the
    /// ray's factor and, in fog, the fog's transmittance along the ray.
    pub fn pixel_share(&self, term: Color) -> Color {
        let fog = self.fog.map_or(1.0, |fog| fog.transmittance);
        self.factor * fog * term
    }
}

impl RayTree {
    /// The sum of all nodes' contributions: the pixel colour, up to rounding.
    pub fn sum_of_contributions(&self) -> Color {
        self.nodes.iter().map(|n| n.contribution).sum()
    }
}
