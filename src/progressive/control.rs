//! A render's control and report, whatever traces it: cancel, pause and resume from another
//! thread, the progress and ray counts other threads read, the statistics of each pass, and the
//! loop that runs a plan's passes one after another with a backend's sweep.

use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::{Duration, Instant};

use super::plan::Pass;
use crate::stats::{RayCounts, SharedRayCounts};

/// What one pass of progressive rendering did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassStats {
    pub pass: Pass,
    /// Pixels that took samples in this pass: those traced (not painted) in a block pass, all
    /// in a sample pass, those refined in an anti-aliasing round. Its samples are the eye rays
    /// in `rays.primary`.
    pub pixels: u64,
    pub rays: RayCounts,
    pub time: Duration,
}

/// A whole render.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderStats {
    pub passes: Vec<PassStats>,
    pub rays: RayCounts,
    pub time: Duration,
    /// The item buffer's raster pass and read-back before the render, when the CPU's eye rays
    /// start from it (not in `time`; the GPU tracer's raster pass is part of its render).
    pub raster_time: Duration,
}

impl RenderStats {
    /// Millions of rays per second over the whole render.
    pub fn mrays_per_second(&self) -> f64 {
        self.rays.total() as f64 / self.time.as_secs_f64().max(1e-9) / 1e6
    }
}

/// The render was cancelled before it finished.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cancelled;

/// Where a render is, readable from any thread.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Progress {
    /// Index of the running pass, and how many there are.
    pub pass: u32,
    pub passes: u32,
    /// Block size of the running pass (1 for sample and anti-aliasing passes).
    pub block_size: u32,
    /// Samples per pixel the running pass brings its pixels to (1 for block passes).
    pub samples: u32,
    /// Rows of blocks done in the running pass, and how many it has.
    pub rows_done: u32,
    pub rows: u32,
    pub finished: bool,
}

/// Lets other threads cancel, pause and resume a render and watch its progress.
#[derive(Debug, Default)]
pub struct RenderControl {
    cancelled: AtomicBool,
    /// While set, the tracing threads wait (asleep on `resumed`) before their next band.
    paused: Mutex<bool>,
    resumed: Condvar,
    pass: AtomicU32,
    passes: AtomicU32,
    block_size: AtomicU32,
    samples: AtomicU32,
    rows_done: AtomicU32,
    rows: AtomicU32,
    finished: AtomicBool,
    rays: SharedRayCounts,
    pixels: AtomicU64,
}

impl RenderControl {
    /// Stops the render at the next band (a paused render too).
    pub fn cancel(&self) {
        self.cancelled.store(true, Ordering::Relaxed);
        // Under the lock, so that a thread about to wait sees the flag or hears this.
        let _paused = self.paused.lock();
        self.resumed.notify_all();
    }

    /// Holds the render before its next band until [`resume`](Self::resume) (or a cancel).
    pub fn pause(&self) {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner()) = true;
    }

    pub fn resume(&self) {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner()) = false;
        self.resumed.notify_all();
    }

    pub fn is_paused(&self) -> bool {
        *self.paused.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Sleeps while the render is paused and not cancelled.
    fn wait_while_paused(&self) {
        let paused = self.paused.lock().unwrap_or_else(|e| e.into_inner());
        let _resumed = self
            .resumed
            .wait_while(paused, |paused| *paused && !self.is_cancelled())
            .unwrap_or_else(|e| e.into_inner());
    }

    pub fn is_cancelled(&self) -> bool {
        self.cancelled.load(Ordering::Relaxed)
    }

    pub fn progress(&self) -> Progress {
        Progress {
            pass: self.pass.load(Ordering::Relaxed),
            passes: self.passes.load(Ordering::Relaxed),
            block_size: self.block_size.load(Ordering::Relaxed),
            samples: self.samples.load(Ordering::Relaxed),
            rows_done: self.rows_done.load(Ordering::Relaxed),
            rows: self.rows.load(Ordering::Relaxed),
            finished: self.finished.load(Ordering::Relaxed),
        }
    }

    /// Pixel samples traced so far in this render (each pixel once per sample).
    pub fn pixels_traced(&self) -> u64 {
        self.pixels.load(Ordering::Relaxed)
    }

    /// Rays traced so far in this render.
    pub fn rays(&self) -> RayCounts {
        self.rays.get()
    }

    /// Before a band of a pass: waits while the render is paused; `Err` once it is cancelled.
    pub(crate) fn wait_for_band(&self) -> Result<(), Cancelled> {
        self.wait_while_paused();
        if self.is_cancelled() {
            Err(Cancelled)
        } else {
            Ok(())
        }
    }

    /// A pass of `rows` rows of `block_size` blocks starts, bringing its pixels to `samples`.
    pub(crate) fn start_pass(&self, block_size: u32, samples: u32, rows: u32) {
        self.block_size.store(block_size, Ordering::Relaxed);
        self.samples.store(samples, Ordering::Relaxed);
        self.rows.store(rows, Ordering::Relaxed);
        self.rows_done.store(0, Ordering::Relaxed);
    }

    /// A band of `rows` rows of the running pass is done: it took `samples` pixel samples and
    /// traced `counts`.
    pub(crate) fn band_done(&self, rows: u32, samples: u64, counts: &RayCounts) {
        self.rays.add(counts);
        self.pixels.fetch_add(samples, Ordering::Relaxed);
        self.rows_done.fetch_add(rows, Ordering::Relaxed);
    }
}

/// Runs the passes of `plan` one after another with a backend's `run_pass`, keeping `control`'s
/// progress and calling `on_pass` after each.
pub fn run_plan(
    plan: &[Pass],
    control: &RenderControl,
    mut on_pass: impl FnMut(&PassStats),
    mut run_pass: impl FnMut(Pass) -> Result<PassStats, Cancelled>,
) -> Result<RenderStats, Cancelled> {
    control.passes.store(plan.len() as u32, Ordering::Relaxed);
    let start = Instant::now();
    let mut stats = RenderStats::default();
    for (i, &pass) in plan.iter().enumerate() {
        control.pass.store(i as u32, Ordering::Relaxed);
        let pass_stats = run_pass(pass)?;
        stats.rays += pass_stats.rays;
        stats.passes.push(pass_stats);
        on_pass(&pass_stats);
    }
    stats.time = start.elapsed();
    control.finished.store(true, Ordering::Relaxed);
    Ok(stats)
}
