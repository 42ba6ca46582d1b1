//! Carrying out [`Action`]s: navigation moves the camera (through [`navigation`]), picking a
//! surface point sets the orbit centre, picking a pixel shows its ray tree (and [`rays3d`] its
//! figure, seen from outside), skip and pause steer
//! refinement, the display's actions (exposure, tone curve, snapshot, split view) change how the
//! image is shown, material and light edits change the controls, and the scene, save and print
//! actions do what they say.

use std::path::PathBuf;
use std::sync::Arc;

use raylab::camera::Camera;
use raylab::formats::toml::camera_table;
use raylab::srgb_image::SrgbImage;

use super::App;
use crate::viewer::input::action::Action;
use crate::viewer::input::{navigation, pick};
use crate::viewer::layout::{PixelRect, check_window_size, window_point};
use crate::viewer::save;
use crate::viewer::scene::ShownScene;
use crate::viewer::scene::edits::{LightEdit, MaterialEdit};
use crate::viewer::ui::ray_tree_panel;

impl App {
    /// Carries out `action`; `image_rect` is where the image is in the window (physical pixels).
    pub fn apply(&mut self, action: Action, image_rect: PixelRect) {
        match action {
            Action::Open(path) => {
                if let Some(p) = &path {
                    self.ui.panel.open_field = p.display().to_string();
                }
                self.start_load(path);
            }
            Action::Save => self.save(),
            Action::ResizeWindow { width, height } => {
                if let Some(gfx) = &self.gpu {
                    let size = winit::dpi::LogicalSize::new(width, height);
                    let physical = size.to_physical::<u32>(gfx.window().scale_factor());
                    let max = gfx.max_side();
                    match check_window_size(physical.width, physical.height, max, "this GPU") {
                        // The new size, if granted, arrives as a Resized event.
                        Ok(()) => _ = gfx.window().request_inner_size(size),
                        Err(e) => {
                            eprintln!("warning: the window is not resized: {e}");
                            self.ui.panel.message = Some(format!("not resized: {e}"));
                        }
                    }
                }
            }
            Action::PrintCamera => {
                if let Some(s) = self.scene.shown() {
                    println!("{}", save::camera_snippet(&s.controls.camera));
                    if let Some(observer) = &s.observer {
                        println!("{}", camera_table("observer", observer));
                    }
                    self.ui.panel.message = Some("camera printed on the terminal".into());
                }
            }
            Action::PickCentre { x, y } => self.pick_centre(x, y),
            Action::PickPixel { x, y } => self.pick_pixel((x, y)),
            Action::CloseRayTree => self.close_ray_tree(),
            Action::Rays3d(_)
            | Action::ToggleRays3d
            | Action::Rays3dOrbit { .. }
            | Action::Rays3dGenerations(_) => self.rays3d(action),
            Action::PrintTree => self.print_tree(),
            Action::Click { x, y } => self.click(x, y, image_rect),
            Action::Skip => {
                if let Some(shown) = self.scene.shown() {
                    self.tracing.skip(shown, self.ui.panel.max_side);
                }
            }
            Action::TogglePause => self.pause(!self.tracing.paused()),
            Action::Pause => self.pause(true),
            Action::Resume => self.pause(false),
            Action::PrintStatus => {
                let status = self.tracing.status(self.scene.loading(), self.clock.fps());
                println!("status: {}", status.replace('\n', " · "));
            }
            Action::Snapshot => self.snapshot(),
            Action::SetDebugView(debug_view) => {
                if let Some(s) = self.scene.shown_mut() {
                    s.controls.debug_view = debug_view;
                }
            }
            Action::SetDevice(device) => {
                if let Some(s) = self.scene.shown_mut() {
                    s.controls.device = device;
                }
            }
            Action::SetFirstHit(first_hit) => {
                if let Some(s) = self.scene.shown_mut() {
                    s.controls.first_hit = first_hit;
                }
            }
            display @ (Action::Compare(_)
            | Action::ToggleCompare
            | Action::CompareDifference
            | Action::ToggleDifference
            | Action::Divider(_)
            | Action::Exposure(_)
            | Action::ToneCurve(_)) => self.ui.panel.display.apply(display),
            Action::EditMaterial { name, edit } => self.edit_material(&name, edit),
            Action::EditLight { number, edit } => self.edit_light(number, edit),
            Action::SaveScene => {
                let message = self
                    .scene
                    .save_edits()
                    .unwrap_or_else(|e| format!("cannot save the scene: {e}"));
                println!("{message}");
                self.ui.panel.message = Some(message);
            }
            Action::StoreView(_)
            | Action::RecallView(_)
            | Action::Turntable(_)
            | Action::PlayPath(_) => self.views(action),
            other => {
                if let Some(s) = self.scene.shown_mut() {
                    navigate(s, other, image_rect);
                }
            }
        }
    }

