//! Seeing inside the tracer: the ray tree of one pixel ([`trace_ray_tree`], recorded by a
//! [`crate::whitted::TreeObserver`] of the Whitted tracer's own code, and printed as text), the
//! object each pixel sees ([`object_ids`]), and the debug views of the whole image
//! ([`DebugView`], a [`crate::progressive::SampleColoring`] that the renderer refines like the shaded
//! image) with the [`Legend`]s that explain their colours. It builds on [`crate::whitted`] and
//! [`crate::progressive`]; neither knows about it.

mod debug_view;
mod legend;
mod ray_tree;
mod recorder;
mod tree_text;
mod view_color;

pub use debug_view::{DebugView, max_rays};
pub use legend::{
    BVH_COST_MAX, Legend, depth_grey, depth_range, heat, heat_bar, log_position,
    tree_depth_position,
};
pub use ray_tree::{
    Blocker, Cut, FirstHitSource, LightShare, NodeHit, RayNode, RayTree, ShadowRay,
};
pub use recorder::{object_ids, trace_ray_tree};
pub use view_color::{MISS_COLOR, id_color};
