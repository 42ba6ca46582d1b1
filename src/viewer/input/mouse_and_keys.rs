//! Mouse and keyboard navigation over the image, the conventions people know: left-drag orbits,
//! right- or middle-drag pans, the wheel dollies, W/A/S/D/Q/E fly, F frames the scene,
//! double-click sets the orbit centre; Ctrl+S saves and C prints the camera. A click that is not
//! a drag (or the key I) picks the pixel under the cursor (its ray tree is shown), Esc closes the
//! tree. B keeps a snapshot to compare with, V turns the split view on and off, X the difference
//! display (the live side as a heat map of its difference from the snapshot). Enter skips the
//! coarse passes (block size 1 at once), Space pauses and resumes refinement.
//! Ctrl+1…9 stores the camera as a view, 1…9 recalls it; T previews a turntable and P the path
//! through the views (again: stop). Turns one frame's egui input into [`Action`]s.

use egui::{Key, Modifiers, MouseWheelUnit, PointerButton};
use glam::Vec3;

use super::action::Action;
use crate::viewer::layout::{PixelRect, image_pixel, image_point};
use crate::viewer::scene::views::TURNTABLE_FRAMES;

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

/// The keys of views 1 to 9.
const VIEW_KEYS: [Key; 9] = [
    Key::Num1,
    Key::Num2,
    Key::Num3,
    Key::Num4,
    Key::Num5,
    Key::Num6,
    Key::Num7,
    Key::Num8,
    Key::Num9,
];

/// Where the image is and how big, for turning cursor positions into image points.
pub struct ImageArea {
    /// Where the image is shown (letterboxed, or filling the area in fit mode), in physical
    /// pixels.
    pub image_rect: PixelRect,
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
            area.image_rect,
            area.image_size.0,
            area.image_size.1,
            pos.x * ppp,
            pos.y * ppp,
        )
    {
        actions.push(Action::PickCentre { x, y });
    }
    // egui tells a click from a drag: released before moving past its drag threshold.
    let inspect_key = !ctx.egui_wants_keyboard_input()
        && ctx.input_mut(|i| i.consume_key(Modifiers::NONE, Key::I));
    let inspect_at = if response.clicked_by(PointerButton::Primary) {
        response.interact_pointer_pos()
    } else if inspect_key {
        response.hover_pos()
    } else {
        None
    };
    if let Some(pos) = inspect_at
        && let Some((x, y)) = image_pixel(
            area.image_rect,
            area.image_size.0,
            area.image_size.1,
            pos.x * ppp,
            pos.y * ppp,
        )
    {
        actions.push(Action::PickPixel { x, y });
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
        if i.consume_key(Modifiers::NONE, Key::R) {
            actions.push(Action::ToggleRays3d);
        }
        if i.consume_key(Modifiers::NONE, Key::Escape) {
            actions.push(Action::CloseRayTree);
        }
        if i.consume_key(Modifiers::NONE, Key::Enter) {
            actions.push(Action::Skip);
        }
        if i.consume_key(Modifiers::NONE, Key::Space) {
            actions.push(Action::TogglePause);
        }
        if i.consume_key(Modifiers::NONE, Key::B) {
            actions.push(Action::Snapshot);
        }
        if i.consume_key(Modifiers::NONE, Key::V) {
            actions.push(Action::ToggleCompare);
        }
        if i.consume_key(Modifiers::NONE, Key::X) {
            actions.push(Action::ToggleDifference);
        }
        for (number, key) in (1..).zip(VIEW_KEYS) {
            if i.consume_key(Modifiers::COMMAND, key) {
                actions.push(Action::StoreView(number));
            }
            if i.consume_key(Modifiers::NONE, key) {
                actions.push(Action::RecallView(number));
            }
        }
        if i.consume_key(Modifiers::NONE, Key::T) {
            actions.push(Action::Turntable(TURNTABLE_FRAMES));
        }
        if i.consume_key(Modifiers::NONE, Key::P) {
            actions.push(Action::PlayPath(None));
        }
        actions
    })
}

