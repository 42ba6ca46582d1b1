//! `raylab render`: the image it writes in every format, from any folder, with a debug view and
//! its legend; mistakes in the scene or the settings; and the same pixels as the library's
//! pass-by-pass render.

use std::path::Path;

use crate::common::run::{raylab, stderr};

#[test]
fn renders_the_default_scene_from_any_directory() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(
        &["render", "-o", "out.png", "--width", "64", "--height", "48"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let image = image::open(dir.path().join("out.png")).unwrap();
    assert_eq!((image.width(), image.height()), (64, 48));
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("64×48") && summary.contains("Mrays/s"),
        "{summary}"
    );
    assert!(
        summary.contains("3072 eye"),
        "one eye ray per pixel: {summary}"
    );
}

#[test]
fn renders_a_scene_file_to_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/glass.toml");
    for ext in ["png", "ppm", "exr", "hdr"] {
        let name = format!("glass.{ext}");
        let out = raylab(
            &[
                "render",
                scene.to_str().unwrap(),
                "-o",
                &name,
                "--width",
                "32",
                "--height",
                "24",
                "--samples",
                "2",
                "--threads",
                "1",
            ],
            dir.path(),
        );
        assert!(out.status.success(), "{ext}: {}", stderr(&out));
        assert!(
            image::open(dir.path().join(&name)).is_ok(),
            "{ext} reads back"
        );
    }
}

#[test]
fn a_broken_scene_file_reports_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("broken.toml"),
        "[camera]\neye = [0, 1, 5]\n\n[[objects]]\ntype = \"sphere\"\nradius = -2\n",
    )
    .unwrap();
    let out = raylab(&["render", "broken.toml", "-o", "x.png"], dir.path());
    assert!(!out.status.success());
    let err = stderr(&out);
    assert!(err.contains("broken.toml:6:10"), "{err}");
    assert!(err.contains("radius"), "{err}");
    assert!(!dir.path().join("x.png").exists(), "no image on failure");
}

#[test]
fn bad_settings_and_paths_are_errors_not_panics() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &str); 5] = [
        (
            &["render", "--block-size", "3", "-o", "a.png"],
            "block_size",
        ),
        (&["render", "--width", "0", "-o", "a.png"], "image size"),
        (
            &["render", "-o", "a.gif", "--width", "8", "--height", "8"],
            "unknown image format",
        ),
        (&["render", "missing.toml"], "missing.toml"),
        (&["render", "--threads", "0"], "--threads"),
    ];
    for (args, expected) in cases {
        let out = raylab(args, dir.path());
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = stderr(&out);
        assert!(
            err.contains(expected) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
}

#[test]
fn render_view_writes_the_debug_view_and_its_legend() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "32", "--height", "24"];
    let render = |view: &str, output: &str| {
        let mut args = vec!["render", "-o", output, "--view", view];
        args.extend(size);
        raylab(&args, dir.path())
    };
    let out = render("bvh-cost", "cost.png");
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("log scale") && stdout.contains("cost.legend.png"),
        "{stdout}"
    );
    let legend = image::open(dir.path().join("cost.legend.png")).unwrap();
    assert_eq!((legend.width(), legend.height()), (256, 24));
    let cost = image::open(dir.path().join("cost.png")).unwrap().to_rgb8();

    let out = render("normals", "normals.png");
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        !dir.path().join("normals.legend.png").exists(),
        "no scale, no legend"
    );
    let normals = image::open(dir.path().join("normals.png"))
        .unwrap()
        .to_rgb8();
    assert_ne!(cost, normals, "the views differ");

    let out = render("sparkles", "x.png");
    assert!(!out.status.success());
    assert!(stderr(&out).contains("bvh-cost"), "{}", stderr(&out));
}

#[test]
fn render_writes_the_image_a_pass_by_pass_render_ends_with() {
    // `raylab render` traces every pixel in one sweep, not block size by block size as the
    // viewer does: the same pixels to the bit, with uniform or adaptive anti-aliasing.
    use raylab::formats::toml::default_scene;
    use raylab::progressive::render_image;
    use raylab::render::assemble;
    let dir = tempfile::tempdir().unwrap();
    for (samples, threshold) in [(4, 0.0), (8, 0.02)] {
        let flags = [
            "--samples",
            &samples.to_string(),
            "--aa-threshold",
            &threshold.to_string(),
        ];
        let mut args = vec![
            "render",
            "-o",
            "sweep.exr",
            "--size",
            "40x30",
            "--threads",
            "2",
        ];
        args.extend(flags);
        let out = raylab(&args, dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
        let written = image::open(dir.path().join("sweep.exr"))
            .unwrap()
            .to_rgb32f();

        let mut scene = default_scene().unwrap();
        let s = &mut scene.settings;
        (s.width, s.height, s.samples, s.aa_threshold) = (40, 30, samples, threshold);
        let (pixels, stats) = render_image(&assemble(scene).unwrap().tracer());
        assert!(stats.passes.len() > 5, "block passes and more samples");
        let expected: Vec<f32> = pixels.iter().flat_map(|c| c.to_array()).collect();
        assert!(
            written.as_raw() == &expected,
            "{samples} samples, threshold {threshold}"
        );
    }
}
