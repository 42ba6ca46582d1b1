//! The colour of one pixel sample in a debug view: a [`DebugView`] is a [`SampleColoring`], what
//! [`crate::progressive`] writes to the film for an eye ray. The first-hit views look at the eye
//! ray's hit; the tree views trace the whole Whitted tree (the renderer's own code) with an
//! observer that counts.

use glam::{Vec2, Vec3};

use super::debug_view::{DebugView, max_rays};
use super::legend::{
    BVH_COST_MAX, depth_grey, depth_range, heat, log_position, tree_depth_position,
};
use crate::bvh::cost::{BvhCost, TraversalCost};
use crate::color::Color;
use crate::item_buffer::Item;
use crate::primitive::{Hit, SurfacePoint};
use crate::progressive::{SampleColoring, Shaded};
use crate::ray::Ray;
use crate::sampling::hash;
use crate::stats::RayCounts;
use crate::whitted::{EYE_RAY_T_MIN, RayKind, Tracer, TreeObserver};

/// What a pixel whose eye ray misses shows in every view but the shaded one.
pub const MISS_COLOR: Color = Color::ZERO;

/// Each view's colour of the neighbouring eye rays `rays`. The shaded view is the renderer's
/// own [`Shaded`], with the eye rays traced as one packet.
impl SampleColoring for DebugView {
    fn shade(
        &self,
        tracer: &Tracer,
        rays: &[Ray],
        items: &[Option<Item>],
        colors: &mut [Color],
        counts: &mut RayCounts,
    ) {
        match *self {
            DebugView::Shaded => Shaded.shade(tracer, rays, items, colors, counts),
            DebugView::ItemBuffer => {
                let geometry = &tracer.scene.geometry;
                for (item, color) in items.iter().zip(colors) {
                    *color = item.map_or(MISS_COLOR, |item| {
                        let hit = Hit {
                            t: item.t,
                            prim: item.prim,
                            part: item.part,
                            bary: Vec2::ZERO,
                        };
                        id_color(geometry.part_id(&hit))
                    });
                }
            }
            view => {
                for (ray, color) in rays.iter().zip(colors) {
                    *color = debug_color(tracer, view, ray, counts);
                }
            }
        }
    }
}

/// The colour of one eye ray in a debug view other than the shaded one.
fn debug_color(tracer: &Tracer, view: DebugView, ray: &Ray, counts: &mut RayCounts) -> Color {
    let scene = tracer.scene;
    let tree_view = |tree: &TreeStats, rays: u64| match view {
        DebugView::TreeDepth => heat(tree_depth_position(tree.depth, scene.settings.max_depth)),
        DebugView::RayCount => heat(log_position(rays as f32, max_rays(scene) as f32)),
        _ => heat(log_position(tree.cost.total() as f32, BVH_COST_MAX)),
    };
    match view {
        DebugView::TreeDepth | DebugView::RayCount | DebugView::BvhCost => {
            let mut tree = TreeStats::default();
            let before = counts.total();
            tracer.trace_eye_observed(ray, counts, &mut tree);
            if tree.eye_hit {
                tree_view(&tree, counts.total() - before)
            } else {
                MISS_COLOR
            }
        }
        _ => first_hit_color(tracer, view, ray, counts),
    }
}

/// What the tree views need to know of a pixel's ray tree.
#[derive(Default)]
struct TreeStats {
    eye_hit: bool,
    /// The deepest ray's depth.
    depth: u32,
    cost: BvhCost,
}

impl TraversalCost for TreeStats {
    fn node_visited(&mut self) {
        self.cost.node_visited();
    }
    fn prims_tested(&mut self, count: usize) {
        self.cost.prims_tested(count);
    }
}

/// The cost of a pixel's tree without the shadow cache, so that it depends on the pixel alone,
/// not on the pixels its thread traced before.
impl TreeObserver for TreeStats {
    const USES_SHADOW_CACHE: bool = false;

    fn ray(&mut self, _: RayKind, depth: u32, _: &Ray, _: f32, _: Color) {
        self.depth = self.depth.max(depth);
    }
    fn hit(&mut self, _: &Hit, _: &SurfacePoint, _: Vec3, _: bool) {
        self.eye_hit = true;
    }
}

/// The first-hit views: normals, depth, UV, object and material ids.
fn first_hit_color(tracer: &Tracer, view: DebugView, ray: &Ray, counts: &mut RayCounts) -> Color {
    counts.primary += 1;
    let Some(hit) = tracer.closest_hit(ray, EYE_RAY_T_MIN) else {
        return MISS_COLOR;
    };
    counts.primary_hits += 1;
    let scene = tracer.scene;
    let geometry = &scene.geometry;
    let surface = geometry.surface(ray, &hit);
    match view {
        DebugView::Normals => surface.normal * 0.5 + 0.5,
        DebugView::Depth => {
            let (near, far) = depth_range(tracer);
            let depth = (surface.point - scene.camera.eye).dot(-scene.camera.n);
            depth_grey((depth - near) / (far - near))
        }
        DebugView::Uv => Vec3::new(
            surface.uv.x.rem_euclid(1.0),
            surface.uv.y.rem_euclid(1.0),
            0.0,
        ),
        DebugView::ObjectId => id_color(geometry.part_id(&hit)),
        _ => id_color(surface.material),
    }
}

/// A colour for `id`, distinct from its neighbours' (a hash), never black or near-black.
pub fn id_color(id: u32) -> Color {
    let h = hash(id.wrapping_mul(0x9e37_79b9) ^ 0x5bd1_e995);
    let channel = |shift: u32| 0.15 + 0.85 * ((h >> shift) & 0xff) as f32 / 255.0;
    Color::new(channel(0), channel(8), channel(16))
}
