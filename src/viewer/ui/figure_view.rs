//! The ray-tree figure over the image while an observer looks at it: the layer the ray tree
//! thread drew (the image plane, the lines and the markers, in their exact colours, hidden behind
//! surfaces) painted over the observer's render; while the observer moves on from the one it was
//! drawn for, its lines projected at once through the new observer instead; and the line under
//! the cursor, whose node the ray tree panel then highlights.

use egui::{Color32, Rect, Stroke, TextureHandle, TextureOptions, pos2, vec2};
use glam::Vec2;
use raylab::camera::Camera;
use raylab::figure::Layer;

use crate::viewer::workers::picked_pixel::PickedPixel;
use crate::viewer::workers::ray_tree_thread::FigureLayer;

/// How near the cursor must come to a line, in points, to hover it.
const HOVER_DISTANCE: f32 = 6.0;

/// The figure's egui texture, kept while the drawing it shows stays the newest.
#[derive(Default)]
pub struct FigureView {
    texture: Option<(u64, TextureHandle)>,
}

impl FigureView {
    /// Paints the picked pixel's figure over `image` (the image's rectangle, in points) of a
    /// `size` image rendered by `observer`, if it is drawn for that size; notes the node whose
    /// line the cursor is over.
    pub fn paint(
        &mut self,
        ui: &egui::Ui,
        picked: &mut PickedPixel,
        (image, size): (Rect, (u32, u32)),
        observer: Camera,
    ) {
        picked.figure.hovered_node = None;
        let Some(drawn) = &picked.figure.drawn else {
            return;
        };
        let layer = &drawn.layer;
        if (layer.width, layer.height) != size {
            return;
        }
        if drawn.ask.observer != observer {
            paint_lines(ui, drawn, (image, size), &observer);
            return;
        }
        let serial = picked.figure.serial;
        if self.texture.as_ref().is_none_or(|(s, _)| *s != serial) {
            let texture = ui.ctx().load_texture(
                "ray-tree figure",
                color_image(layer),
                TextureOptions::NEAREST,
            );
            self.texture = Some((serial, texture));
        }
        if let Some((_, texture)) = &self.texture {
            let uv = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
            ui.painter_at(image)
                .image(texture.id(), image, uv, Color32::WHITE);
        }
        let Some(cursor) = ui.ctx().pointer_hover_pos().filter(|p| image.contains(*p)) else {
            return;
        };
        let scale = image.width() / size.0.max(1) as f32;
        let at = Vec2::new(
            (cursor.x - image.min.x) / scale,
            (cursor.y - image.min.y) / scale,
        );
        picked.figure.hovered_node =
            nearest_node(&drawn.ask.observer, drawn, size, at, HOVER_DISTANCE / scale);
    }
}

/// The figure's lines projected through `observer`, unlit and in front of everything: what the
/// figure shows while its drawing for this observer is on its way.
fn paint_lines(
    ui: &egui::Ui,
    drawn: &FigureLayer,
    (image, size): (Rect, (u32, u32)),
    observer: &Camera,
) {
    let painter = ui.painter_at(image);
    let scale = image.width() / size.0.max(1) as f32;
    let to_screen = |p: Vec2| image.min + vec2(p.x, p.y) * scale;
    for segment in &drawn.figure.segments {
        if let Some((a, b)) = observer.project_segment(segment.from, segment.to, size.0, size.1) {
            let [r, g, b_] = segment.kind.color();
            let stroke = Stroke::new(2.0, Color32::from_rgb(r, g, b_));
            painter.line_segment([to_screen(a), to_screen(b)], stroke);
        }
    }
}

/// The node of the line nearest to the image point `at` (pixels), within `within` pixels.
fn nearest_node(
    observer: &Camera,
    drawn: &FigureLayer,
    (width, height): (u32, u32),
    at: Vec2,
    within: f32,
) -> Option<usize> {
    let lines = drawn.figure.segments.iter().filter_map(|s| {
        let (a, b) = observer.project_segment(s.from, s.to, width, height)?;
        let ab = b - a;
        let t = ((at - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
        Some((at.distance(a + ab * t), s.node?))
    });
    lines
        .filter(|(d, _)| *d <= within)
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, node)| node)
}

/// The layer as an egui image: its colours where it paints, clear elsewhere.
fn color_image(layer: &Layer) -> egui::ColorImage {
    let pixels = layer
        .pixels
        .iter()
        .map(|p| p.map_or(Color32::TRANSPARENT, |[r, g, b]| Color32::from_rgb(r, g, b)))
        .collect();
    egui::ColorImage::new([layer.width as usize, layer.height as usize], pixels)
}
