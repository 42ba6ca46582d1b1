//! The tracer's colours in egui: linear RGB to the sRGB bytes egui draws (as the image on screen
//! encodes them), and a swatch with its numbers.

use egui::{Color32, RichText};
use raylab::color::{Color, to_srgb8};

/// `c` (linear RGB, clamped to [0, 1]) as egui draws it.
pub fn color32(c: Color) -> Color32 {
    match to_srgb8(&[c.clamp(Color::ZERO, Color::ONE)])[..] {
        [r, g, b] => Color32::from_rgb(r, g, b),
        _ => Color32::MAGENTA,
    }
}

/// A small swatch of `c` and its numbers.
pub fn swatch(ui: &mut egui::Ui, c: Color) {
    ui.horizontal(|ui| {
        egui::color_picker::show_color(ui, color32(c), egui::vec2(22.0, 12.0));
        ui.label(RichText::new(format!("{:.3} {:.3} {:.3}", c.x, c.y, c.z)).monospace());
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_are_encoded_like_the_image() {
        assert_eq!(color32(Color::ZERO), Color32::BLACK);
        assert_eq!(
            color32(Color::new(1.0, 0.0, 4.0)),
            Color32::from_rgb(255, 0, 255)
        );
        // Linear 0.5 is sRGB 188, as the image's pixels are encoded.
        assert_eq!(color32(Color::splat(0.5)), Color32::from_rgb(188, 188, 188));
    }
}
