//! `--first-hit raster` as a user meets it: `render` on the CPU writes the rays' image byte for
//! byte, on the GPU the CPU's image within rounding, and says how many eye rays started from
//! the item buffer; the item-buffer view shows what the object view shows; `inspect` says where
//! a pixel's first hit came from; `bench` times the raster pass and both searches; and what
//! cannot be done (no GPU adapter) is a clear error. These need a GPU adapter (Mesa's lavapipe
//! will do): without one they fail, saying what to install.

use std::path::Path;
use std::process::Command;

use crate::common::run::{raylab, stderr};
use crate::harness::mean_level_difference;

/// `raylab render` of the default scene at 64 × 48 with `extra` arguments into `name`: the
/// file's bytes and the standard output.
fn render(dir: &Path, name: &str, extra: &[&str]) -> (Vec<u8>, String) {
    let args = [&["render", "--size", "64x48", "-o", name][..], extra].concat();
    let out = raylab(&args, dir);
    assert!(out.status.success(), "{extra:?}: {}", stderr(&out));
    let bytes = std::fs::read(dir.join(name)).unwrap();
    (bytes, String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The numbers N and M of a line `first hits: raster, N of M eye rays from the item buffer …`.
fn from_item_buffer(report: &str) -> (u64, u64) {
    let line = report
        .lines()
        .map(str::trim)
        .find_map(|line| line.strip_prefix("first hits: raster, "))
        .unwrap_or_else(|| panic!("no first-hits line in {report}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(words[1], "of", "{line}");
    assert!(line.contains(" eye rays from the item buffer"), "{line}");
    (words[0].parse().unwrap(), words[2].parse().unwrap())
}

#[test]
fn render_from_the_item_buffer_writes_the_rays_image_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    for samples in ["1", "4"] {
        let (rays, rays_report) = render(dir.path(), "rays.png", &["--samples", samples]);
        let (raster, report) = render(
            dir.path(),
            "raster.png",
            &["--samples", samples, "--first-hit", "raster"],
        );
        assert!(rays == raster, "--samples {samples}: the PNGs differ");
        assert!(!rays_report.contains("first hits"), "{rays_report}");
        let (from_items, eye_rays) = from_item_buffer(&report);
        assert!(eye_rays >= 64 * 48, "{report}");
        assert!(from_items > eye_rays / 2, "{report}");
    }
}

#[test]
fn the_gpu_tracer_from_the_item_buffer_writes_the_cpus_image_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let (on_cpu, _) = render(dir.path(), "cpu.png", &[]);
    let (on_gpu, report) = render(
        dir.path(),
        "gpu.png",
        &["--device", "gpu", "--first-hit", "raster"],
    );
    let pixels = |bytes: &[u8]| image::load_from_memory(bytes).unwrap().to_rgb8().into_raw();
    let (on_cpu, on_gpu) = (pixels(&on_cpu), pixels(&on_gpu));
    let mean = mean_level_difference(&on_gpu, &on_cpu);
    assert!(mean <= 0.5, "mean difference {mean} levels");
    let (from_items, eye_rays) = from_item_buffer(&report);
    assert_eq!(eye_rays, 64 * 48, "{report}");
    assert!(from_items > eye_rays / 2, "{report}");
    assert!(report.contains("(gpu: "), "{report}");
}

#[test]
fn the_item_buffer_view_shows_the_objects_the_rays_see() {
    let dir = tempfile::tempdir().unwrap();
    let (object, _) = render(dir.path(), "object.png", &["--view", "object"]);
    let (items, _) = render(dir.path(), "items.png", &["--view", "item-buffer"]);
    let pixels = |bytes: &[u8]| image::load_from_memory(bytes).unwrap().to_rgb8();
    let (object, items) = (pixels(&object), pixels(&items));
    let same = object
        .pixels()
        .zip(items.pixels())
        .filter(|(a, b)| a == b)
        .count();
    // Only pixels at a silhouette may differ.
    assert!(
        same * 100 >= 99 * 64 * 48,
        "{same} of {} pixels the same",
        64 * 48
    );
    assert!(items.pixels().any(|p| p.0 != [0, 0, 0]), "nothing drawn");
}

#[test]
fn inspect_says_whether_the_first_hit_came_from_the_item_buffer() {
    let dir = tempfile::tempdir().unwrap();
    let inspect = |pixel: &str, json: bool| {
        let mut args = vec!["inspect", "--pixel", pixel, "--first-hit", "raster"];
        if json {
            args.push("--json");
        }
        let out = raylab(&args, dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    // The middle of the default scene shows a glass ball; its top-left corner, the background.
    let ball = inspect("320,240", false);
    assert!(
        ball.contains("first hit: from the item buffer (sphere #"),
        "{ball}"
    );
    let background = inspect("5,5", false);
    assert!(
        background.contains("first hit: searched in full (the item buffer holds nothing here)"),
        "{background}"
    );
    let json: serde_json::Value = serde_json::from_str(&inspect("320,240", true)).unwrap();
    assert_eq!(json["first_hit"]["from"], "item-buffer", "{json}");
    let plain = raylab(&["inspect", "--pixel", "320,240"], dir.path());
    assert!(!String::from_utf8_lossy(&plain.stdout).contains("first hit:"));
}

#[test]
fn bench_times_the_raster_pass_and_both_searches() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "bench",
        "--scenes",
        "default",
        "--size",
        "32",
        "--repeat",
        "1",
        "--first-hit",
        "raster",
        "--json",
        "bench.json",
    ];
    let out = raylab(&args, dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let report = String::from_utf8_lossy(&out.stdout);
    let (from_items, eye_rays) = from_item_buffer(&report);
    assert_eq!(eye_rays, 32 * 32, "{report}");
    assert!(from_items > 0, "{report}");
    assert!(report.contains("raster pass and read-back"), "{report}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("bench.json")).unwrap())
            .unwrap();
    let first_hits = &json["scenes"][0]["first_hits"];
    assert_eq!(first_hits["eye_rays"], 32 * 32, "{json}");
    assert!(
        first_hits["nodes_per_eye_ray_raster"].as_f64().unwrap() > 0.0,
        "{json}"
    );
}

#[test]
fn what_the_item_buffer_cannot_do_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let no_adapter = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args([
            "render",
            "--first-hit",
            "raster",
            "--size",
            "16",
            "-o",
            "out.png",
        ])
        .current_dir(dir.path())
        .env("WGPU_ADAPTER_NAME", "no-such-gpu")
        .output()
        .unwrap();
    for (out, expected) in [
        (
            no_adapter,
            "--first-hit raster draws the item buffer on the GPU: no GPU adapter named like",
        ),
        (
            raylab(
                &["render", "--first-hit", "zbuffer", "-o", "out.png"],
                dir.path(),
            ),
            "unknown first-hit search `zbuffer`",
        ),
    ] {
        let message = stderr(&out);
        assert!(message.contains(expected), "{message}");
        assert!(!message.contains("panicked"), "{message}");
        assert!(matches!(out.status.code(), Some(1 | 2)), "{message}");
    }
    assert!(
        !dir.path().join("out.png").exists(),
        "no image for a refused render"
    );
}
