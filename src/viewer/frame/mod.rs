//! One frame: the panels, the inspector and the navigation (egui) with the overlay over the image,
//! the actions, restarting refinement and re-tracing the inspected pixel, the film
//! uploaded if it changed, the frame drawn and presented, the screenshot and exit when the
//! script is done, and when the next frame is due.

pub mod timing;

use std::time::{Duration, Instant};

use winit::event_loop::ActiveEventLoop;

use super::app::App;
use crate::viewer::gpu::painter::FrameContent;
use crate::viewer::gpu::screenshot;
use crate::viewer::gpu::surface::Acquired;
use crate::viewer::gpu::upload::write_texture;
use crate::viewer::input::action::Action;
use crate::viewer::input::mouse_and_keys::{self, ImageArea};
use crate::viewer::tracing::worker::Outcome;
use crate::viewer::ui::layout::{PixelRect, letterbox};
use crate::viewer::ui::overlay;
use crate::viewer::ui::panels;
use crate::viewer::ui::ray_tree_panel;

impl App {
    /// The panels, the status line and the image area; returns the actions and where the image
    /// goes (physical pixels).
    fn ui(&mut self, ui: &mut egui::Ui, seconds: f32) -> (Vec<Action>, PixelRect) {
        let mut actions = Vec::new();
        let status = self.status();
        panels::status_bar(ui, &status, &self.panel);
        let legend = self.rendering.as_ref().and_then(|r| r.report.legend());
        if let Some(controls) = &mut self.controls {
            actions.extend(panels::side_panel(
                ui,
                controls,
                &mut self.panel,
                legend.as_ref(),
            ));
        }
        actions.extend(ray_tree_panel::show(ui, &mut self.picked));
        if self.picked.hovered.is_some() {
            self.picked.want_object_ids();
        }
        let ppp = ui.ctx().pixels_per_point();
        let image_size = self
            .rendering
            .as_ref()
            .map_or((0, 0), |r| (r.film.width(), r.film.height()));
        let mut shown = PixelRect::ZERO;
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
            let area = PixelRect {
                x: rect.min.x * ppp,
                y: rect.min.y * ppp,
                width: rect.width() * ppp,
                height: rect.height() * ppp,
            };
            shown = letterbox(area, image_size.0, image_size.1);
            let image = egui::Rect::from_min_size(
                egui::pos2(shown.x / ppp, shown.y / ppp),
                egui::vec2(shown.width / ppp, shown.height / ppp),
            );
            let far = self.scene.as_ref().map_or(1.0, |s| overlay::far(s.bounds));
            self.overlay.paint(ui, &self.picked, image, image_size, far);
            if self.rendering.is_none() {
                let text = self
                    .panel
                    .load_error
                    .as_deref()
                    .unwrap_or("loading the scene…");
                ui.put(rect, egui::Label::new(text));
            }
            let area = ImageArea {
                shown,
                pixels_per_point: ppp,
                image_size,
            };
            actions.extend(mouse_and_keys::actions(ui.ctx(), &response, &area, seconds));
        });
        (actions, shown)
    }

    pub fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        let dt = now - self.last_frame;
        self.last_frame = now;
        let Some(gfx) = &mut self.gfx else { return };
        let mut raw_input = gfx.egui_state.take_egui_input(&gfx.window);
        self.synthetic.play(&mut raw_input.events);
        for time in self.picked.receive() {
            if self.timing.enabled() {
                eprintln!("stats: {time}");
            }
        }
        let ctx = self.egui_ctx.clone();
        let mut actions = Vec::new();
        let mut shown = None;
        let mut output = ctx.run_ui(raw_input, |ui| {
            let (a, s) = self.ui(ui, dt.as_secs_f32().min(0.1));
            actions = a;
            shown = Some(s);
        });
        let shown = shown.unwrap_or(PixelRect::ZERO);
        for action in actions {
            self.apply(action, shown);
        }
        self.sync_render(now);
        self.sync_picked_pixel();
        // The script sees what this frame's input started (a click's picked, say).
        if let Some(action) = self.options.script.next(self.idle(), self.loads) {
            self.apply(action, shown);
            self.sync_render(now);
            self.sync_picked_pixel();
        }
        let idle = self.idle();

        let Some(gfx) = &mut self.gfx else { return };
        gfx.egui_state
            .handle_platform_output(&gfx.window, output.platform_output);
        let primitives =
            ctx.tessellate(std::mem::take(&mut output.shapes), output.pixels_per_point);
        gfx.painter
            .set_textures(&gfx.gpu, &mut output.textures_delta);

        // Upload the film if it changed; remember how far the render was when it was read.
        let mut uploaded = None;
        if let Some(r) = &self.rendering {
            let progress = r.control.progress();
            let (texture, created) =
                gfx.painter
                    .quad
                    .image_texture(&gfx.gpu.device, r.film.width(), r.film.height());
            if created {
                self.uploader.invalidate();
            }
            let start = Instant::now();
            if let Some(rgba) = self.uploader.changed_pixels(&r.film) {
                write_texture(&gfx.gpu.queue, texture, rgba);
                self.timing.upload(start.elapsed());
                uploaded = Some(progress);
            } else if r.report.outcome().is_some() {
                uploaded = Some(progress);
            }
        }

        let content = FrameContent {
            primitives: &primitives,
            pixels_per_point: output.pixels_per_point,
            shown,
        };
        let mut presented = false;
        match gfx.surface.acquire(&gfx.gpu) {
            Acquired::Frame(frame) => {
                gfx.painter.paint(&gfx.gpu, &frame.texture, &content);
                gfx.window.pre_present_notify();
                gfx.gpu.queue.present(frame);
                presented = true;
            }
            Acquired::Retry => gfx.window.request_redraw(),
            Acquired::Skip => {}
        }
        let done =
            self.options.exit_when_done && presented && self.options.script.is_done() && idle;
        if done && let Some(path) = &self.options.screenshot {
            let size = gfx.surface.size();
            let format = gfx.surface.format();
            match screenshot::save(&gfx.gpu, &mut gfx.painter, format, size, &content, path) {
                Ok(()) => {
                    let s = shown;
                    println!(
                        "screenshot {}: {}×{} window, image at x {} y {} size {}×{}",
                        path.display(),
                        size.0,
                        size.1,
                        s.x,
                        s.y,
                        s.width,
                        s.height
                    );
                }
                Err(e) => self.error = Some(e),
            }
        }
        gfx.painter.free_textures(&mut output.textures_delta);

        let tracing = self.rendering.as_ref().is_some_and(|r| !r.settled);
        if presented {
            self.fps = 0.9 * self.fps + 0.1 / dt.as_secs_f32().max(1e-4);
            self.timing.frame(dt, tracing);
            if let (Some(r), Some(progress)) = (&mut self.rendering, uploaded) {
                r.shown(progress, &mut self.timing);
                if matches!(r.report.outcome(), Some(Outcome::Failed(_))) {
                    r.settled = true;
                }
            }
        }
        if done {
            if self.timing.enabled() {
                eprintln!("{}", self.timing.summary());
            }
            self.exit(event_loop);
            return;
        }

        // The next frame: soon while something moves, else when egui or an event asks.
        let animating = tracing
            || self.loading
            || mouse_and_keys::flying(&ctx)
            || !self.options.script.is_done()
            || !self.synthetic.is_empty();
        let egui_delay = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        let frame_time = Duration::from_secs_f32(1.0 / self.options.max_fps.max(1.0));
        self.next_frame = if animating {
            Some(now + frame_time)
        } else if egui_delay < Duration::from_secs(3600) {
            Some(now + egui_delay.max(frame_time))
        } else {
            None
        };
    }
}
