//! The tracing behind the window: the render worker refining the image, the render in progress,
//! the scene copies the tracing threads keep, the caustic photon map they share, and the picked
//! pixel whose ray tree is traced on its own thread. [`Tracing`] keeps both in step with the
//! shown scene and its controls, and, while they stay still, has the caustics sharpened; it
//! picks the starting block size from the measured tracing speed ([`start_block`]), and skips
//! the preview or pauses and resumes refinement when asked.

pub mod caustics;
pub mod picked_pixel;
pub mod ray_tree_thread;
pub mod rendering;
pub mod start_block;
pub mod status;
pub mod worker;
pub mod working_scene;

use std::sync::Arc;
use std::time::Instant;

use raylab::camera::Camera;
use raylab::film::Film;
use raylab::gpu::device::GpuDevice;
use raylab::progressive::{Progress, RenderControl};

use self::caustics::{MAX_ROUNDS, SharedCaustics};
use self::picked_pixel::PickedPixel;
use self::rendering::Rendering;
use self::start_block::StartBlock;
use self::status::{RenderStatus, status_line};
use self::worker::{Job, JobReport, Outcome, Worker};
use crate::viewer::scene::ShownScene;
use crate::viewer::scene::controls::TraceSetup;
use crate::viewer::timing::Timing;

/// The render and the picked pixel, each on its own threads.
pub struct Tracing {
    worker: Worker,
    /// The render in progress (or the last one), once a scene is shown.
    pub rendering: Option<Rendering>,
    /// The pixel whose ray tree is shown.
    pub picked: PickedPixel,
    /// Why the controls cannot be rendered as they are.
    pub control_error: Option<String>,
    /// The tracing speed measured so far, which picks the starting block size.
    start_block: StartBlock,
}

impl Tracing {
    /// Starts the render worker and the ray tree thread (each with `threads` tracing threads,
    /// 0: one per core; the worker renders on `gpu` what asks for the GPU, opening one then if
    /// `None`); `wake` tells the window a ray tree has come.
    pub fn start(
        threads: usize,
        gpu: Option<Arc<GpuDevice>>,
        wake: impl Fn() + Send + 'static,
    ) -> Result<Tracing, String> {
        let caustics = SharedCaustics::default();
        let worker = Worker::start(threads, caustics.clone(), gpu)?;
        let picked = PickedPixel::start(threads, caustics, wake)?;
        Ok(Tracing {
            worker,
            rendering: None,
            picked,
            control_error: None,
            start_block: StartBlock::default(),
        })
    }

    /// Restarts refinement if the scene or the controls differ from what is being rendered
    /// (`max_side`: the largest image side the GPU takes). Returns whether it restarted with
    /// them.
    pub fn sync_render(&mut self, shown: &ShownScene, max_side: u32, changed_at: Instant) -> bool {
        if self.rendering.as_ref().is_some_and(|r| r.renders(shown)) {
            self.sharpen_caustics(shown, max_side);
            return false;
        }
        let controls = shown.rendered_controls();
        let mut setup = match controls.setup(max_side) {
            Ok(setup) => setup,
            Err(e) => {
                self.control_error = Some(e);
                return false;
            }
        };
        self.control_error = None;
        if controls.auto_block {
            let s = &mut setup.settings;
            s.block_size = self.start_block.choose(s.width, s.height, s.block_size);
        }
        self.submit(shown, setup, changed_at);
        true
    }

    /// Skips the coarse passes of the render of `shown`: unless it already runs (or ran) at
    /// block size 1, it starts again there at once. A paused render resumes.
    pub fn skip(&mut self, shown: &ShownScene, max_side: u32) {
        let Some(r) = &self.rendering else {
            return;
        };
        let progress = r.control.progress();
        let at_one = progress.finished || progress.pass + 1 >= r.block_passes();
        if at_one || !r.renders(shown) {
            // A pending change restarts it anyway.
            self.set_paused(false);
            return;
        }
        if let Ok(mut setup) = shown.rendered_controls().setup(max_side) {
            setup.settings.block_size = 1;
            self.submit(shown, setup, Instant::now());
        }
    }

    /// Refinement is paused: the tracing threads sleep until it resumes or a change restarts it.
    pub fn paused(&self) -> bool {
        self.rendering
            .as_ref()
            .is_some_and(|r| r.control.is_paused() && !r.control.progress().finished)
    }

    /// Pauses or resumes the running render; returns whether that changed anything (a finished
    /// render has nothing to pause).
    pub fn set_paused(&mut self, paused: bool) -> bool {
        let Some(r) = &self.rendering else {
            return false;
        };
        if r.settled || r.control.progress().finished || self.paused() == paused {
            return false;
        }
        if paused {
            r.control.pause();
        } else {
            r.control.resume();
        }
        true
    }

