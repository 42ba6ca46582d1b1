//! The starting block size the viewer picks (the "auto" choice of the block size control): the
//! smallest block size whose first pass takes at most [`FIRST_PASS_BUDGET`] at the speed the
//! last passes were traced at, so the first image after a change comes within a frame at any
//! resolution (Cycles' viewport does the same). Without a measurement yet (the first render),
//! the scene's own block size is used. `raylab render` always starts at the settings' block
//! size.

use std::time::Duration;

use raylab::progressive::{Pass, PassStats};
use raylab::settings::MAX_BLOCK_SIZE;

/// How long the first (coarse) pass may take: half a frame at 60 frames per second, leaving the
/// rest for the upload and the drawing.
pub const FIRST_PASS_BUDGET: Duration = Duration::from_millis(8);

/// The traced pixels the speed is measured over: older passes count for less and less.
const MEMORY_PIXELS: f64 = 1_000_000.0;

/// The measured speed of tracing, and the starting block size it gives.
#[derive(Clone, Debug, Default)]
pub struct StartBlock {
    /// Seconds and pixels traced in the passes measured (the latest [`MEMORY_PIXELS`] pixels).
    seconds: f64,
    pixels: f64,
}

impl StartBlock {
    /// Takes the block passes of a render into the measurement (the anti-aliasing passes after
    /// them cost differently: they compare neighbours and sample only some pixels).
    pub fn observe(&mut self, passes: &[PassStats]) {
        for pass in passes.iter().filter(|p| matches!(p.pass, Pass::Block(_))) {
            self.seconds += pass.time.as_secs_f64();
            self.pixels += pass.pixels as f64;
        }
        if self.pixels > MEMORY_PIXELS {
            let keep = MEMORY_PIXELS / self.pixels;
            self.seconds *= keep;
            self.pixels *= keep;
        }
    }

    /// Seconds per traced pixel (wall time, all tracing threads together), once measured.
    pub fn seconds_per_pixel(&self) -> Option<f64> {
        (self.pixels >= 1.0).then(|| self.seconds / self.pixels)
    }

    /// The starting block size for a `width × height` image: the smallest power of two whose
    /// pass fits the budget (at most [`MAX_BLOCK_SIZE`]), or `fallback` before any measurement.
    pub fn choose(&self, width: u32, height: u32, fallback: u32) -> u32 {
        let Some(cost) = self.seconds_per_pixel() else {
            return fallback;
        };
        let budget = FIRST_PASS_BUDGET.as_secs_f64();
        let fits = |b: u32| {
            let pixels = f64::from(width.div_ceil(b)) * f64::from(height.div_ceil(b));
            pixels * cost <= budget
        };
        std::iter::successors(Some(1), |b| (b * 2 <= MAX_BLOCK_SIZE).then_some(b * 2))
            .find(|&b| fits(b))
            .unwrap_or(MAX_BLOCK_SIZE)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass(pixels: u64, micros: u64) -> PassStats {
        PassStats {
            pass: Pass::Block(1),
            pixels,
            rays: Default::default(),
            time: Duration::from_micros(micros),
        }
    }

    #[test]
    fn before_any_measurement_the_scenes_block_size_is_used() {
        assert_eq!(StartBlock::default().choose(2560, 1440, 16), 16);
        let mut none = StartBlock::default();
        none.observe(&[]);
        assert_eq!(none.choose(640, 480, 8), 8);
    }

    #[test]
    fn the_first_pass_fits_the_budget_at_any_size() {
        // 0.5 µs a pixel: 16 000 pixels in 8 ms.
        let mut start = StartBlock::default();
        let refine = PassStats {
            pass: Pass::Refine(1),
            ..pass(1_000, 50_000)
        };
        start.observe(&[pass(100_000, 20_000), pass(300_000, 180_000), refine]);
        assert_eq!(start.seconds_per_pixel(), Some(0.5e-6), "block passes only");
        // 512²: block 8 traces 4 096 pixels; block 4 would trace 16 384.
        assert_eq!(start.choose(512, 512, 1), 8);
        // 2560×1440: block 16 traces 14 400 pixels; block 8 would trace 57 600.
        assert_eq!(start.choose(2560, 1440, 1), 16);
        // A tiny image is traced at once.
        assert_eq!(start.choose(64, 64, 16), 1);
        for (w, h) in [(512, 512), (1280, 800), (2560, 1440), (4096, 4096)] {
            let b = start.choose(w, h, 1);
            let traced = f64::from(w.div_ceil(b) * h.div_ceil(b));
            assert!(traced * 0.5e-6 <= 0.008, "{w}×{h}: block {b}");
            if b > 1 {
                let finer = f64::from(w.div_ceil(b / 2) * h.div_ceil(b / 2));
                assert!(
                    finer * 0.5e-6 > 0.008,
                    "{w}×{h}: block {b} is not the smallest"
                );
            }
        }
    }

    #[test]
    fn a_slow_scene_starts_at_the_largest_block_and_old_passes_fade() {
        let mut start = StartBlock::default();
        // 1 ms a pixel: not even 64 fits.
        start.observe(&[pass(2_000, 2_000_000)]);
        assert_eq!(start.choose(2560, 1440, 1), MAX_BLOCK_SIZE);
        // Many fast passes later, the slow one is forgotten.
        for _ in 0..20 {
            start.observe(&[pass(1_000_000, 100_000)]);
        }
        let cost = start.seconds_per_pixel().unwrap();
        assert!(cost < 0.2e-6, "{cost}");
    }
}
