//! The picked pixel's ray tree drawn over the image (with egui's painter, on top of the image
//! quad): each ray projected through the camera as a line in its kind's colour, the colours of
//! the ray-tree figure ([`SegmentKind::color`]: eye white, reflected cyan, transmitted magenta,
//! shadow rays dashed yellow, or red with a cross where they are blocked), the picked pixel
//! framed in the image plane's grey, and a translucent mask over the object of the hovered node.

use egui::{Color32, Pos2, Rect, Shape, Stroke, TextureHandle, TextureOptions, pos2, vec2};
use glam::Vec2;
use raylab::aabb::Aabb;
use raylab::camera::Camera;
use raylab::figure::SegmentKind;
use raylab::inspect::RayTree;

use crate::viewer::workers::picked_pixel::PickedPixel;
use crate::viewer::workers::ray_tree_thread::ObjectIds;

/// Shadow rays are dashed over the image (solid in the figure seen from outside).
fn dashed(kind: SegmentKind) -> bool {
    matches!(kind, SegmentKind::Shadow | SegmentKind::ShadowBlocked)
}

/// A line's colour as egui paints it.
fn color32(kind: SegmentKind) -> Color32 {
    let [r, g, b] = kind.color();
    Color32::from_rgb(r, g, b)
}

/// A ray projected onto the image, in image pixels (x right, y down).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    pub kind: SegmentKind,
    pub from: Vec2,
    pub to: Vec2,
    /// Where a blocked shadow ray was stopped, if that point is in front of the eye.
    pub blocker: Option<Vec2>,
}

/// The rays of `tree` seen by `camera` on a `width × height` image: each ray from its origin
/// to its hit (`far` along it if it missed), each shadow ray to its light (`far` at most) or to
/// the blocker that stopped it. Rays wholly behind the eye are left out.
pub fn segments(
    tree: &RayTree,
    camera: &Camera,
    (width, height): (u32, u32),
    far: f32,
) -> Vec<Segment> {
    let project = |a, b| camera.project_segment(a, b, width, height);
    let mut out = Vec::new();
    for node in &tree.nodes {
        let end = node
            .hit
            .as_ref()
            .map_or(node.origin + node.dir * far, |h| h.point);
        if let Some((from, to)) = project(node.origin, end) {
            out.push(Segment {
                kind: SegmentKind::of_ray(node.kind),
                from,
                to,
                blocker: None,
            });
        }
        for shadow in &node.shadows {
            let stop = shadow
                .blockers
                .last()
                .filter(|_| shadow.blocked)
                .map(|b| b.t);
            let length = stop.unwrap_or(shadow.distance).min(far);
            let end = shadow.origin + shadow.dir * length;
            if let Some((from, to)) = project(shadow.origin, end) {
                let (kind, blocker) = match stop {
                    Some(_) => (
                        SegmentKind::ShadowBlocked,
                        camera.project(end, width, height),
                    ),
                    None => (SegmentKind::Shadow, None),
                };
                out.push(Segment {
                    kind,
                    from,
                    to,
                    blocker,
                });
            }
        }
    }
    out
}

/// How far a ray that missed is drawn: well past the scene (whose `bounds` planes leave out).
pub fn far(bounds: Aabb) -> f32 {
    let reach = if bounds.is_finite() && !bounds.is_empty() {
        bounds.extent().length() + bounds.center().length()
    } else {
        0.0
    };
    2.0 * reach.max(50.0)
}

/// The overlay's egui texture of the highlight mask, kept while the object and the ids stay.
#[derive(Default)]
pub struct Overlay {
    mask: Option<(u64, u32, TextureHandle)>,
}