    /// Changes a field of the material called `name`, or numbered `#K` (the script's `material`
    /// step).
    fn edit_material(&mut self, name: &str, edit: MaterialEdit) {
        let Some(s) = self.scene.shown_mut() else {
            return;
        };
        let names = &s.scene.scene().material_names;
        let number = || name.strip_prefix('#')?.parse::<usize>().ok();
        let index = names.iter().position(|n| n == name).or_else(number);
        match index.filter(|&i| i < names.len()) {
            Some(index) => edit.apply(&mut s.controls.materials[index]),
            None => {
                let message = format!(
                    "no material `{name}` in the scene (it has {})",
                    names.join(", ")
                );
                eprintln!("{message}");
                self.ui.panel.message = Some(message);
            }
        }
    }

    /// Changes a field of light `number`, counted from 1 (the script's `light` step).
    fn edit_light(&mut self, number: usize, edit: LightEdit) {
        let Some(s) = self.scene.shown_mut() else {
            return;
        };
        let count = s.controls.lights.len();
        let result = match number
            .checked_sub(1)
            .and_then(|i| s.controls.lights.get_mut(i))
        {
            Some(light) => edit.apply(light),
            None => Err(format!("the scene has {count} lights")),
        };
        if let Err(e) = result {
            let message = format!("cannot edit light {number}: {e}");
            eprintln!("{message}");
            self.ui.panel.message = Some(message);
        }
    }

    /// Pauses or resumes refinement, saying so with `--stats`.
    fn pause(&mut self, paused: bool) {
        if self.tracing.set_paused(paused) && self.clock.timing.enabled() {
            eprintln!("stats: {}", if paused { "paused" } else { "resumed" });
        }
    }

    fn pick_centre(&mut self, x: f32, y: f32) {
        let Some(ShownScene {
            scene, controls, ..
        }) = self.scene.shown_mut()
        else {
            return;
        };
        let Ok(camera) = Camera::new(controls.camera) else {
            return;
        };
        let size = (controls.settings.width, controls.settings.height);
        let point = pick::surface_point(scene.scene(), &scene.assembled.bvh, &camera, size, (x, y));
        match point.and_then(|p| navigation::look_at_point(&controls.camera, p)) {
            Some(spec) => controls.camera = spec,
            None => self.ui.panel.message = Some("no surface under the cursor".into()),
        }
    }

    /// A left click at the centre of image pixel (x, y), through egui like a mouse's.
    fn click(&mut self, x: u32, y: u32, image_rect: PixelRect) {
        let Some(r) = &self.tracing.rendering else {
            return;
        };
        let (width, height) = (r.film.width(), r.film.height());
        if x >= width || y >= height || image_rect.is_empty() {
            self.ui.panel.message = Some(format!(
                "cannot click pixel ({x}, {y}): it is outside the {width}×{height} image"
            ));
            return;
        }
        let (px, py) = window_point(image_rect, width, height, (x as f32 + 0.5, y as f32 + 0.5));
        let ppp = self.ui.egui.pixels_per_point();
        self.input.click(egui::pos2(px / ppp, py / ppp));
    }

    /// Prints the ray tree panel's headings, one line each, after `tree: `.
    fn print_tree(&self) {
        let picked = &self.tracing.picked;
        match (&picked.tree, &picked.error) {
            (_, Some(e)) => println!("tree: error: {e}"),
            (Some(traced), None) => {
                let tree = &traced.tree;
                for line in ray_tree_panel::heading_lines(tree) {
                    println!("tree: {line}");
                }
                let (x, y) = tree.pixel;
                let compared = self.ui.panel.compared.as_deref();
                if let Some(image) = compared.filter(|i| x < i.width && y < i.height) {
                    let tone = self.ui.panel.display.tone;
                    for line in ray_tree_panel::compared_lines(tree, image.at(x, y), tone) {
                        println!("tree: {line}");
                    }
                }
            }
            (None, None) => println!("tree: none"),
        }
    }