    /// Once the image of a view with caustics is done and on screen, renders it again with
    /// another round of photons in the map, until the map holds [`MAX_ROUNDS`] rounds, starting
    /// at block size 1 so that the picture only sharpens.
    fn sharpen_caustics(&mut self, shown: &ShownScene, max_side: u32) {
        let Some(r) = &self.rendering else {
            return;
        };
        let done = r.settled && r.report.outcome() == Some(Outcome::Finished);
        let per_round = r.controls.settings.caustic_photons;
        if !done || per_round == 0 {
            return;
        }
        let rounds = r.report.photons() / per_round;
        if rounds >= MAX_ROUNDS {
            return;
        }
        if let Ok(mut setup) = shown.rendered_controls().setup(max_side) {
            setup.caustic_round = rounds;
            setup.settings.block_size = 1;
            self.submit(shown, setup, Instant::now());
        }
    }

    /// Starts rendering `shown` as `setup` says, on the film of the render before when it has
    /// the same size. With caustics, anti-aliasing waits for their last round: each round paints
    /// every pixel again at block size 1, which would throw the extra samples away.
    fn submit(&mut self, shown: &ShownScene, mut setup: TraceSetup, changed_at: Instant) {
        if setup.settings.caustic_photons > 0 && setup.caustic_round + 1 < MAX_ROUNDS {
            setup.settings.samples = 1;
        }
        let (caustic_round, start_block) = (setup.caustic_round, setup.settings.block_size);
        let (width, height) = (setup.settings.width, setup.settings.height);
        let film = match &self.rendering {
            // The film is reused at the same size: the new render's first pass paints over
            // every pixel, and until then the old image stays on screen.
            Some(r) if (r.film.width(), r.film.height()) == (width, height) => r.film.clone(),
            _ => Arc::new(Film::new(width, height)),
        };
        if let Some(old) = &self.rendering {
            old.control.cancel();
        }
        let control = Arc::new(RenderControl::default());
        let report = Arc::new(JobReport::new());
        let job = Job {
            scene: shown.scene.clone(),
            setup,
            film: film.clone(),
            control: control.clone(),
            report: report.clone(),
        };
        if let Err(e) = self.worker.submit(job) {
            self.control_error = Some(e);
        }
        self.rendering = Some(Rendering {
            scene: shown.scene.clone(),
            controls: shown.rendered_controls().into_owned(),
            film,
            control,
            report,
            changed_at,
            first_image_shown: false,
            block_one_shown: false,
            settled: false,
            caustic_round,
            start_block,
            passes_measured: 0,
        });
    }

    /// Keeps the picked pixel on the shown scene and controls; the error says why the pick was
    /// dropped.
    pub fn sync_picked_pixel(&mut self, shown: &ShownScene, max_side: u32) -> Result<(), String> {
        let setup = shown.controls.setup(max_side).ok();
        let synced = self.picked.sync(&shown.scene, &shown.controls, setup);
        let observer = shown.observer.and_then(|spec| Camera::new(spec).ok());
        self.picked.sync_figure(observer);
        synced
    }

    /// Refinement is under way (not paused): more passes will reach the screen.
    pub fn refining(&self) -> bool {
        self.rendering.as_ref().is_some_and(|r| !r.settled) && !self.paused()
    }

    /// Refinement of `shown` is over and on screen (controls that cannot be rendered leave the
    /// last render as the final one).
    pub fn settled_on(&self, shown: Option<&ShownScene>) -> bool {
        match (&self.rendering, shown) {
            (Some(r), Some(shown)) => {
                r.settled && (r.renders(shown) || self.control_error.is_some())
            }
            _ => false,
        }
    }

    /// How far the render is, once a scene is shown.
    pub fn progress(&self) -> Option<Progress> {
        self.rendering.as_ref().map(|r| r.control.progress())
    }

    /// The render has ended (finished, cancelled or failed): its film changes no more.
    pub fn ended(&self) -> bool {
        self.rendering
            .as_ref()
            .is_some_and(|r| r.report.outcome().is_some())
    }

    /// Notes what a frame just put on screen: the film as it was at `uploaded`, if it was read,
    /// and the caustic photons shot for it.
    pub fn on_screen(&mut self, uploaded: Option<Progress>, timing: &mut Timing) {
        if let Some(shot) = self.rendering.as_ref().and_then(|r| r.report.take_shot()) {
            timing.note(shot);
        }
        if let Some(r) = &mut self.rendering {
            let passes = r.report.passes();
            self.start_block
                .observe(passes.get(r.passes_measured..).unwrap_or_default());
            r.passes_measured = passes.len();
        }
        if let (Some(r), Some(progress)) = (&mut self.rendering, uploaded) {
            r.reached_screen(progress, timing);
            if matches!(r.report.outcome(), Some(Outcome::Failed(_))) {
                r.settled = true;
            }
        }
    }

    /// Stops the render (the viewer is closing).
    pub fn cancel(&self) {
        if let Some(r) = &self.rendering {
            r.control.cancel();
        }
    }

    /// The status line: the render's pass, progress and speed (`fps`: the window's frame rate),
    /// its error, or that a scene is `loading`.
    pub fn status(&self, loading: bool, fps: f32) -> String {
        let Some(r) = &self.rendering else {
            return if loading { "loading…" } else { "no scene" }.to_string();
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
            fps,
            photons: r.report.photons(),
            start_block: r.start_block,
            auto_block: r.controls.auto_block && r.caustic_round == 0,
            paused: self.paused(),
            device: r.report.device(),
        })
    }
}
