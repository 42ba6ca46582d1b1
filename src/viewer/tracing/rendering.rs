//! The render in progress: restarting refinement when the scene or the controls change (the
//! running pass is cancelled and the new job starts from the coarse block size), what of it has
//! reached the screen, and the status line about it.

use std::sync::Arc;
use std::time::Instant;

use raylab::film::Film;
use raylab::progressive::{Progress, RenderControl};

use super::worker::{Job, JobReport, Outcome};
use crate::viewer::app::App;
use crate::viewer::frame::timing::Timing;
use crate::viewer::scene::controls::Controls;
use crate::viewer::scene::source::LoadedScene;
use crate::viewer::ui::status::{RenderStatus, status_line};

/// The render in progress (or the last one), and what of it has reached the screen.
pub struct Rendering {
    pub scene: Arc<LoadedScene>,
    pub controls: Controls,
    pub film: Arc<Film>,
    pub control: Arc<RenderControl>,
    pub report: Arc<JobReport>,
    /// When the change that started it was made.
    pub changed_at: Instant,
    pub first_image_shown: bool,
    pub block_one_shown: bool,
    /// The last pass is on screen (or the render failed): nothing more will come.
    pub settled: bool,
}

impl Rendering {
    /// Number of block passes (the block size 1 pass is the last of them).
    fn block_passes(&self) -> u32 {
        self.controls.settings.block_size.max(1).ilog2() + 1
    }

    /// Notes what a frame just put on screen: the film as it was at `progress`.
    pub fn shown(&mut self, progress: Progress, timing: &mut Timing) {
        let after = self.changed_at.elapsed();
        if !self.first_image_shown && (progress.pass >= 1 || progress.finished) {
            self.first_image_shown = true;
            timing.first_image(after, self.controls.settings.block_size);
        }
        if !self.block_one_shown && (progress.pass >= self.block_passes() || progress.finished) {
            self.block_one_shown = true;
            let s = &self.controls.settings;
            timing.block_one(after, (s.width, s.height));
        }
        if progress.finished {
            self.settled = true;
        }
    }
}

impl App {
    /// Restarts refinement if the scene or the controls differ from what is being rendered.
    pub fn sync_render(&mut self, changed_at: Instant) {
        let (Some(scene), Some(controls)) = (&self.scene, &self.controls) else {
            return;
        };
        let current = self
            .rendering
            .as_ref()
            .is_some_and(|r| Arc::ptr_eq(&r.scene, scene) && r.controls == *controls);
        if current {
            return;
        }
        let setup = match controls.setup(self.panel.max_side) {
            Ok(setup) => setup,
            Err(e) => {
                self.panel.control_error = Some(e);
                return;
            }
        };
        self.panel.control_error = None;
        let settings = &setup.settings;
        if self.options.size.is_some()
            || self.file_controls.as_ref().is_some_and(|f| {
                (f.settings.width, f.settings.height) != (settings.width, settings.height)
            })
        {
            // A size the user chose stays for the next scenes.
            self.options.size = Some((settings.width, settings.height));
        }
        // And so does the view.
        self.options.view = setup.view;
        let film = match &self.rendering {
            // The film is reused at the same size: the new render's first pass paints over
            // every pixel, and until then the old image stays on screen.
            Some(r) if (r.film.width(), r.film.height()) == (settings.width, settings.height) => {
                r.film.clone()
            }
            _ => Arc::new(Film::new(settings.width, settings.height)),
        };
        if let Some(old) = &self.rendering {
            old.control.cancel();
        }
        let control = Arc::new(RenderControl::default());
        let report = Arc::new(JobReport::new());
        let job = Job {
            scene: scene.clone(),
            setup,
            film: film.clone(),
            control: control.clone(),
            report: report.clone(),
        };
        if let Err(e) = self.worker.submit(job) {
            self.panel.control_error = Some(e);
        }
        self.rendering = Some(Rendering {
            scene: scene.clone(),
            controls: controls.clone(),
            film,
            control,
            report,
            changed_at,
            first_image_shown: false,
            block_one_shown: false,
            settled: false,
        });
    }

    /// Keeps the inspector on the current scene and controls, and takes what it traced.
    pub fn sync_picked_pixel(&mut self) {
        let (Some(scene), Some(controls)) = (&self.scene, &self.controls) else {
            return;
        };
        let setup = controls.setup(self.panel.max_side).ok();
        if let Err(e) = self.picked.sync(scene, controls, setup) {
            eprintln!("{e}");
            self.panel.message = Some(e);
        }
    }

    /// Refinement of the current scene and controls is over and on screen, no scene is loading,
    /// the inspector has traced its pixel and the window has the size it was last given.
    pub fn idle(&self) -> bool {
        // A resize the window system made but the surface has not caught up with yet.
        let resizing = self.gfx.as_ref().is_some_and(|g| {
            let size = g.window.inner_size();
            g.surface.size() != (size.width, size.height)
        });
        let settled = match (&self.rendering, &self.scene, &self.controls) {
            (Some(r), Some(scene), Some(controls)) => {
                let current = Arc::ptr_eq(&r.scene, scene) && r.controls == *controls;
                // Controls that cannot be rendered leave the last render as the final one.
                r.settled && (current || self.panel.control_error.is_some())
            }
            _ => false,
        };
        let inspecting = self.picked.busy() || !self.synthetic.is_empty();
        !self.loading && !resizing && settled && !inspecting
    }

    pub fn status(&self) -> String {
        let Some(r) = &self.rendering else {
            return if self.loading {
                "loading…"
            } else {
                "no scene"
            }
            .to_string();
        };
        let outcome = r.report.outcome();
        if let Some(Outcome::Failed(e)) = &outcome {
            return e.clone();
        }
        let pass_times: Vec<_> = r.report.passes().iter().map(|p| p.time).collect();
        let elapsed = match outcome {
            Some(_) if !pass_times.is_empty() => pass_times.iter().sum(),
            _ => r.report.started.elapsed(),
        };
        status_line(&RenderStatus {
            progress: r.control.progress(),
            pass_times,
            rays: r.control.rays(),
            elapsed,
            fps: self.fps,
        })
    }
}
