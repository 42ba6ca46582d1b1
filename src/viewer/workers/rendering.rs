//! The render in progress: the scene and controls it renders, its film and report, and what of
//! it has reached the screen.

use std::sync::Arc;
use std::time::Instant;

use raylab::film::Film;
use raylab::progressive::{Progress, RenderControl};

use super::worker::JobReport;
use crate::viewer::scene::ShownScene;
use crate::viewer::scene::controls::Controls;
use crate::viewer::scene::source::LoadedScene;
use crate::viewer::timing::Timing;

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
    /// The rounds of caustic photons added for this view before this render (0: a new view).
    pub caustic_round: u32,
    /// The block size it starts at (the viewer's choice when the controls say auto).
    pub start_block: u32,
    /// Its finished passes already taken into the measured tracing speed.
    pub passes_measured: usize,
}

impl Rendering {
    /// Whether this renders `shown`'s scene with its controls as they are.
    pub fn renders(&self, shown: &ShownScene) -> bool {
        Arc::ptr_eq(&self.scene, &shown.scene) && self.controls == *shown.rendered_controls()
    }

    /// Number of block passes (the block size 1 pass is the last of them).
    pub fn block_passes(&self) -> u32 {
        self.start_block.max(1).ilog2() + 1
    }

    /// Notes what a frame just put on screen: the film as it was at `progress`. The renders
    /// that sharpen caustics are not timed: nothing changed before them.
    pub fn reached_screen(&mut self, progress: Progress, timing: &mut Timing) {
        if self.caustic_round > 0 {
            self.settled |= progress.finished;
            return;
        }
        let after = self.changed_at.elapsed();
        if !self.first_image_shown && (progress.pass >= 1 || progress.finished) {
            self.first_image_shown = true;
            timing.first_image(after, self.start_block);
        }
        if !self.block_one_shown && (progress.pass >= self.block_passes() || progress.finished) {
            self.block_one_shown = true;
            let s = &self.controls.settings;
            timing.block_one(after, (s.width, s.height));
        }
        if progress.finished && !self.settled {
            self.settled = true;
            let s = &self.controls.settings;
            timing.refined(after, (s.width, s.height));
        }
    }
}
