//! Measurements of the viewer itself, printed with `--stats`: frames per second while the tracer
//! runs, the time to upload the film, and for each restart the time from the change to the first
//! coarse image on screen, to block size 1 on screen and to the last pass on screen.

use std::time::{Duration, Instant};

/// How often the frame rate is printed.
const LOG_EVERY: Duration = Duration::from_secs(2);

pub struct Timing {
    enabled: bool,
    /// Frames drawn while tracing, and the time they covered.
    frames: u32,
    tracing: Duration,
    window_frames: u32,
    window_time: Duration,
    first_images: Vec<Duration>,
    block_ones: Vec<Duration>,
    /// Film-to-texture uploads and the time they took, and how many of them were made on the
    /// GPU from the GPU tracer's film.
    uploads: u32,
    upload_time: Duration,
    uploads_on_gpu: u32,
    last_log: Instant,
}

impl Timing {
    pub fn new(enabled: bool) -> Timing {
        Timing {
            enabled,
            frames: 0,
            tracing: Duration::ZERO,
            window_frames: 0,
            window_time: Duration::ZERO,
            first_images: Vec::new(),
            block_ones: Vec::new(),
            uploads: 0,
            upload_time: Duration::ZERO,
            uploads_on_gpu: 0,
            last_log: Instant::now(),
        }
    }

    /// A frame was drawn, `dt` after the one before.
    pub fn frame(&mut self, dt: Duration, tracing: bool) {
        if !tracing {
            return;
        }
        self.frames += 1;
        self.tracing += dt;
        self.window_frames += 1;
        self.window_time += dt;
        if self.enabled && self.last_log.elapsed() >= LOG_EVERY && self.window_time > Duration::ZERO
        {
            eprintln!(
                "stats: UI {:.1} fps while tracing; upload {:.2} ms on average",
                fps(self.window_frames, self.window_time),
                self.mean_upload_ms()
            );
            self.window_frames = 0;
            self.window_time = Duration::ZERO;
            self.last_log = Instant::now();
        }
    }

    /// The film was converted and written to the texture in `time`, on the GPU from the GPU
    /// tracer's film if `on_gpu`.
    pub fn upload(&mut self, time: Duration, on_gpu: bool) {
        self.uploads += 1;
        self.upload_time += time;
        self.uploads_on_gpu += u32::from(on_gpu);
    }

    fn mean_upload_ms(&self) -> f64 {
        ms(self.upload_time) / f64::from(self.uploads.max(1))
    }

    /// The first image of a restart reached the screen `after` the change.
    pub fn first_image(&mut self, after: Duration, block_size: u32) {
        self.first_images.push(after);
        if self.enabled {
            eprintln!(
                "stats: first image (block size {block_size}) {:.1} ms after the change",
                ms(after)
            );
        }
    }

    /// Prints what happened (caustic photons shot, say) with the other measurements.
    pub fn note(&self, what: impl std::fmt::Display) {
        if self.enabled {
            eprintln!("stats: {what}");
        }
    }

    /// Block size 1 reached the screen `after` the change.
    pub fn block_one(&mut self, after: Duration, pixels: (u32, u32)) {
        self.block_ones.push(after);
        if self.enabled {
            eprintln!(
                "stats: block size 1 at {}×{} {:.1} ms after the change",
                pixels.0,
                pixels.1,
                ms(after)
            );
        }
    }

    /// The last pass of a render (anti-aliasing included) reached the screen `after` the change.
    pub fn refined(&mut self, after: Duration, pixels: (u32, u32)) {
        if self.enabled {
            eprintln!(
                "stats: refined at {}×{} {:.1} ms after the change",
                pixels.0,
                pixels.1,
                ms(after)
            );
        }
    }

    /// One line over the whole session.
    pub fn summary(&self) -> String {
        format!(
            "stats: summary: UI {:.1} fps while tracing ({} frames); upload {:.2} ms on average \
             ({} of {} made on the GPU from its film); first image median {} over {} restarts; \
             block size 1 median {} over {} renders",
            fps(self.frames, self.tracing),
            self.frames,
            self.mean_upload_ms(),
            self.uploads_on_gpu,
            self.uploads,
            median_ms(&self.first_images),
            self.first_images.len(),
            median_ms(&self.block_ones),
            self.block_ones.len(),
        )
    }

    pub fn enabled(&self) -> bool {
        self.enabled
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn fps(frames: u32, time: Duration) -> f64 {
    frames as f64 / time.as_secs_f64().max(1e-9)
}

fn median_ms(times: &[Duration]) -> String {
    let mut sorted = times.to_vec();
    sorted.sort();
    match sorted.get(sorted.len() / 2) {
        Some(&median) => format!("{:.1} ms", ms(median)),
        None => "n/a".to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_summary_counts_frames_and_medians() {
        let mut t = Timing::new(false);
        for _ in 0..30 {
            t.frame(Duration::from_millis(20), true);
        }
        t.frame(Duration::from_secs(5), false);
        for ms in [30, 10, 20] {
            t.first_image(Duration::from_millis(ms), 16);
        }
        t.block_one(Duration::from_millis(700), (512, 512));
        t.upload(Duration::from_millis(1), false);
        t.upload(Duration::from_millis(3), true);
        let s = t.summary();
        assert!(s.contains("UI 50.0 fps while tracing (30 frames)"), "{s}");
        assert!(
            s.contains("upload 2.00 ms on average (1 of 2 made on the GPU from its film)"),
            "{s}"
        );
        assert!(
            s.contains("first image median 20.0 ms over 3 restarts"),
            "{s}"
        );
        assert!(
            s.contains("block size 1 median 700.0 ms over 1 renders"),
            "{s}"
        );
        assert!(Timing::new(false).summary().contains("n/a"));
    }
}
