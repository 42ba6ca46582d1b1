//! The options that override a scene's settings, taken alike by `render`, `inspect` and `view`:
//! named in every help, sizes, the threads limit, the anti-aliasing threshold, and the same
//! errors for bad values.

use crate::common::run::{raylab, stderr};
use crate::harness::{SMALL_BENCH, assert_every_help_names, raylab_without_display};

/// What `--threads` may be at most: four per core.
fn most_threads() -> usize {
    4 * std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The options that override a scene's settings, shared by `render`, `inspect` and `view`.
const OVERRIDES: [&str; 10] = [
    "--width",
    "--height",
    "--size",
    "--max-depth",
    "--min-weight",
    "--block-size",
    "--samples",
    "--fog-steps",
    "--caustic-photons",
    "--caustic-gather",
];

#[test]
fn threads_past_four_per_core_are_refused_by_every_command() {
    let dir = tempfile::tempdir().unwrap();
    let cores = most_threads() / 4;
    let too_many = (most_threads() + 1).to_string();
    let cases: [&[&str]; 4] = [
        &["render", "--width", "8", "--height", "8", "-o", "a.png"],
        &SMALL_BENCH,
        &["view", "--exit-when-done"],
        &["--exit-when-done"],
    ];
    for args in cases {
        let mut args = args.to_vec();
        args.extend(["--threads", &too_many]);
        let out = raylab(&args, dir.path());
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = stderr(&out);
        let expected = format!(
            "at most {} (4 per core, and this machine has {cores} cores)",
            most_threads()
        );
        assert!(err.contains(&expected), "{args:?}: {err}");
    }
    assert!(!dir.path().join("a.png").exists());
    let at_most = most_threads().to_string();
    let out = raylab(
        &[
            "render",
            "--width",
            "8",
            "--height",
            "8",
            "--threads",
            &at_most,
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn render_inspect_and_view_take_the_same_setting_overrides() {
    let dir = tempfile::tempdir().unwrap();
    assert_every_help_names(&OVERRIDES, dir.path());
}

#[test]
fn render_takes_a_size_as_the_viewer_does() {
    let dir = tempfile::tempdir().unwrap();
    for (size, expected) in [("40", (40, 40)), ("30x20", (30, 20))] {
        let out = raylab(&["render", "-o", "out.png", "--size", size], dir.path());
        assert!(out.status.success(), "--size {size}: {}", stderr(&out));
        let image = image::open(dir.path().join("out.png")).unwrap();
        assert_eq!((image.width(), image.height()), expected, "--size {size}");
    }
}

#[test]
fn inspect_takes_a_size() {
    let dir = tempfile::tempdir().unwrap();
    let inside = raylab(&["inspect", "--size", "8", "--pixel", "7,7"], dir.path());
    assert!(inside.status.success(), "{}", stderr(&inside));
    let outside = raylab(&["inspect", "--size", "8", "--pixel", "8,0"], dir.path());
    assert!(!outside.status.success());
    assert!(
        stderr(&outside).contains("outside the 8×8 image"),
        "{}",
        stderr(&outside)
    );
}

#[test]
fn a_size_with_a_width_or_height_is_refused_by_every_command() {
    let dir = tempfile::tempdir().unwrap();
    for command in [
        &["render", "-o", "a.png"][..],
        &["inspect", "--pixel", "1,1"],
        &["view"],
    ] {
        for side in ["--width", "--height"] {
            let mut args = command.to_vec();
            args.extend(["--size", "8", side, "4"]);
            let out = raylab(&args, dir.path());
            assert_eq!(out.status.code(), Some(2), "{args:?}");
            let err = stderr(&out);
            assert!(
                err.contains("--size") && err.contains("cannot be used with"),
                "{args:?}: {err}"
            );
        }
    }
    assert!(!dir.path().join("a.png").exists());
}

#[test]
fn the_viewer_takes_every_override_as_render_does() {
    let dir = tempfile::tempdir().unwrap();
    // Taken: without a display, the viewer gets as far as opening its window.
    for args in [
        &["view", "--width", "64"][..],
        &["view", "--height", "64"],
        &["--min-weight", "0.1"],
        &[
            "view",
            "--max-depth",
            "3",
            "--block-size",
            "4",
            "--samples",
            "2",
            "--fog-steps",
            "8",
        ],
    ] {
        let out = raylab_without_display(args, dir.path());
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains("cannot open a window"), "{args:?}: {err}");
    }
    // A bad one is refused before the window opens, with render's message.
    for bad in [
        &["--min-weight", "2"][..],
        &["--max-depth", "0"],
        &["--block-size", "3"],
        &["--samples", "0"],
        &["--fog-steps", "0"],
    ] {
        let view = raylab_without_display(&[&["view"][..], bad].concat(), dir.path());
        let render = raylab(
            &[&["render", "-o", "out.png"][..], bad].concat(),
            dir.path(),
        );
        assert_eq!(view.status.code(), Some(1), "{bad:?}");
        assert_eq!(render.status.code(), Some(1), "{bad:?}");
        assert!(!stderr(&render).is_empty(), "{bad:?}");
        assert_eq!(stderr(&view), stderr(&render), "{bad:?}");
    }
}

#[test]
fn the_anti_aliasing_threshold_is_taken_and_checked() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(
        &[
            "render",
            "-o",
            "aa.png",
            "--size",
            "32",
            "--samples",
            "4",
            "--aa-threshold",
            "0.03",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(dir.path().join("aa.png").exists());
    // Out of range: the settings' message (exit 1); not a number: the command line's (exit 2).
    for (value, message, code) in [
        (
            "1.5",
            "aa_threshold must be between 0 (uniform sampling) and 1, got 1.5",
            1,
        ),
        ("-0.5", "aa_threshold must be between 0", 1),
        ("lots", "`lots` is not a finite number", 2),
    ] {
        for command in [&["render"][..], &["inspect", "--pixel", "0,0"], &["view"]] {
            let flag = format!("--aa-threshold={value}");
            let out = raylab(&[command, &[flag.as_str()]].concat(), dir.path());
            assert_eq!(out.status.code(), Some(code), "{command:?} {value}");
            let error = stderr(&out);
            assert!(error.contains(message), "{command:?} {value}: {error}");
        }
    }
}

#[test]
fn window_sizes_past_the_limit_are_refused_before_a_window_opens() {
    let dir = tempfile::tempdir().unwrap();
    for size in ["16385x100", "100000x100000"] {
        let out = raylab_without_display(&["view", "--window", size], dir.path());
        assert_eq!(out.status.code(), Some(2), "{size}: {}", stderr(&out));
        let text = stderr(&out);
        assert!(
            text.contains("sides must be from 1 to 16384"),
            "{size}: {text}"
        );
        assert!(!text.contains("panicked"), "{size}: {text}");
    }
    let out = raylab_without_display(&["view", "--script", "resize 16385 100"], dir.path());
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("from 1 to 16384"), "{}", stderr(&out));
}
