//! How the image is shown, apart from how it is traced: the exposure and tone curve, and the
//! comparison with a snapshot (`B` keeps one, or `raylab view --compare IMAGE` gives one; the
//! split view shows it left of a draggable divider and the live image right of it, or with `X`
//! the heat map of the live image's difference from it). Owns their state, their side panel
//! section, and the divider and labels drawn over the image. Changing any of it never restarts
//! refinement.

use egui::{Color32, Slider, Stroke};
use raylab::tone::{Tone, ToneCurve};
use strum::IntoEnumIterator;

use crate::viewer::display::quad::Display;
use crate::viewer::display::upload::DIFFERENCE_TOP;
use crate::viewer::input::action::Action;

/// Points either side of the divider where a drag moves it.
const DIVIDER_GRIP: f32 = 6.0;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplayControls {
    pub tone: Tone,
    /// Split the image: the snapshot left of the divider, the live image right of it.
    pub compare: bool,
    /// While splitting, show the live image's difference from the snapshot instead of its
    /// colours.
    pub difference: bool,
    /// Where the divider is, as a fraction of the image's width from its left edge.
    pub divider: f32,
    /// The size of the image the snapshot was taken of, if one was; it is dropped when the
    /// image's size changes.
    pub snapshot: Option<(u32, u32)>,
    /// The snapshot is the user's own image (`--compare`), not one B kept: the split view's
    /// sides read "your image" and "raylab".
    pub snapshot_is_yours: bool,
}

impl Default for DisplayControls {
    fn default() -> DisplayControls {
        DisplayControls {
            tone: Tone::default(),
            compare: false,
            difference: false,
            divider: 0.5,
            snapshot: None,
            snapshot_is_yours: false,
        }
    }
}

impl DisplayControls {
    /// How the image is shown: the tone, and the divider while comparing.
    pub fn settings(&self) -> Display {
        Display {
            tone: self.tone,
            divider: if self.splits() { self.divider } else { 0.0 },
            difference: self.splits() && self.difference,
        }
    }

    /// The split view is on and has a snapshot to show.
    fn splits(&self) -> bool {
        self.compare && self.snapshot.is_some()
    }

    /// Carries out a display action (others do nothing here).
    pub fn apply(&mut self, action: Action) {
        match action {
            Action::Compare(on) => (self.compare, self.difference) = (on, false),
            Action::ToggleCompare => self.compare = !self.compare,
            Action::CompareDifference => (self.compare, self.difference) = (true, true),
            Action::ToggleDifference => {
                self.difference = !self.difference;
                self.compare |= self.difference;
            }
            Action::Divider(fraction) => self.divider = fraction.clamp(0.0, 1.0),
            Action::Exposure(stops) => {
                self.tone.exposure =
                    stops.clamp(*Tone::EXPOSURE_RANGE.start(), *Tone::EXPOSURE_RANGE.end());
            }
            Action::ToneCurve(curve) => self.tone.curve = curve,
            _ => {}
        }
    }

    /// Forgets the snapshot if the image (when there is one) no longer has its size; returns
    /// whether it did.
    pub fn drop_stale_snapshot(&mut self, image_size: (u32, u32)) -> bool {
        let stale = image_size != (0, 0) && self.snapshot.is_some_and(|s| s != image_size);
        if stale {
            self.snapshot = None;
        }
        stale
    }
}

