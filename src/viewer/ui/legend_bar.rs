//! The colour bar of a heat-map (or depth) view, drawn in the tracing panel under the view's
//! name: the legend's colours from low to high, its ticks and their labels.

use egui::{Align2, FontId, Rect, Sense, Stroke, pos2, vec2};
use raylab::inspect::Legend;

use super::swatch::color32;

const BAR_HEIGHT: f32 = 14.0;
const TICK_LENGTH: f32 = 4.0;
const LABEL_HEIGHT: f32 = 14.0;

/// Draws `legend` across the panel's width.
pub fn show(ui: &mut egui::Ui, legend: &Legend) {
    ui.label(&legend.label);
    let width = ui.available_width().min(280.0);
    let height = BAR_HEIGHT + TICK_LENGTH + LABEL_HEIGHT;
    let (rect, _) = ui.allocate_exact_size(vec2(width, height), Sense::hover());
    let painter = ui.painter_at(rect.expand(2.0));
    let n = legend.colors.len().max(1) as f32;
    for (i, &c) in legend.colors.iter().enumerate() {
        let x0 = rect.left() + width * i as f32 / n;
        let x1 = rect.left() + width * (i + 1) as f32 / n;
        let cell = Rect::from_x_y_ranges(x0..=x1, rect.top()..=rect.top() + BAR_HEIGHT);
        painter.rect_filled(cell, 0.0, color32(c));
    }
    let text = ui.visuals().text_color();
    for (position, label) in &legend.ticks {
        let x = rect.left() + width * position.clamp(0.0, 1.0);
        let bottom = rect.top() + BAR_HEIGHT;
        painter.line_segment(
            [pos2(x, bottom), pos2(x, bottom + TICK_LENGTH)],
            Stroke::new(1.0, text),
        );
        let align = match *position {
            p if p <= 0.0 => Align2::LEFT_TOP,
            p if p >= 1.0 => Align2::RIGHT_TOP,
            _ => Align2::CENTER_TOP,
        };
        let at = pos2(x, bottom + TICK_LENGTH);
        painter.text(at, align, label, FontId::proportional(11.0), text);
    }
}
