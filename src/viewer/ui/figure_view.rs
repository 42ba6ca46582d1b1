//! The ray-tree figure over the image while an observer looks at it: the layer the ray tree
//! thread drew (the image plane, the lines and the markers, in their exact colours) painted over
//! the observer's render, and the line under the cursor, whose node the ray tree panel then
//! highlights.

use egui::{Color32, Rect, TextureHandle, TextureOptions, pos2};
use glam::Vec2;
use raylab::camera::Camera;
use raylab::figure::Layer;

use crate::viewer::workers::picked_pixel::PickedPixel;

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
        image: Rect,
        size: (u32, u32),
    ) {
        picked.figure.hovered_node = None;
        let Some(drawn) = &picked.figure.drawn else {
            return;
        };
        let layer = &drawn.layer;
        if (layer.width, layer.height) != size {
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

/// The node of the line nearest to the image point `at` (pixels), within `within` pixels.
fn nearest_node(
    observer: &Camera,
    drawn: &crate::viewer::workers::ray_tree_thread::FigureLayer,
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