/// The side panel's Display section: exposure, tone curve, snapshot and split.
pub fn section(ui: &mut egui::Ui, display: &mut DisplayControls, actions: &mut Vec<Action>) {
    egui::CollapsingHeader::new("Display")
        .default_open(true)
        .show(ui, |ui| {
            let tone = &mut display.tone;
            ui.add(
                Slider::new(&mut tone.exposure, Tone::EXPOSURE_RANGE)
                    .step_by(0.1)
                    .text("exposure (stops)"),
            );
            egui::ComboBox::from_label("tone curve")
                .selected_text(tone.curve.to_string())
                .show_ui(ui, |ui| {
                    for curve in ToneCurve::iter() {
                        ui.selectable_value(&mut tone.curve, curve, curve.to_string());
                    }
                });
            ui.horizontal(|ui| {
                if ui
                    .button("Snapshot (B)")
                    .on_hover_text("keep the image as it is now, to compare with")
                    .clicked()
                {
                    actions.push(Action::Snapshot);
                }
                ui.add_enabled(
                    display.snapshot.is_some(),
                    egui::Checkbox::new(&mut display.compare, "compare (V)"),
                );
                ui.add_enabled(
                    display.compare && display.snapshot.is_some(),
                    egui::Checkbox::new(&mut display.difference, "difference (X)"),
                )
                .on_hover_text(format!(
                    "the live side as the heat map of each pixel's largest channel difference \
                     from the snapshot: black equal, light yellow {DIFFERENCE_TOP} levels or more"
                ));
            });
            if display.snapshot.is_some() {
                ui.add(Slider::new(&mut display.divider, 0.0..=1.0).text("divider"));
            }
        });
}

/// While comparing: the divider over `image` (where the image is, in points) with a label on
/// each side, and dragging the divider. Call after the image area's own response, so that a
/// drag on the divider moves it instead of orbiting.
pub fn split_view(ui: &mut egui::Ui, display: &mut DisplayControls, image: egui::Rect) {
    if !display.splits() || image.width() < 1.0 {
        return;
    }
    let x = image.left() + display.divider * image.width();
    let grip = egui::Rect::from_x_y_ranges(x - DIVIDER_GRIP..=x + DIVIDER_GRIP, image.y_range());
    let response = ui
        .interact(
            grip,
            ui.make_persistent_id("split view divider"),
            egui::Sense::drag(),
        )
        .on_hover_cursor(egui::CursorIcon::ResizeHorizontal);
    if response.dragged()
        && let Some(pos) = response.interact_pointer_pos()
    {
        display.divider = ((pos.x - image.left()) / image.width()).clamp(0.0, 1.0);
    }
    let x = image.left() + display.divider * image.width();
    let painter = ui.painter_at(image);
    painter.vline(x, image.y_range(), Stroke::new(2.0, Color32::WHITE));
    let (left, right) = split_labels(display);
    // White on a dark shadow, readable over any image; each label stays whole inside the
    // image, on its side of the divider where there is room.
    let font = egui::FontId::proportional(14.0);
    let top = image.top() + 4.0;
    for (text, left_side) in [(left, true), (right, false)] {
        let galley = painter.layout_no_wrap(text.to_string(), font.clone(), Color32::WHITE);
        let width = galley.size().x;
        let wanted = if left_side { x - 6.0 - width } else { x + 6.0 };
        let most = (image.right() - 4.0 - width).max(image.left() + 4.0);
        let left_edge = wanted.clamp(image.left() + 4.0, most);
        for (offset, color) in [(1.0, Color32::BLACK), (0.0, Color32::WHITE)] {
            let at = egui::pos2(left_edge + offset, top + offset);
            painter.text(at, egui::Align2::LEFT_TOP, text, font.clone(), color);
        }
    }
}

