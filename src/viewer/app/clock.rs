//! When frames come: the time between them, the window's frame rate, and when the next frame is
//! due (soon while something moves, when egui asks, or not until an event arrives), with the
//! viewer's own measurements for `--stats`.

use std::time::{Duration, Instant};

use winit::event_loop::ControlFlow;

use crate::viewer::timing::Timing;

pub struct FrameClock {
    /// The measurements printed with `--stats`.
    pub timing: Timing,
    last_frame: Instant,
    fps: f32,
    next_frame: Option<Instant>,
    /// Most frames per second while something moves.
    max_fps: f32,
}

impl FrameClock {
    pub fn new(stats: bool, max_fps: f32) -> FrameClock {
        FrameClock {
            timing: Timing::new(stats),
            last_frame: Instant::now(),
            fps: 0.0,
            next_frame: None,
            max_fps,
        }
    }

    /// Starts a frame: the time now and since the frame before.
    pub fn start_frame(&mut self) -> (Instant, Duration) {
        let now = Instant::now();
        let dt = now - self.last_frame;
        self.last_frame = now;
        (now, dt)
    }

    /// The window's frame rate, smoothed.
    pub fn fps(&self) -> f32 {
        self.fps
    }

    /// A frame reached the screen `dt` after the one before, while `tracing` or not.
    pub fn presented(&mut self, dt: Duration, tracing: bool) {
        self.fps = 0.9 * self.fps + 0.1 / dt.as_secs_f32().max(1e-4);
        self.timing.frame(dt, tracing);
    }

    /// Sets when the next frame is due, for a frame started at `now`: soon while something is
    /// `animating`, else after `egui_delay` if egui asked for a repaint, else not until an event.
    pub fn schedule(&mut self, now: Instant, animating: bool, egui_delay: Duration) {
        let frame_time = Duration::from_secs_f32(1.0 / self.max_fps.max(1.0));
        self.next_frame = if animating {
            Some(now + frame_time)
        } else if egui_delay < Duration::from_secs(3600) {
            Some(now + egui_delay.max(frame_time))
        } else {
            None
        };
    }

    /// How the event loop waits for the next frame, and whether that frame is due now.
    pub fn wait(&mut self) -> (ControlFlow, bool) {
        match self.next_frame {
            Some(t) if Instant::now() >= t => {
                self.next_frame = None;
                (ControlFlow::Wait, true)
            }
            Some(t) => (ControlFlow::WaitUntil(t), false),
            None => (ControlFlow::Wait, false),
        }
    }
}