/// Whether a flying key is held (the viewer then keeps drawing frames).
pub fn flying(ctx: &egui::Context) -> bool {
    !ctx.egui_wants_keyboard_input()
        && ctx.input(|i| !i.modifiers.any() && FLY_KEYS.iter().any(|(k, _)| i.key_down(*k)))
}

#[cfg(test)]
mod tests {
    use egui::{Event, Pos2, TouchPhase, pos2, vec2};

    use super::*;
    use crate::viewer::input::harness::Harness;

    fn key(key: Key, pressed: bool, modifiers: Modifiers) -> Event {
        Event::Key {
            key,
            physical_key: None,
            pressed,
            repeat: false,
            modifiers,
        }
    }

    fn button(button: PointerButton, pressed: bool, pos: Pos2) -> Event {
        Event::PointerButton {
            pos,
            button,
            pressed,
            modifiers: Modifiers::NONE,
        }
    }

    /// A left click at `at`: moved there, pressed and released a frame apart.
    fn click(at: Pos2) -> Vec<Vec<Event>> {
        vec![
            vec![Event::PointerMoved(at)],
            vec![button(PointerButton::Primary, true, at)],
            vec![button(PointerButton::Primary, false, at)],
        ]
    }

    fn drag(with: PointerButton) -> Vec<Action> {
        let mut h = Harness::new();
        let start = pos2(50.0, 50.0);
        let mut frames = vec![
            vec![Event::PointerMoved(start)],
            vec![button(with, true, start)],
        ];
        for i in 1..=5 {
            frames.push(vec![Event::PointerMoved(
                start + vec2(4.0 * i as f32, 2.0 * i as f32),
            )]);
        }
        frames.push(vec![button(with, false, pos2(70.0, 60.0))]);
        h.frames(frames)
    }

    #[test]
    fn left_drag_orbits_with_the_cursor() {
        let actions = drag(PointerButton::Primary);
        let (yaw, pitch) = actions.iter().fold((0.0, 0.0), |(y, p), a| match a {
            Action::Orbit { yaw, pitch } => (y + yaw, p + pitch),
            other => panic!("unexpected {other:?}"),
        });
        // Dragged 20 right and 10 down (some of it may go to the drag threshold).
        assert!((-6.001..-3.0).contains(&yaw), "{yaw}");
        assert!(pitch > 1.5 && pitch < 3.001, "{pitch}");
    }

    #[test]
    fn right_and_middle_drag_pan() {
        for with in [PointerButton::Secondary, PointerButton::Middle] {
            let actions = drag(with);
            assert!(!actions.is_empty());
            assert!(
                actions
                    .iter()
                    .all(|a| matches!(a, Action::Pan { dx, dy } if *dx > 0.0 && *dy > 0.0)),
                "{actions:?}"
            );
        }
    }

    #[test]
    fn the_wheel_dollies_over_the_image() {
        let mut h = Harness::new();
        let wheel = Event::MouseWheel {
            unit: MouseWheelUnit::Line,
            delta: vec2(0.0, 2.0),
            phase: TouchPhase::Move,
            source: egui::MouseWheelSource::Wheel,
            modifiers: Modifiers::NONE,
        };
        let actions = h.frames(vec![
            vec![Event::PointerMoved(pos2(30.0, 30.0))],
            vec![wheel],
        ]);
        assert_eq!(actions, vec![Action::Dolly(2.0)]);
    }

    #[test]
    fn a_click_inspects_the_pixel_under_the_cursor_and_so_does_the_key_i() {
        let mut h = Harness::new();
        let actions = h.frames(click(pos2(55.0, 25.0)));
        assert_eq!(actions, vec![Action::PickPixel { x: 5, y: 2 }]);
        let actions = h.frames(vec![
            vec![Event::PointerMoved(pos2(99.0, 0.0))],
            vec![key(Key::I, true, Modifiers::NONE)],
            vec![key(Key::Escape, true, Modifiers::NONE)],
        ]);
        assert_eq!(
            actions,
            vec![Action::PickPixel { x: 9, y: 0 }, Action::CloseRayTree]
        );
    }

