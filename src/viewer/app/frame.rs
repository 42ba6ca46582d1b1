//! One frame, in two steps. [`App::update`] changes the state: the window's input and the
//! script's clicks go through egui (the panels, the ray tree panel, the image area), the actions
//! are carried out, refinement restarts and the picked pixel is traced again if the scene or the
//! controls changed, the script takes its step, and the next frame is scheduled.
//! [`App::paint`] shows it: egui's shapes over the image (the film uploaded if it changed),
//! presented, and the screenshot when the script is done. Then the viewer exits if it is done.

use std::time::{Duration, Instant};

use winit::event_loop::ActiveEventLoop;

use super::App;
use crate::viewer::input::mouse_and_keys;
use crate::viewer::layout::PixelRect;

/// What an update hands to the paint.
pub struct Frame {
    output: egui::FullOutput,
    /// Where the image goes, in physical pixels.
    image_rect: PixelRect,
    /// The time since the frame before.
    dt: Duration,
    /// The viewer exits once this frame is on screen.
    finishing: bool,
}

impl App {
    /// Draws a frame (the window asked for one).
    pub fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let Some(frame) = self.update() else { return };
        let finishing = frame.finishing;
        if self.paint(frame) && finishing {
            if self.clock.timing.enabled() {
                eprintln!("{}", self.clock.timing.summary());
            }
            self.exit(event_loop);
        }
    }

    /// The state changes of a frame, up to what it will show; `None` without a window.
    fn update(&mut self) -> Option<Frame> {
        let (now, dt) = self.clock.start_frame();
        let gfx = self.gpu.as_mut()?;
        let mut raw_input = gfx.take_egui_input();
        self.input.play(&mut raw_input.events);
        for time in self.tracing.picked.receive() {
            if self.clock.timing.enabled() {
                eprintln!("stats: {time}");
            }
        }
        let status = self.tracing.status(self.scene.loading(), self.clock.fps());
        let seconds = dt.as_secs_f32().min(0.1);
        let ctx = self.ui.egui.clone();
        let mut actions = Vec::new();
        let mut image_rect = PixelRect::ZERO;
        let output = ctx.run_ui(raw_input, |ui| {
            (actions, image_rect) =
                self.ui
                    .show(ui, &mut self.scene, &mut self.tracing, &status, seconds);
        });
        for action in actions {
            self.apply(action, image_rect);
        }
        self.step_preview();
        self.sync_tracing(now);
        // The script sees what this frame's input started (a click's ray tree, say). Its steps
        // start once the first scene has loaded (or failed to): before, there is no camera.
        if self.scene.loads() > 0
            && let Some(action) = self.input.next_step(self.idle(), self.scene.loads())
        {
            self.apply(action, image_rect);
            self.sync_tracing(now);
        }
        let finishing = self.input.finishing(self.idle());

        // The next frame: soon while something moves, else when egui or an event asks.
        let animating = self.tracing.refining()
            || self.scene.loading()
            || mouse_and_keys::flying(&ctx)
            || self.input.busy()
            || self.previewing();
        let egui_delay = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        self.clock.schedule(now, animating, egui_delay);
        Some(Frame {
            output,
            image_rect,
            dt,
            finishing,
        })
    }

    /// Paints the frame and notes what reached the screen; returns whether it was presented.
    fn paint(&mut self, frame: Frame) -> bool {
        let Some(gfx) = &mut self.gpu else {
            return false;
        };
        let screenshot = self.input.screenshot().filter(|_| frame.finishing);
        gfx.set_display(self.ui.panel.display.settings());
        gfx.set_compared(self.ui.panel.compared.clone());
        // How far the render was before its film is read: the film is at least that far.
        let progress = self.tracing.progress();
        let rendering = self.tracing.rendering.as_ref();
        let film = rendering.map(|r| &r.film);
        let on_gpu = rendering.and_then(|r| r.report.film_on_gpu());
        let painted = gfx.paint(
            &self.ui.egui,
            frame.output,
            frame.image_rect,
            (film, on_gpu.as_deref()),
            screenshot,
        );
        if let Some((time, on_gpu)) = painted.upload {
            self.clock.timing.upload(time, on_gpu);
        }
        if let Some(e) = painted.screenshot_error {
            self.ended = Some(Err(e));
        }
        if painted.presented {
            self.clock.presented(frame.dt, self.tracing.refining());
            let on_screen = progress.filter(|_| painted.upload.is_some() || self.tracing.ended());
            self.tracing.on_screen(on_screen, &mut self.clock.timing);
        }
        painted.presented
    }

    /// Keeps the render and the picked pixel on the shown scene and its controls.
    fn sync_tracing(&mut self, changed_at: Instant) {
        let Some(shown) = self.scene.shown() else {
            return;
        };
        let max_side = self.ui.panel.max_side;
        let restarted = self.tracing.sync_render(shown, max_side, changed_at);
        if let Err(e) = self.tracing.sync_picked_pixel(shown, max_side) {
            eprintln!("{e}");
            self.ui.panel.message = Some(e);
        }
        if restarted {
            self.scene.keep_choices();
        }
    }

    /// Refinement of the current scene and controls is over and on screen, no scene is loading,
    /// the picked pixel's tree is traced, no scripted click is playing, and the window has the
    /// size it was last given, and no preview of the views plays.
    fn idle(&self) -> bool {
        let resizing = self.gpu.as_ref().is_some_and(|g| g.resizing());
        let settled = self.tracing.settled_on(self.scene.shown());
        let picking = self.tracing.picked.busy()
            || self.tracing.picked.figure_busy()
            || self.input.clicking();
        !self.scene.loading() && !resizing && settled && !picking && !self.previewing()
    }
}