impl Overlay {
    /// Paints the picked pixel's ray tree over `image` (the image's rectangle, in points) of a
    /// `size` image; `far` is how far a ray that missed is drawn.
    pub fn paint(
        &mut self,
        ui: &egui::Ui,
        picked: &PickedPixel,
        image: Rect,
        size: (u32, u32),
        far: f32,
    ) {
        let painter = ui.painter_at(image);
        let scale = vec2(
            image.width() / size.0.max(1) as f32,
            image.height() / size.1.max(1) as f32,
        );
        let to_screen = |p: Vec2| image.min + vec2(p.x * scale.x, p.y * scale.y);
        if let (Some(object), Some(ids)) = (picked.hovered, picked.current_object_ids())
            && ids.size == size
        {
            let stale = self
                .mask
                .as_ref()
                .is_none_or(|(k, o, _)| (*k, *o) != (ids.key, object));
            if stale {
                let texture = ui.ctx().load_texture(
                    "highlight",
                    highlight_mask(ids, object),
                    TextureOptions::NEAREST,
                );
                self.mask = Some((ids.key, object, texture));
            }
            if let Some((_, _, texture)) = &self.mask {
                let uv = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
                painter.image(texture.id(), image, uv, Color32::WHITE);
            }
        }
        let (Some(traced), Some((x, y))) = (&picked.tree, picked.pixel) else {
            return;
        };
        if !picked.show_overlay || traced.size != size {
            return;
        }
        for s in segments(&traced.tree, &traced.camera, size, far) {
            let stroke = Stroke::new(1.5, color32(s.kind));
            let (a, b) = (to_screen(s.from), to_screen(s.to));
            if dashed(s.kind) {
                painter.extend(Shape::dashed_line(&[a, b], stroke, 6.0, 4.0));
            } else {
                painter.line_segment([a, b], stroke);
            }
            if let Some(at) = s.blocker {
                cross(&painter, to_screen(at), stroke);
            }
        }
        let pixel = Rect::from_min_max(
            to_screen(Vec2::new(x as f32, y as f32)),
            to_screen(Vec2::new(x as f32 + 1.0, y as f32 + 1.0)),
        );
        let frame = Rect::from_center_size(pixel.center(), pixel.size().max(vec2(7.0, 7.0)));
        painter.rect_stroke(
            frame,
            0.0,
            Stroke::new(1.5, color32(SegmentKind::ImagePlane)),
            egui::StrokeKind::Outside,
        );
    }
}

fn cross(painter: &egui::Painter, at: Pos2, stroke: Stroke) {
    let d = 4.0;
    painter.line_segment([at + vec2(-d, -d), at + vec2(d, d)], stroke);
    painter.line_segment([at + vec2(-d, d), at + vec2(d, -d)], stroke);
}

/// Translucent magenta where `object` is seen, clear elsewhere.
pub fn highlight_mask(ids: &ObjectIds, object: u32) -> egui::ColorImage {
    let mark = Color32::from_rgba_unmultiplied(255, 0, 255, 110);
    let pixels = ids
        .ids
        .iter()
        .map(|&id| {
            if id == object {
                mark
            } else {
                Color32::TRANSPARENT
            }
        })
        .collect();
    egui::ColorImage::new([ids.size.0 as usize, ids.size.1 as usize], pixels)
}

#[cfg(test)]
mod tests {
    use raylab::inspect::trace_ray_tree;

    use super::*;
    use crate::viewer::scene::source;

    #[test]
    fn the_overlay_uses_the_figures_colours_and_dashes_only_shadow_rays() {
        use strum::IntoEnumIterator;
        for kind in SegmentKind::iter() {
            let [r, g, b] = kind.color();
            assert_eq!(color32(kind), Color32::from_rgb(r, g, b));
        }
        let dashed: Vec<_> = SegmentKind::iter().filter(|&k| dashed(k)).collect();
        assert_eq!(
            dashed,
            vec![SegmentKind::Shadow, SegmentKind::ShadowBlocked]
        );
    }

    #[test]
    fn the_eye_ray_lands_on_its_pixel_and_blocked_shadow_rays_are_marked() {
        let mut loaded = source::load(None, None).unwrap();
        let size = 32;
        (
            loaded.assembled.scene.settings.width,
            loaded.assembled.scene.settings.height,
        ) = (size, size);
        let tracer = loaded.assembled.tracer();
        let camera = loaded.assembled.scene.camera;
        let mut blocked = 0;
        for (x, y) in (0..size).flat_map(|y| (0..size).map(move |x| (x, y))) {
            let tree = trace_ray_tree(&tracer, x, y);
            let segments = segments(&tree, &camera, (size, size), far(loaded.bounds));
            let eye = segments[0];
            assert_eq!(eye.kind, SegmentKind::Eye);
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            for end in [eye.from, eye.to] {
                assert!(end.distance(centre) < 0.01, "({x}, {y}): {eye:?}");
            }
            for s in &segments {
                assert_eq!(s.blocker.is_some(), s.kind == SegmentKind::ShadowBlocked);
            }
            blocked += segments
                .iter()
                .filter(|s| s.kind == SegmentKind::ShadowBlocked)
                .count();
        }
        assert!(blocked > 0, "the default scene has shadows");
    }

    #[test]
    fn the_mask_covers_the_hovered_object_only() {
        let ids = ObjectIds {
            key: 1,
            ids: vec![0, 1, u32::MAX, 1],
            size: (2, 2),
            time: Default::default(),
        };
        let mask = highlight_mask(&ids, 1);
        assert_eq!(mask.size, [2, 2]);
        let covered: Vec<bool> = mask.pixels.iter().map(|p| p.a() > 0).collect();
        assert_eq!(covered, vec![false, true, false, true]);
    }
}
