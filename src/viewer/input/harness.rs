//! A test harness for the viewer's input: feeds egui frames of events over an image area and
//! collects the [`Action`]s that [`mouse_and_keys::actions`] makes of them.

use egui::{Event, Pos2, vec2};

use super::action::Action;
use super::mouse_and_keys::{self, ImageArea};
use crate::viewer::layout::PixelRect;

/// Feeds egui frames of events (each frame 1/60 s after the last) over a 100×100 image area
/// showing a 10×10 image, and collects the actions.
pub struct Harness {
    pub ctx: egui::Context,
    time: f64,
}

impl Harness {
    pub fn new() -> Harness {
        Harness {
            ctx: egui::Context::default(),
            time: 0.0,
        }
    }

    pub fn frame(&mut self, events: Vec<Event>) -> Vec<Action> {
        self.time += 1.0 / 60.0;
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(Pos2::ZERO, vec2(100.0, 100.0))),
            time: Some(self.time),
            events,
            ..Default::default()
        };
        let mut actions = Vec::new();
        let mut output = self.ctx.run_ui(input, |ui| {
            let rect = ui.available_rect_before_wrap();
            let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
            let area = ImageArea {
                image_rect: PixelRect {
                    x: 0.0,
                    y: 0.0,
                    width: 100.0,
                    height: 100.0,
                },
                pixels_per_point: 1.0,
                image_size: (10, 10),
            };
            actions = mouse_and_keys::actions(ui.ctx(), &response, &area, 0.5);
        });
        // Nothing is painted here.
        output.textures_delta.clear();
        actions
    }

    pub fn frames(&mut self, frames: Vec<Vec<Event>>) -> Vec<Action> {
        frames.into_iter().flat_map(|e| self.frame(e)).collect()
    }
}
