//! The debug views: what the image shows instead of (or as) the shaded colour. Each is rendered
//! progressively like the shaded image ([`super::view_color`] computes a pixel); the heat-map
//! and depth views come with a [`Legend`] that says what their colours mean.

use strum::VariantNames;

use super::legend::{Legend, depth_range};
#[cfg(feature = "gpu")]
use crate::gpu::frame::GpuView;
use crate::scene::Scene;
use crate::whitted::Tracer;

/// What a rendered image shows. The command line and the viewer name it in kebab case
/// (`tree-depth`), some by a shorter name (`object`).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    Hash,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "kebab-case", parse_err_ty = String, parse_err_fn = unknown_view)]
pub enum DebugView {
    /// The Whitted colour.
    #[default]
    Shaded,
    /// The shading normal `n` of the first hit (pointing out of the surface's front) as
    /// `n × 0.5 + 0.5`.
    Normals,
    /// The distance of the first hit along the view direction, grey from white (near) to black
    /// (far) over the range [`depth_range`] takes from the scene's bounds.
    Depth,
    /// The first hit's texture coordinates as `(fract u, fract v, 0)`.
    Uv,
    /// A distinct colour per object (mesh) seen by the eye ray.
    #[strum(serialize = "object")]
    ObjectId,
    /// A distinct colour per material seen by the eye ray.
    #[strum(serialize = "material")]
    MaterialId,
    /// The [`ObjectId`](Self::ObjectId) colours of the first hits the raster pass found, the
    /// item buffer ([`crate::item_buffer`]): black where it drew nothing, or the render has no
    /// item buffer.
    ItemBuffer,
    /// How deep the pixel's ray tree went: heat map over 1 ..= max_depth.
    TreeDepth,
    /// Rays traced for the pixel (eye, shadow, reflected, transmitted): heat map, log scale.
    #[strum(serialize = "rays")]
    RayCount,
    /// BVH nodes visited plus primitives tested by all the pixel's rays: heat map, log scale.
    BvhCost,
}

#[cfg(feature = "gpu")]
impl DebugView {
    /// The view as the GPU tracer draws it, or why it is drawn on the CPU only: the heat maps,
    /// which look at the whole ray tree.
    pub fn on_gpu(self, tracer: &Tracer) -> Result<GpuView, String> {
        Ok(match self {
            DebugView::Shaded => GpuView::Shaded,
            DebugView::Normals => GpuView::Normals,
            DebugView::Depth => {
                let (near, far) = depth_range(tracer);
                GpuView::Depth { near, far }
            }
            DebugView::Uv => GpuView::Uv,
            DebugView::ObjectId => GpuView::Object,
            DebugView::MaterialId => GpuView::Material,
            DebugView::TreeDepth
            | DebugView::RayCount
            | DebugView::BvhCost
            | DebugView::ItemBuffer => {
                return Err(format!("the {self} view is drawn on the CPU only"));
            }
        })
    }
}

impl DebugView {
    /// The colour bar of a heat-map view (and the grey bar of the depth view), `None` for views
    /// whose colours are not a scale.
    pub fn legend(self, tracer: &Tracer) -> Option<Legend> {
        let scene = tracer.scene;
        match self {
            DebugView::Depth => Some(Legend::depth(depth_range(tracer))),
            DebugView::TreeDepth => Some(Legend::tree_depth(scene.settings.max_depth)),
            DebugView::RayCount => Some(Legend::ray_count(max_rays(scene))),
            DebugView::BvhCost => Some(Legend::bvh_cost()),
            _ => None,
        }
    }
}

/// The most rays one pixel's tree can trace: a full binary tree of `max_depth` levels, each
/// ray with one shadow ray per light.
pub fn max_rays(scene: &Scene) -> u64 {
    let depth = scene.settings.max_depth.min(63);
    let rays = (1u64 << depth) - 1;
    rays * (1 + scene.lights.len() as u64)
}

/// Why `s` is no view's name.
fn unknown_view(s: &str) -> String {
    format!(
        "unknown view `{s}`; the views are {}",
        DebugView::VARIANTS.join(", ")
    )
}