    /// Saves the image and the camera it was rendered with.
    fn save(&mut self) {
        let Some(r) = &self.tracing.rendering else {
            return;
        };
        let path = PathBuf::from(self.ui.panel.save_field.trim());
        let tone = self.ui.panel.display.tone;
        let message = save::save_view(&path, &r.film, &r.controls.camera, tone)
            .unwrap_or_else(|e| format!("cannot save: {e}"));
        println!("{message}");
        self.ui.panel.message = Some(message);
    }

    /// Keeps the image on screen as the snapshot (its pixels too, through the tone shown) and
    /// shows the split view.
    fn snapshot(&mut self) {
        let Some(gfx) = &mut self.gpu else { return };
        let panel = &mut self.ui.panel;
        let display = &mut panel.display;
        display.snapshot = gfx.snapshot();
        display.snapshot_is_yours = false;
        display.compare = display.snapshot.is_some();
        panel.compared = self.tracing.rendering.as_ref().map(|r| {
            let (width, height) = (r.film.width(), r.film.height());
            let pixels = (0..height)
                .flat_map(|y| (0..width).map(move |x| (x, y)))
                .map(|(x, y)| display.tone.map(r.film.get(x, y)))
                .collect();
            Arc::new(SrgbImage::new(width, height, pixels))
        });
        let message = match display.snapshot {
            Some(_) => "snapshot kept: it shows left of the divider (V: split on or off)",
            None => "no image to keep yet",
        };
        self.ui.panel.message = Some(message.into());
    }
}

impl App {
    /// Stores, recalls or previews the views (see [`crate::viewer::scene::views`]), saying what
    /// was done in the status message.
    fn views(&mut self, action: Action) {
        let Some(s) = self.scene.shown_mut() else {
            return;
        };
        let camera = s.controls.camera;
        let done = match action {
            Action::StoreView(n) => s.views.store(n, camera).inspect(|m| println!("{m}")),
            Action::RecallView(n) => match s.views.views.get(n) {
                Some(view) => {
                    s.controls.camera = view;
                    Ok(format!("view {n}"))
                }
                None => Err(format!("no view {n} yet: Ctrl+{n} stores one")),
            },
            Action::Turntable(frames) => s.views.toggle_turntable(camera, frames),
            Action::PlayPath(frames) => s.views.toggle_path(frames),
            _ => return,
        };
        self.ui.panel.message = Some(done.unwrap_or_else(|e| e));
    }

    /// A preview of the views is playing.
    pub fn previewing(&self) -> bool {
        self.scene.shown().is_some_and(|s| s.views.previewing())
    }

    /// Moves the camera to the preview's next frame once the frame before is on screen.
    pub fn step_preview(&mut self) {
        let Some(s) = self.scene.shown() else { return };
        let shown_before = self
            .tracing
            .rendering
            .as_ref()
            .is_some_and(|r| r.renders(s) && (r.first_image_shown || r.settled));
        let Some(s) = self.scene.shown_mut() else {
            return;
        };
        if shown_before && let Some(camera) = s.views.next_frame() {
            s.controls.camera = camera;
        }
    }
}

/// Moves the camera of `s` as a navigation action asks (the ray-tree figure's observer while it
/// is shown, else the scene camera); `image_rect` is where the image is in the window (physical
/// pixels), for panning.
fn navigate(s: &mut ShownScene, action: Action, image_rect: PixelRect) {
    let spec = s.observer.as_ref().unwrap_or(&s.controls.camera);
    let bounds = s.scene.bounds;
    let size = (s.controls.settings.width, s.controls.settings.height);
    let new = match action {
        Action::Orbit { yaw, pitch } => Some(navigation::orbit(spec, yaw, pitch)),
        Action::Pan { dx, dy } => {
            let height = if image_rect.is_empty() {
                size.1 as f32
            } else {
                image_rect.height
            };
            Some(navigation::pan(spec, dx, dy, height))
        }
        Action::Dolly(steps) => Some(navigation::dolly(spec, steps)),
        Action::Fly { motion, seconds } => {
            let distance = navigation::fly_speed(spec, bounds) * seconds;
            Some(navigation::fly(spec, motion, distance))
        }
        Action::Frame => spec.framing(&bounds, size.0 as f32 / size.1.max(1) as f32),
        Action::ResetCamera => Some(s.scene.scene().camera.spec),
        _ => None,
    };
    if let Some(new) = new {
        *s.observer.as_mut().unwrap_or(&mut s.controls.camera) = new;
    }
}
