//! The status lines: the current pass and block size, progress within the pass, the block size
//! the render started at (and whether the viewer picked it), whether it is paused, milliseconds
//! per pass; then rays traced by kind, the tracing speed, what traces (the CPU's threads or the
//! GPU) and the window's frame rate.

use std::time::Duration;

use raylab::progressive::Progress;
use raylab::stats::RayCounts;

/// What the status line reports about the running (or last) render.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderStatus {
    pub progress: Progress,
    /// Times of the passes finished so far.
    pub pass_times: Vec<Duration>,
    pub rays: RayCounts,
    /// Time since the render started (to its end, once finished).
    pub elapsed: Duration,
    /// Frames per second of the window.
    pub fps: f32,
    /// Photons in the caustic map (0: caustics off).
    pub photons: u32,
    /// The block size the render started at (0: not said), and whether the viewer picked it.
    pub start_block: u32,
    pub auto_block: bool,
    /// Refinement is paused.
    pub paused: bool,
    /// What traces: `cpu: N threads` or `gpu: ADAPTER (BACKEND)` (empty: not said yet).
    pub device: String,
}

/// Two lines of text.
pub fn status_line(s: &RenderStatus) -> String {
    let p = &s.progress;
    let state = if p.finished {
        format!("done: {} passes", p.passes)
    } else {
        let percent = if p.rows == 0 {
            0.0
        } else {
            100.0 * p.rows_done as f32 / p.rows as f32
        };
        let pass = if p.samples > 1 {
            format!("anti-aliasing to {} samples", p.samples)
        } else {
            format!("block {}", p.block_size)
        };
        format!(
            "pass {}/{} · {pass} · {percent:.0}%",
            p.pass + 1,
            p.passes.max(1)
        )
    };
    let start = match (s.start_block, s.auto_block) {
        (0, _) => String::new(),
        (b, true) => format!(" · started at block {b} (auto)"),
        (b, false) => format!(" · started at block {b}"),
    };
    let paused = if s.paused { "paused · " } else { "" };
    let pass_times = if s.pass_times.is_empty() {
        "–".to_string()
    } else {
        let ms: Vec<String> = s
            .pass_times
            .iter()
            .map(|t| format!("{:.1}", t.as_secs_f64() * 1e3))
            .collect();
        ms.join(" / ")
    };
    let r = &s.rays;
    let mrays = r.total() as f64 / s.elapsed.as_secs_f64().max(1e-9) / 1e6;
    let over_budget = if r.over_budget > 0 {
        format!(" · {} rays cut by the ray budget", r.over_budget)
    } else {
        String::new()
    };
    let device = if s.device.is_empty() {
        String::new()
    } else {
        format!(" on {}", s.device)
    };
    let items = if r.from_item_buffer > 0 {
        format!(" · {} from the item buffer", r.from_item_buffer)
    } else {
        String::new()
    };
    let caustics = if s.photons > 0 {
        format!(" · caustics: {} photons", s.photons)
    } else {
        String::new()
    };
    format!(
        "{paused}{state}{start} · ms per pass: {pass_times}{caustics}\nrays: {} eye ({} hit{items}), {} \
         shadow, {} reflected, {} transmitted{over_budget} · {mrays:.2} Mrays/s{device} · {:.0} fps",
        r.primary, r.primary_hits, r.shadow, r.reflected, r.transmitted, s.fps
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_running_render_shows_its_pass_block_and_progress() {
        let s = RenderStatus {
            progress: Progress {
                pass: 1,
                passes: 5,
                block_size: 8,
                rows_done: 16,
                rows: 64,
                finished: false,
                samples: 1,
            },
            pass_times: vec![Duration::from_micros(1_250), Duration::from_micros(12_340)],
            rays: RayCounts {
                primary: 1_000_000,
                primary_hits: 900_000,
                shadow: 500_000,
                reflected: 300_000,
                transmitted: 200_000,
                over_budget: 7,
                ..Default::default()
            },
            elapsed: Duration::from_secs(1),
            fps: 59.6,
            photons: 0,
            start_block: 0,
            auto_block: false,
            paused: false,
            device: String::new(),
        };
        let line = status_line(&s);
        assert!(line.starts_with("pass 2/5 · block 8 · 25%"), "{line}");
        assert!(line.contains("ms per pass: 1.2 / 12.3\nrays:"), "{line}");
        assert!(
            line.contains("transmitted · 7 rays cut by the ray budget"),
            "{line}"
        );
        assert!(
            line.contains("1000000 eye (900000 hit), 500000 shadow"),
            "{line}"
        );
        assert!(line.contains("2.00 Mrays/s · 60 fps"), "{line}");
        let on_gpu = RenderStatus {
            device: "gpu: llvmpipe (vulkan)".into(),
            ..s
        };
        let line = status_line(&on_gpu);
        assert!(
            line.contains("2.00 Mrays/s on gpu: llvmpipe (vulkan) · 60 fps"),
            "{line}"
        );
        assert!(!line.contains("caustics"), "{line}");
    }

    #[test]
    fn with_caustics_on_the_photon_count_shows() {
        let s = RenderStatus {
            photons: 40_000,
            ..RenderStatus::default()
        };
        let line = status_line(&s);
        assert!(
            line.contains("ms per pass: – · caustics: 40000 photons\n"),
            "{line}"
        );
    }

    #[test]
    fn the_starting_block_size_and_a_pause_show() {
        let running = RenderStatus {
            progress: Progress {
                passes: 6,
                block_size: 32,
                rows: 10,
                ..Progress::default()
            },
            start_block: 32,
            auto_block: true,
            paused: true,
            ..RenderStatus::default()
        };
        let line = status_line(&running);
        assert!(
            line.starts_with("paused · pass 1/6 · block 32 · 0% · started at block 32 (auto) · "),
            "{line}"
        );
        let fixed = RenderStatus {
            start_block: 8,
            ..RenderStatus::default()
        };
        let line = status_line(&fixed);
        assert!(
            line.contains(" · started at block 8 · ms per pass"),
            "{line}"
        );
        assert!(!line.contains("paused"), "{line}");
    }

    #[test]
    fn an_anti_aliasing_round_says_how_many_samples_it_brings_pixels_to() {
        let s = RenderStatus {
            progress: Progress {
                pass: 6,
                passes: 8,
                block_size: 1,
                samples: 8,
                rows_done: 3,
                rows: 4,
                ..Progress::default()
            },
            ..RenderStatus::default()
        };
        let line = status_line(&s);
        assert!(
            line.starts_with("pass 7/8 · anti-aliasing to 8 samples · 75%"),
            "{line}"
        );
    }

    #[test]
    fn a_finished_render_says_so() {
        let s = RenderStatus {
            progress: Progress {
                passes: 5,
                finished: true,
                ..Progress::default()
            },
            ..RenderStatus::default()
        };
        let line = status_line(&s);
        assert!(
            line.starts_with("done: 5 passes · ms per pass: –\n"),
            "{line}"
        );
    }
}
