//! Small editing widgets the panels share: a vector's three numbers, to drag or type.

use egui::DragValue;

/// A vector's three numbers, to drag or type, after `label`.
pub fn vector(ui: &mut egui::Ui, label: &str, v: &mut glam::Vec3) {
    ui.horizontal(|ui| {
        ui.label(label);
        for c in [&mut v.x, &mut v.y, &mut v.z] {
            ui.add(DragValue::new(c).speed(0.02).max_decimals(3));
        }
    });
}