    #[test]
    fn double_click_picks_the_image_point() {
        let mut h = Harness::new();
        let at = pos2(55.0, 25.0);
        let mut frames = click(at);
        frames.extend(click(at).into_iter().skip(1));
        let actions = h.frames(frames);
        // Each click also inspects the pixel (the first cannot know a second will come).
        let (centre, inspect): (Vec<_>, Vec<_>) = actions
            .into_iter()
            .partition(|a| matches!(a, Action::PickCentre { .. }));
        assert_eq!(centre, vec![Action::PickCentre { x: 5.5, y: 2.5 }]);
        assert!(!inspect.is_empty());
        assert!(
            inspect
                .iter()
                .all(|a| *a == Action::PickPixel { x: 5, y: 2 })
        );
    }

    #[test]
    fn keys_fly_frame_save_and_print() {
        let mut h = Harness::new();
        let actions = h.frame(vec![
            key(Key::W, true, Modifiers::NONE),
            key(Key::D, true, Modifiers::NONE),
        ]);
        assert_eq!(
            actions,
            vec![Action::Fly {
                motion: Vec3::new(1.0, 0.0, 1.0),
                seconds: 0.5
            }]
        );
        assert!(flying(&h.ctx));
        let actions = h.frame(vec![
            key(Key::W, false, Modifiers::NONE),
            key(Key::D, false, Modifiers::NONE),
            key(Key::F, true, Modifiers::NONE),
            key(Key::C, true, Modifiers::NONE),
        ]);
        assert_eq!(actions, vec![Action::Frame, Action::PrintCamera]);
        assert!(!flying(&h.ctx));
        // Ctrl+S saves, and the S held with Ctrl does not fly backwards.
        let actions = h.frame(vec![
            Event::ModifiersChanged(Modifiers::COMMAND),
            key(Key::S, true, Modifiers::COMMAND),
        ]);
        assert_eq!(actions, vec![Action::Save]);
    }

    #[test]
    fn enter_skips_the_preview_and_space_pauses() {
        let mut h = Harness::new();
        let actions = h.frame(vec![
            key(Key::Enter, true, Modifiers::NONE),
            key(Key::Space, true, Modifiers::NONE),
        ]);
        assert_eq!(actions, vec![Action::Skip, Action::TogglePause]);
    }

    #[test]
    fn b_keeps_a_snapshot_v_turns_the_split_on_and_off_and_x_the_difference() {
        let mut h = Harness::new();
        let actions = h.frame(vec![key(Key::B, true, Modifiers::NONE)]);
        assert_eq!(actions, vec![Action::Snapshot]);
        let actions = h.frame(vec![
            key(Key::B, false, Modifiers::NONE),
            key(Key::V, true, Modifiers::NONE),
        ]);
        assert_eq!(actions, vec![Action::ToggleCompare]);
        let actions = h.frame(vec![
            key(Key::V, false, Modifiers::NONE),
            key(Key::X, true, Modifiers::NONE),
        ]);
        assert_eq!(actions, vec![Action::ToggleDifference]);
    }

    #[test]
    fn ctrl_digits_store_views_digits_recall_them_and_t_and_p_preview() {
        let mut h = Harness::new();
        let actions = h.frame(vec![
            Event::ModifiersChanged(Modifiers::COMMAND),
            key(Key::Num3, true, Modifiers::COMMAND),
        ]);
        assert_eq!(actions, vec![Action::StoreView(3)]);
        let actions = h.frame(vec![
            Event::ModifiersChanged(Modifiers::NONE),
            key(Key::Num3, false, Modifiers::COMMAND),
            key(Key::Num9, true, Modifiers::NONE),
            key(Key::T, true, Modifiers::NONE),
            key(Key::P, true, Modifiers::NONE),
        ]);
        assert_eq!(
            actions,
            vec![
                Action::RecallView(9),
                Action::Turntable(TURNTABLE_FRAMES),
                Action::PlayPath(None)
            ]
        );
    }
}
