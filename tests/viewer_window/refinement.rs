//! Progressive refinement in the window: passes down to block size 1 and anti-aliasing close to a
//! 256-sample reference, caustics sharpened while the view is still, a restart on a camera
//! change, skip, pause and resume, and uniform sampling that shows what `render` saves.

use std::process::Command;

use raylab::formats::toml::default_scene;

use crate::harness::{
    cpu_render, cpu_render_sampled, image_rect, mismatches, printed_camera, run_to_screenshot,
    shown_pixels,
};

/// Root mean square difference of two sRGB images, on a 0–1 scale.
fn rmse(a: &[u8], b: &[u8]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(&p, &q)| ((f64::from(p) - f64::from(q)) / 255.0).powi(2))
        .sum();
    (sum / a.len() as f64).sqrt()
}

#[test]
fn caustics_sharpen_while_the_view_is_still_and_a_camera_move_reuses_the_photons() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("caustic.toml");
    std::fs::write(
        &path,
        "[render]\ncaustic_photons = 5000\n[camera]\neye = [0, 3, 6]\nlook_at = [0, 0.5, 0]\n\
         [[lights]]\ntype = \"spot\"\nposition = [-2, 5, -2]\ndirection = [2, -5, 2]\n\
         angle = 30\nintensity = 30\n[materials.glass]\ndiffuse = 0\ntransparency = 1\n\
         ior = 1.5\n[[objects]]\ntype = \"plane\"\nnormal = [0, 1, 0]\n[[objects]]\n\
         type = \"sphere\"\ncenter = [0, 1, 0]\nradius = 1\nmaterial = \"glass\"\n",
    )
    .unwrap();
    let (run, _) = run_to_screenshot(
        dir.path(),
        &[
            path.to_str().unwrap(),
            "--size",
            "64",
            "--stats",
            "--script",
            "wait; orbit 20 0; wait",
        ],
    );
    let stats = &run.stderr;
    // The first view: a new map, then a round at a time up to 8 × 5000 photons.
    let (first, after_move) = stats
        .rsplit_once("stats: first image")
        .expect("two views were rendered");
    assert_eq!(
        first.matches("caustics: new map, 5000 photons").count(),
        1,
        "{stats}"
    );
    assert!(
        first.contains("caustics: sharpened, 40000 photons"),
        "{stats}"
    );
    assert!(!first.contains("45000 photons"), "{stats}");
    // The camera moved: the same photons serve, none are shot.
    assert!(!after_move.contains("caustics:"), "{stats}");
}

#[test]
fn a_scripted_camera_change_restarts_refinement_and_ends_on_the_new_view() {
    let dir = tempfile::tempdir().unwrap();
    let saved = dir.path().join("saved.png");
    let size = 80;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--samples",
            "1",
            "--block-size",
            "8",
            "--stats",
            "--script",
            "wait; orbit 40 15 4; dolly 1; wait; print-camera; save",
            "--save",
            saved.to_str().unwrap(),
        ],
    );
    let scene = default_scene().unwrap();
    let camera = printed_camera(&run.stdout);
    assert!(
        (camera.eye - scene.camera.spec.eye).length() > 0.5,
        "the camera moved"
    );
    assert_eq!(
        camera.look_at, scene.camera.spec.look_at,
        "orbit keeps the centre"
    );
    // Refinement ran to block size 1 once for the first view and again after the change.
    let block_ones = run.stderr.matches("block size 1 at").count();
    assert!(block_ones >= 2, "{}", run.stderr);
    let rect = image_rect(&run.stdout);
    let new_view = cpu_render(&scene, size, camera);
    assert_eq!(
        mismatches(&shot, rect, size, &new_view),
        0,
        "the window shows the new view"
    );
    let old_view = cpu_render(&scene, size, scene.camera.spec);
    assert!(mismatches(&shot, rect, size, &old_view) > (size * size / 10) as usize);
    // Save wrote the image itself and a camera snippet that reads back as the printed camera.
    assert_eq!(image::open(&saved).unwrap().to_rgb8().into_raw(), new_view);
    let snippet = std::fs::read_to_string(dir.path().join("saved.camera.toml")).unwrap();
    assert_eq!(printed_camera(&snippet), camera);
}

