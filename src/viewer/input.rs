//! Mouse and keyboard navigation over the image, the conventions people know: left-drag orbits,
//! right- or middle-drag pans, the wheel dollies, W/A/S/D/Q/E fly, F frames the scene,
//! double-click sets the orbit centre; Ctrl+S saves and C prints the camera. Turns one frame's
//! egui input into [`Action`]s.

use egui::{Key, Modifiers, MouseWheelUnit, PointerButton};
use glam::Vec3;

use super::action::Action;
use super::layout::{PixelRect, image_point};

/// Degrees of orbit per point of drag.
const ORBIT_DEGREES_PER_POINT: f32 = 0.3;
/// Points of smooth scrolling that count as one wheel step.
const POINTS_PER_WHEEL_STEP: f32 = 50.0;

/// The flying keys and their directions (x right, y up, z forward).
const FLY_KEYS: [(Key, Vec3); 6] = [
    (Key::W, Vec3::Z),
    (Key::S, Vec3::NEG_Z),
    (Key::A, Vec3::NEG_X),
    (Key::D, Vec3::X),
    (Key::E, Vec3::Y),
    (Key::Q, Vec3::NEG_Y),
];

/// Where the image is and how big, for turning cursor positions into image points.
pub struct ImageArea {
    /// The letterboxed image, in physical pixels.
    pub shown: PixelRect,
    pub pixels_per_point: f32,
    pub image_size: (u32, u32),
}

/// The actions of this frame's input: the mouse over the image area (`response`) and the keys
/// when no text field has the keyboard. `seconds` is the frame's length, for flying.
pub fn actions(
    ctx: &egui::Context,
    response: &egui::Response,
    area: &ImageArea,
    seconds: f32,
) -> Vec<Action> {
    let mut actions = Vec::new();
    let ppp = area.pixels_per_point;
    let drag = response.drag_delta();
    if drag != egui::Vec2::ZERO {
        if response.dragged_by(PointerButton::Primary) {
            actions.push(Action::Orbit {
                yaw: -drag.x * ORBIT_DEGREES_PER_POINT,
                pitch: drag.y * ORBIT_DEGREES_PER_POINT,
            });
        } else if response.dragged_by(PointerButton::Secondary)
            || response.dragged_by(PointerButton::Middle)
        {
            actions.push(Action::Pan {
                dx: drag.x * ppp,
                dy: drag.y * ppp,
            });
        }
    }
    if response.double_clicked()
        && let Some(pos) = response.interact_pointer_pos()
        && let Some((x, y)) = image_point(
            area.shown,
            area.image_size.0,
            area.image_size.1,
            pos.x * ppp,
            pos.y * ppp,
        )
    {
        actions.push(Action::PickCentre { x, y });
    }
    if response.hovered() {
        let steps = ctx.input(|i| {
            i.events
                .iter()
                .map(|e| match e {
                    egui::Event::MouseWheel {
                        unit: MouseWheelUnit::Line,
                        delta,
                        ..
                    } => delta.y,
                    egui::Event::MouseWheel {
                        unit: MouseWheelUnit::Page,
                        delta,
                        ..
                    } => delta.y * 10.0,
                    egui::Event::MouseWheel { delta, .. } => delta.y / POINTS_PER_WHEEL_STEP,
                    _ => 0.0,
                })
                .sum::<f32>()
        });
        if steps != 0.0 {
            actions.push(Action::Dolly(steps));
        }
    }
    if !ctx.egui_wants_keyboard_input() {
        actions.extend(key_actions(ctx, seconds));
    }
    actions
}

fn key_actions(ctx: &egui::Context, seconds: f32) -> Vec<Action> {
    ctx.input_mut(|i| {
        let mut actions = Vec::new();
        if i.consume_key(Modifiers::COMMAND, Key::S) {
            actions.push(Action::Save);
        }
        let plain = !i.modifiers.any();
        let motion: Vec3 = FLY_KEYS
            .iter()
            .filter(|(key, _)| plain && i.key_down(*key))
            .map(|(_, dir)| *dir)
            .sum();
        if motion != Vec3::ZERO {
            actions.push(Action::Fly { motion, seconds });
        }
        if i.consume_key(Modifiers::NONE, Key::F) {
            actions.push(Action::Frame);
        }
        if i.consume_key(Modifiers::NONE, Key::C) {
            actions.push(Action::PrintCamera);
        }
        actions
    })
}

/// Whether a flying key is held (the viewer then keeps drawing frames).
pub fn flying(ctx: &egui::Context) -> bool {
    !ctx.egui_wants_keyboard_input()
        && ctx.input(|i| !i.modifiers.any() && FLY_KEYS.iter().any(|(k, _)| i.key_down(*k)))
}
