//! Seeing inside the tracer: the ray tree of one pixel ([`trace_ray_tree`], recorded by an
//! observer of the Whitted tracer's own code), the object each pixel sees ([`object_ids`]),
//! and the debug views of the whole image ([`DebugView`], rendered by [`view_colors`]).

mod debug_view;
mod legend;
mod ray_tree;
mod recorder;
mod tree_text;
mod view_color;

pub use debug_view::{DebugView, max_rays};
pub use legend::{
    BVH_COST_MAX, Legend, depth_grey, depth_range, heat, log_position, tree_depth_position,
};
pub use ray_tree::{Blocker, Cut, NodeHit, RayNode, RayTree, ShadowRay};
pub use recorder::{eye_ray, object_ids, trace_ray_tree};
pub use view_color::{MISS_COLOR, id_color, view_colors};