#[test]
fn left_alone_the_viewer_refines_the_default_scene_close_to_a_256_spp_reference() {
    let dir = tempfile::tempdir().unwrap();
    let size = 96;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--window",
            "700x500",
            "--stats",
        ],
    );
    assert!(run.stderr.contains("refined at 96×96"), "{}", run.stderr);
    let shown = shown_pixels(&shot, image_rect(&run.stdout), (size, size));
    let reference = cpu_render_sampled(size, 256, 0.0);
    let one_sample = cpu_render_sampled(size, 1, 0.0);
    let (shown_error, one_error) = (rmse(&shown, &reference), rmse(&one_sample, &reference));
    assert!(
        shown_error < 0.5 * one_error,
        "RMSE against 256 spp: the viewer {shown_error:.4}, one sample {one_error:.4}"
    );
    // The viewer's default (16 samples at most, threshold 0.03) is the CPU's, pixel for pixel.
    let adaptive = cpu_render_sampled(size, 16, 0.03);
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &adaptive),
        0
    );
}

#[test]
fn with_a_threshold_of_zero_the_viewer_shows_what_render_saves() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let sampling = ["--samples", "4", "--aa-threshold", "0"];
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[&["--size", "64", "--window", "600x400"][..], &sampling].concat(),
    );
    let saved = dir.path().join("render.png");
    let render = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(
            [
                &["render", "-o", saved.to_str().unwrap(), "--size", "64"][..],
                &sampling,
            ]
            .concat(),
        )
        .output()
        .unwrap();
    assert!(render.status.success(), "{render:?}");
    let rendered = image::open(&saved).unwrap().to_rgb8().into_raw();
    assert_eq!(
        rendered,
        cpu_render_sampled(size, 4, 0.0),
        "uniform sampling"
    );
    assert_ne!(rendered, cpu_render_sampled(size, 1, 0.0));
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &rendered),
        0
    );
}

#[test]
fn skip_traces_at_block_size_one_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let size = 256;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--block-size",
            "16",
            "--samples",
            "1",
            "--stats",
            "--script",
            "wait-load 1; skip; wait; print-status",
        ],
    );
    // The first image on screen is already at block size 1: no coarse pass was shown.
    let firsts: Vec<&str> = run
        .stderr
        .lines()
        .filter(|l| l.contains("stats: first image"))
        .collect();
    assert!(!firsts.is_empty(), "{}", run.stderr);
    assert!(
        firsts.iter().all(|l| l.contains("(block size 1)")),
        "{firsts:?}"
    );
    let status = run.stdout.lines().find(|l| l.starts_with("status: "));
    let status = status.unwrap_or_else(|| panic!("no status in {}", run.stdout));
    assert!(
        status.starts_with("status: done: 1 passes · started at block 1 ·"),
        "{status}"
    );
    let scene = default_scene().unwrap();
    let expected = cpu_render(&scene, size, scene.camera.spec);
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &expected),
        0
    );
}

#[test]
fn pause_stops_refinement_and_resume_finishes_it() {
    let dir = tempfile::tempdir().unwrap();
    let (run, _) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            "256",
            "--samples",
            "1",
            "--stats",
            "--script",
            "wait-load 1; pause; print-status; sleep 0.5; print-status; resume; wait; print-status",
        ],
    );
    let statuses: Vec<&str> = run
        .stdout
        .lines()
        .filter_map(|l| l.strip_prefix("status: "))
        .collect();
    assert_eq!(statuses.len(), 3, "{}", run.stdout);
    let eye_rays = |status: &str| {
        let rays = status.split("rays: ").nth(1).unwrap();
        rays.split_whitespace().next().unwrap().to_string()
    };
    // Paused (within the passes: the coarse ones may be done before the pause arrives): the
    // status says so, and half a second later nothing more has been traced.
    for paused in &statuses[..2] {
        assert!(paused.starts_with("paused · pass "), "{paused}");
    }
    assert_eq!(eye_rays(statuses[0]), eye_rays(statuses[1]), "{statuses:?}");
    // Resumed: refinement runs to the end, and block size 1 reaches the screen only then.
    assert!(statuses[2].starts_with("done: "), "{}", statuses[2]);
    assert_eq!(eye_rays(statuses[2]), (256 * 256).to_string());
    let stats = &run.stderr;
    let resumed = stats.find("stats: resumed").expect(stats);
    assert!(stats.find("stats: paused").expect(stats) < resumed);
    assert!(stats.find("block size 1 at 256×256").expect(stats) > resumed);
}