/// The split view's labels, left and right of the divider: the user's image and raylab's, or a
/// snapshot B kept and the live image; the right side is the difference while it is shown.
pub fn split_labels(display: &DisplayControls) -> (&'static str, &'static str) {
    let left = if display.snapshot_is_yours {
        "your image"
    } else {
        "snapshot"
    };
    let right = match (display.difference, display.snapshot_is_yours) {
        (true, _) => "difference",
        (false, true) => "raylab",
        (false, false) => "live",
    };
    (left, right)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sides_name_the_users_image_and_raylabs() {
        let mut d = DisplayControls {
            snapshot_is_yours: true,
            ..Default::default()
        };
        assert_eq!(split_labels(&d), ("your image", "raylab"));
        d.difference = true;
        assert_eq!(split_labels(&d), ("your image", "difference"));
        d.snapshot_is_yours = false;
        d.difference = false;
        assert_eq!(split_labels(&d), ("snapshot", "live"));
    }

    #[test]
    fn the_split_shows_only_with_a_snapshot_and_compare_on() {
        let mut d = DisplayControls::default();
        d.apply(Action::Divider(0.3));
        d.apply(Action::Compare(true));
        assert_eq!(d.settings().divider, 0.0, "no snapshot yet");
        d.snapshot = Some((4, 3));
        assert_eq!(d.settings().divider, 0.3);
        d.apply(Action::ToggleCompare);
        assert_eq!(d.settings().divider, 0.0);
        d.apply(Action::Divider(7.0));
        assert_eq!(d.divider, 1.0);
    }

    #[test]
    fn the_difference_shows_only_in_the_split_and_compare_on_shows_the_image_again() {
        let mut d = DisplayControls {
            snapshot: Some((4, 3)),
            ..DisplayControls::default()
        };
        d.apply(Action::CompareDifference);
        assert!(d.settings().difference && d.settings().divider > 0.0);
        d.apply(Action::Compare(true));
        assert!(!d.settings().difference, "compare on: the live image");
        d.apply(Action::Compare(false));
        d.apply(Action::ToggleDifference);
        assert!(d.settings().difference, "X turns the split on too");
        d.apply(Action::ToggleCompare);
        assert!(!d.settings().difference, "no split, no difference");
        d.snapshot = None;
        d.apply(Action::CompareDifference);
        assert!(!d.settings().difference, "nothing to compare with");
    }

    #[test]
    fn exposure_and_curve_go_to_the_display() {
        let mut d = DisplayControls::default();
        d.apply(Action::Exposure(2.0));
        d.apply(Action::ToneCurve(ToneCurve::Reinhard));
        assert_eq!(
            d.settings().tone,
            Tone::new(2.0, ToneCurve::Reinhard).unwrap()
        );
    }

    #[test]
    fn a_new_image_size_drops_the_snapshot() {
        let mut d = DisplayControls {
            snapshot: Some((4, 3)),
            ..DisplayControls::default()
        };
        assert!(!d.drop_stale_snapshot((4, 3)));
        assert!(
            !d.drop_stale_snapshot((0, 0)),
            "no image: nothing to compare"
        );
        assert_eq!(d.snapshot, Some((4, 3)));
        assert!(d.drop_stale_snapshot((8, 3)));
        assert_eq!(d.snapshot, None);
    }

    /// Drags the left button from `from` to `to` over a 100×100 image area with the split view
    /// on; returns where the divider ends and whether the image itself was dragged.
    fn drag(from: egui::Pos2, to: egui::Pos2) -> (f32, bool) {
        let ctx = egui::Context::default();
        let mut display = DisplayControls {
            compare: true,
            snapshot: Some((10, 10)),
            ..DisplayControls::default()
        };
        let button = |pos, pressed| egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        };
        let mut frames = vec![
            vec![egui::Event::PointerMoved(from)],
            vec![button(from, true)],
        ];
        for k in 1..=5 {
            frames.push(vec![egui::Event::PointerMoved(
                from + (to - from) * k as f32 / 5.0,
            )]);
        }
        frames.push(vec![button(to, false)]);
        let mut image_dragged = false;
        for (k, events) in frames.into_iter().enumerate() {
            let input = egui::RawInput {
                screen_rect: Some(egui::Rect::from_min_size(
                    egui::Pos2::ZERO,
                    egui::vec2(100.0, 100.0),
                )),
                time: Some(k as f64 / 60.0),
                events,
                ..Default::default()
            };
            let mut output = ctx.run_ui(input, |ui| {
                let rect = ui.available_rect_before_wrap();
                let image = ui.allocate_rect(rect, egui::Sense::click_and_drag());
                image_dragged |= image.dragged();
                split_view(ui, &mut display, rect);
            });
            output.textures_delta.clear();
        }
        (display.divider, image_dragged)
    }

    #[test]
    fn dragging_the_divider_moves_it_and_does_not_orbit() {
        let (divider, image_dragged) = drag(egui::pos2(51.0, 50.0), egui::pos2(81.0, 40.0));
        assert!((divider - 0.8).abs() < 0.02, "{divider}");
        assert!(!image_dragged);
        // Away from the divider a drag is the image's (it orbits) and leaves the divider alone.
        let (divider, image_dragged) = drag(egui::pos2(20.0, 50.0), egui::pos2(40.0, 50.0));
        assert_eq!(divider, 0.5);
        assert!(image_dragged);
    }
}
