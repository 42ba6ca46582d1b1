//! The `raylab` command as a user runs it: exit codes, messages, files written.

use std::path::Path;
use std::process::{Command, Output};

fn raylab(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

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
