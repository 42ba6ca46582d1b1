//! The `raylab` command as a user runs it: exit codes, messages, files written.

use std::path::Path;
use std::process::{Command, Output};

mod common;
use common::run::{raylab, stderr};

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
fn gen_writes_an_spd_scene_to_standard_output() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(&["gen", "tree", "--size", "2"], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.starts_with("b 0.078 0.361 0.753\nv\nfrom 4.5 0.4 2\n"),
        "{text}"
    );
    assert_eq!(text.lines().filter(|l| l.starts_with("c ")).count(), 7);
}

#[test]
fn gen_writes_a_file_that_renders() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(&["gen", "balls", "-s", "1", "-o", "balls.nff"], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("10 spheres"), "{}", stderr(&out));
    let out = raylab(
        &[
            "render",
            "balls.nff",
            "-o",
            "balls.png",
            "--width",
            "24",
            "--height",
            "24",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(
        summary.contains("576 eye (576 hit)"),
        "balls has no background: {summary}"
    );
    assert!(image::open(dir.path().join("balls.png")).is_ok());
}

#[test]
fn render_takes_spd_scenes_by_name_at_their_own_size() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(&["render", "spd:tetra:2", "-o", "t.png"], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let image = image::open(dir.path().join("t.png")).unwrap();
    assert_eq!(
        (image.width(), image.height()),
        (512, 512),
        "the `v` resolution"
    );
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("0 reflected, 0 transmitted"), "{summary}");
}

#[test]
fn nff_lights_change_the_picture() {
    let dir = tempfile::tempdir().unwrap();
    let render = |lights: &str, file: &str| {
        let args = [
            "render",
            "spd:tetra:2",
            "-o",
            file,
            "--width",
            "32",
            "--height",
            "32",
            "--nff-lights",
            lights,
        ];
        let out = raylab(&args, dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
        image::open(dir.path().join(file))
            .unwrap()
            .to_rgb8()
            .into_raw()
    };
    assert_ne!(render("readme", "a.png"), render("povray", "b.png"));
    // A value clap cannot read is a usage error (exit code 2).
    let out = raylab(
        &["render", "spd:tetra:2", "--nff-lights", "dim"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("readme, povray"), "{}", stderr(&out));
}

#[test]
fn spd_and_nff_mistakes_are_errors_not_panics() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.nff"), "v\nfrom 0 0 0\nat 1 1 x\n").unwrap();
    // Exit code 1 for a bad scene or size, 2 for a usage error clap reports.
    let cases: [(&[&str], i32, &str); 5] = [
        (
            &["render", "bad.nff", "-o", "a.png"],
            1,
            "bad.nff:3:8: expected a number",
        ),
        (
            &["render", "spd:cube", "-o", "a.png"],
            1,
            "unknown SPD database `cube`",
        ),
        (&["render", "spd:balls:9", "-o", "a.png"], 1, "from 1 to 6"),
        (&["gen", "tetra", "--size", "0"], 1, "from 1 to 10"),
        (&["gen", "cube"], 2, "expected one of balls, gears"),
    ];
    for (args, code, expected) in cases {
        let out = raylab(args, dir.path());
        assert_eq!(out.status.code(), Some(code), "{args:?}");
        let err = stderr(&out);
        assert!(
            err.contains(expected) && !err.contains("panicked"),
            "{args:?}: {err}"
        );
    }
    assert!(!dir.path().join("a.png").exists());
}

#[test]
fn bench_takes_spd_scenes_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(
        &[
            "bench",
            "--scenes",
            "spd:tetra:2",
            "--size",
            "16",
            "--threads",
            "1",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let report = String::from_utf8_lossy(&out.stdout);
    let row = report.lines().find(|l| l.starts_with("spd:tetra:2"));
    assert!(
        row.is_some_and(|r| r.contains(" 16 ")),
        "16 triangles: {report}"
    );
}

#[test]
fn bench_writes_json_with_the_scaling_factor() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(
        &[
            "bench",
            "--scenes",
            "spd:tetra:1,default",
            "--size",
            "16",
            "--threads",
            "2",
            "--repeat",
            "1",
            "--scaling",
            "--json",
            "bench.json",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let json = std::fs::read_to_string(dir.path().join("bench.json")).unwrap();
    assert!(
        json.starts_with('{') && json.trim_end().ends_with('}'),
        "{json}"
    );
    for key in [
        "\"scene\": \"spd:tetra:1\"",
        "\"scene\": \"default\"",
        "\"scaling\": ",
        "\"first_pass_ms\": ",
    ] {
        assert!(json.contains(key), "{key} missing: {json}");
    }
    assert!(!json.contains("\"scaling\": null"), "{json}");
}

#[test]
fn inspect_prints_the_ray_tree_of_a_pixel_as_text_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/glass.toml");
    let args = |json: bool| {
        let mut args = vec![
            "inspect",
            scene.to_str().unwrap(),
            "--pixel",
            "80,60",
            "--width",
            "160",
            "--height",
            "120",
        ];
        if json {
            args.push("--json");
        }
        raylab(&args, dir.path())
    };
    let text = args(false);
    assert!(text.status.success(), "{}", stderr(&text));
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.starts_with("pixel (80, 60): colour"), "{text}");
    assert!(text.contains("eye ray, depth 1"), "{text}");

    let json = args(true);
    assert!(json.status.success(), "{}", stderr(&json));
    let tree: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(tree["pixel"], serde_json::json!([80, 60]));
    let nodes = tree["nodes"].as_array().unwrap();
    assert_eq!(nodes[0]["kind"], "eye");
    assert_eq!(nodes[0]["depth"], 1);
    // Every node but the eye ray names its parent, which lists it as a child.
    for (i, node) in nodes.iter().enumerate().skip(1) {
        let parent = node["parent"].as_u64().unwrap() as usize;
        let children = nodes[parent]["children"].as_array().unwrap();
        assert!(children.contains(&serde_json::json!(i)), "node {i}");
    }
}

#[test]
fn inspect_mistakes_are_errors_not_panics() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &str); 4] = [
        (
            &[
                "inspect", "--pixel", "64,0", "--width", "64", "--height", "48",
            ],
            "outside the 64×48 image",
        ),
        (&["inspect", "--pixel", "3"], "expected X,Y"),
        (&["inspect", "--pixel=-1,2"], "expected X,Y"),
        (&["inspect", "--pixel", "a,b"], "expected X,Y"),
    ];
    for (args, message) in cases {
        let out = raylab(args, dir.path());
        assert!(!out.status.success(), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
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

/// What `--threads` may be at most: four per core.
fn most_threads() -> usize {
    4 * std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// A bench of one tiny scene, run once.
const SMALL_BENCH: [&str; 7] = [
    "bench",
    "--scenes",
    "spd:tetra:1",
    "--size",
    "8",
    "--repeat",
    "1",
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
fn gen_refuses_an_output_that_is_not_nff() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(&["gen", "balls", "-s", "1", "-o", "x.png"], dir.path());
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("-o/--output x.png") && err.contains(".nff"),
        "{err}"
    );
    assert!(!dir.path().join("x.png").exists());
    let out = raylab(&["gen", "balls", "-s", "1", "-o", "X.NFF"], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
}

/// Runs raylab with its standard output a pipe whose reader has gone (as `raylab … | head`
/// after `head` has read enough).
fn raylab_into_a_closed_pipe(args: &[&str], dir: &Path) -> Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .stdout(writer)
        .output()
        .expect("the binary runs")
}

#[test]
fn a_closed_standard_output_ends_every_command_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let inspect = ["inspect", "--pixel", "1,1", "--width", "4", "--height", "4"];
    let cases: [&[&str]; 5] = [
        &["gen", "tree", "--size", "2"],
        &inspect,
        &[&inspect[..], &["--json"][..]].concat(),
        &["render", "--width", "8", "--height", "8", "-o", "a.png"],
        &SMALL_BENCH,
    ];
    for args in cases {
        let out = raylab_into_a_closed_pipe(args, dir.path());
        assert_eq!(out.status.code(), Some(0), "{args:?}: {}", stderr(&out));
        assert_eq!(stderr(&out), "", "{args:?}");
    }
    assert!(
        image::open(dir.path().join("a.png")).is_ok(),
        "saved before printing"
    );
}

#[test]
fn bad_output_paths_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("folder.png")).unwrap();
    std::fs::write(dir.path().join("locked.png"), b"keep").unwrap();
    let locked = dir.path().join("locked.png");
    let mut permissions = std::fs::metadata(&locked).unwrap().permissions();
    permissions.set_readonly(true);
    std::fs::set_permissions(&locked, permissions).unwrap();
    // The scene is missing too: the output's error coming first shows that it is checked
    // before the scene is read, let alone rendered.
    let cases: [(&[&str], &str); 6] = [
        (
            &["render", "missing.toml", "-o", "x.gif"],
            "unknown image format",
        ),
        (
            &["render", "missing.toml", "-o", "no/x.png"],
            "no/x.png: the folder no does not exist",
        ),
        (
            &["render", "missing.toml", "-o", "folder.png"],
            "folder.png: is a folder",
        ),
        (
            &["render", "missing.toml", "-o", "locked.png"],
            "locked.png: is read-only",
        ),
        (
            &["bench", "--scenes", "missing.toml", "--json", "no/b.json"],
            "no/b.json: the folder no does not exist",
        ),
        (
            &[
                "view",
                "missing.toml",
                "--exit-when-done",
                "--screenshot",
                "no/s.png",
            ],
            "no/s.png: the folder no does not exist",
        ),
    ];
    for (args, expected) in cases {
        let out = raylab(args, dir.path());
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains(expected), "{args:?}: {err}");
    }
    assert_eq!(std::fs::read(&locked).unwrap(), b"keep");

    // The legend beside a debug view's image is checked before the render too: nothing is
    // written when it cannot be.
    std::fs::create_dir(dir.path().join("cost.legend.png")).unwrap();
    let out = raylab(
        &[
            "render", "-o", "cost.png", "--view", "bvh-cost", "--width", "8", "--height", "8",
        ],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("cost.legend.png: is a folder"),
        "{}",
        stderr(&out)
    );
    assert!(!dir.path().join("cost.png").exists());
}

#[cfg(unix)]
#[test]
fn an_output_through_a_symbolic_link_keeps_the_link() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("renders")).unwrap();
    std::os::unix::fs::symlink("renders/latest.png", dir.path().join("out.png")).unwrap();
    let out = raylab(
        &["render", "-o", "out.png", "--width", "8", "--height", "8"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let link = std::fs::symlink_metadata(dir.path().join("out.png")).unwrap();
    assert!(link.file_type().is_symlink());
    assert!(image::open(dir.path().join("renders/latest.png")).is_ok());
}

/// The temporary files of unfinished writes in `dir`.
fn temporary_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with(".raylab-"))
        .collect()
}

/// Renders an image large enough that saving it takes a while, sends `signal` as soon as the
/// save has begun (its temporary file has data), and returns the exit code.
#[cfg(unix)]
fn signal_during_the_save(signal: &str, dir: &Path) -> Option<i32> {
    use std::time::{Duration, Instant};
    std::fs::write(dir.join("empty.toml"), "").unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args([
            "render",
            "empty.toml",
            "-o",
            "big.exr",
            "--width",
            "2000",
            "--height",
            "2000",
        ])
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // The probe of the path's folder makes an empty temporary file; the save's one has data.
    let saving = || {
        std::fs::read_dir(dir).unwrap().any(|e| {
            let e = e.unwrap();
            e.file_name().to_string_lossy().starts_with(".raylab-")
                && e.metadata().is_ok_and(|m| m.len() > 0)
        })
    };
    let deadline = Instant::now() + Duration::from_secs(120);
    while !saving() {
        if let Some(status) = child.try_wait().unwrap() {
            return status.code(); // Done before the save could be seen.
        }
        if Instant::now() > deadline {
            child.kill().unwrap();
            panic!("the save did not begin");
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    let pid = child.id().to_string();
    let sent = Command::new("kill")
        .args(["-s", signal, &pid])
        .status()
        .unwrap();
    assert!(sent.success());
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            child.kill().unwrap();
            panic!("raylab did not stop after SIG{signal}");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    status.code()
}

#[cfg(unix)]
#[test]
fn a_signal_during_the_save_leaves_no_temporary_file() {
    for (signal, number) in [("TERM", 15), ("INT", 2)] {
        let dir = tempfile::tempdir().unwrap();
        let code = signal_during_the_save(signal, dir.path());
        // Stopped by the signal (128 + its number, as a shell reports it), or done just before.
        assert!(
            code == Some(128 + number) || code == Some(0),
            "SIG{signal}: exit code {code:?}"
        );
        assert_eq!(
            temporary_files(dir.path()),
            Vec::<String>::new(),
            "SIG{signal}"
        );
        if code == Some(0) {
            assert!(image::open(dir.path().join("big.exr")).is_ok());
        }
    }
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

/// Each command that renders a scene asserts that its `--help` names every one of `flags`.
fn assert_every_help_names(flags: &[&str], dir: &Path) {
    for args in [
        &["render", "--help"][..],
        &["inspect", "--help"],
        &["view", "--help"],
        &["--help"],
    ] {
        let out = raylab(args, dir);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        let help = String::from_utf8_lossy(&out.stdout);
        for flag in flags {
            assert!(help.contains(flag), "{args:?} lacks {flag}: {help}");
        }
    }
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

/// `raylab ARGS` where no window can open (no display).
fn raylab_without_display(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap()
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

/// The camera flags, exactly as `render`, `inspect` and `view` spell them.
const CAMERA_FLAGS: [&str; 4] = [
    "--eye <X,Y,Z>",
    "--look-at <X,Y,Z>",
    "--up <X,Y,Z>",
    "--view-angle <DEG>",
];

/// The eye ray's origin and direction of `inspect ARGS` (pixel 0,0 of a 3×1 image), from its
/// JSON; and its standard error.
fn inspected_eye_ray(args: &[&str], dir: &Path) -> ([f64; 3], [f64; 3], String) {
    let mut all = vec!["inspect", "--json", "--size", "3x1", "--pixel", "0,0"];
    all.extend(args);
    let out = raylab(&all, dir);
    assert!(out.status.success(), "{all:?}: {}", stderr(&out));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let vector = |key: &str| {
        let v = &json["nodes"][0][key];
        [0, 1, 2].map(|i| v[i].as_f64().unwrap())
    };
    (vector("origin"), vector("dir"), stderr(&out))
}

fn close3(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-4)
}

#[test]
fn render_inspect_and_view_take_the_camera_flags() {
    let dir = tempfile::tempdir().unwrap();
    assert_every_help_names(&CAMERA_FLAGS, dir.path());
    // Pixel 0 of a 3×1 image: dir = −n − W·(2/3)·u with W = 3·tan(θ/2), so at 90° and looking
    // down −z from the origin, (−2, 0, −1) normalised.
    let (origin, dir_, _) = inspected_eye_ray(
        &[
            "--eye",
            "0,0,0",
            "--look-at",
            "0, 0, -1",
            "--up",
            "0,1,0",
            "--view-angle",
            "90",
        ],
        dir.path(),
    );
    let s = 5f64.sqrt();
    assert!(close3(origin, [0.0, 0.0, 0.0]), "{origin:?}");
    assert!(close3(dir_, [-2.0 / s, 0.0, -1.0 / s]), "{dir_:?}");
    // Turned upside down by --up, the same pixel looks the other way along x; a negative
    // coordinate needs no `=`.
    let (_, upside_down, _) = inspected_eye_ray(
        &[
            "--eye",
            "0,0,0",
            "--look-at",
            "0,0,-1",
            "--up",
            "0,-1,0",
            "--view-angle",
            "90",
        ],
        dir.path(),
    );
    assert!(
        close3(upside_down, [2.0 / s, 0.0, -1.0 / s]),
        "{upside_down:?}"
    );
    // An eye alone keeps the scene's look-at point (the default scene's is (0, 1, 0)).
    let (origin, _, _) = inspected_eye_ray(&["--eye", "-3,1,0"], dir.path());
    assert!(close3(origin, [-3.0, 1.0, 0.0]), "{origin:?}");
    // Render takes them too: looking away from the scene leaves only the background.
    let out = raylab(
        &[
            "render",
            "-o",
            "away.png",
            "--size",
            "4",
            "--eye",
            "0,1,0",
            "--look-at",
            "0,50,1",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let away = image::open(dir.path().join("away.png")).unwrap().to_rgb8();
    let first = away.get_pixel(0, 0);
    assert!(away.pixels().all(|p| p == first), "only the sky is in view");
}

#[test]
fn bad_camera_flags_are_the_same_errors_for_every_command() {
    let dir = tempfile::tempdir().unwrap();
    // Refused by the flag parser (clap, status 2).
    for (bad, message) in [
        (&["--eye", "1,2"][..], "is not a point or vector (use X,Y,Z"),
        (&["--look-at", "1,2,3,4"], "is not a point or vector"),
        (&["--up", "0,nan,1"], "`nan` is not a finite number"),
        (&["--eye", "inf,0,0"], "`inf` is not a finite number"),
        (&["--view-angle", "wide"], "`wide` is not a finite number"),
    ] {
        for command in [
            &["render", "-o", "a.png"][..],
            &["inspect", "--pixel", "0,0"],
        ] {
            let out = raylab(&[command, bad].concat(), dir.path());
            assert_eq!(out.status.code(), Some(2), "{bad:?}");
            assert!(stderr(&out).contains(message), "{bad:?}: {}", stderr(&out));
        }
        let view = raylab_without_display(&[&["view"][..], bad].concat(), dir.path());
        assert_eq!(view.status.code(), Some(2), "{bad:?}");
        assert!(
            stderr(&view).contains(message),
            "{bad:?}: {}",
            stderr(&view)
        );
    }
    // Refused as the scene file's camera would be, before the window opens.
    for (bad, message) in [
        (
            &["--view-angle", "180"][..],
            "--view-angle: view angle must be between 0 and 180 degrees, got 180",
        ),
        (&["--view-angle", "-5"], "got -5"),
        (
            &["--eye", "1,1,1", "--look-at", "1, 1, 1"],
            "--eye, --look-at: the eye and the look-at point coincide",
        ),
        (
            &["--eye", "0,5,0", "--look-at", "0,-2,0"],
            "--up: the up vector is parallel to the view direction",
        ),
        (&["--up", "0,0,0"], "--up: the up vector is parallel"),
        (&["--eye", "1e20,0,0"], "--eye: the eye"),
    ] {
        let render = raylab(&[&["render", "-o", "a.png"][..], bad].concat(), dir.path());
        let inspect = raylab(
            &[&["inspect", "--pixel", "0,0"][..], bad].concat(),
            dir.path(),
        );
        let view = raylab_without_display(&[&["view"][..], bad].concat(), dir.path());
        for out in [&render, &inspect, &view] {
            assert_eq!(out.status.code(), Some(1), "{bad:?}");
            assert!(stderr(out).contains(message), "{bad:?}: {}", stderr(out));
            assert!(!stderr(out).contains("panicked"), "{bad:?}");
        }
        assert_eq!(stderr(&view), stderr(&render), "{bad:?}");
        assert!(!stderr(&view).contains("cannot open a window"), "{bad:?}");
    }
    // Wrong only with the scene's own camera: the default scene's eye is at (0.6, 3.4, 10).
    let out = raylab(
        &["render", "-o", "a.png", "--look-at", "0.6,-3,10"],
        dir.path(),
    );
    assert!(
        stderr(&out).contains("--up: the up vector"),
        "{}",
        stderr(&out)
    );
    assert!(!dir.path().join("a.png").exists());
}

/// A TOML scene with its own camera at (0, 0, 5) and one sphere.
const ROOM: &str = "[camera]\neye = [0, 0, 5]\nview_angle = 40\n\n[[objects]]\ntype = \"sphere\"\n";

#[test]
fn a_camera_file_beside_the_scene_is_read_and_the_flags_win_over_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("room.toml"), ROOM).unwrap();
    // Without a camera file: the scene's own camera, and no note.
    let (origin, _, err) = inspected_eye_ray(&["room.toml"], dir.path());
    assert!(close3(origin, [0.0, 0.0, 5.0]), "{origin:?}");
    assert!(!err.contains("note:"), "{err}");
    // The file beside it, as the viewer's Ctrl+S writes one (here without `near`, which stays the
    // scene's).
    let camera = "[camera]\neye = [1.0, 2.0, 7.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 1.0, 0.0]\n\
                  view_angle = 30.0\n";
    std::fs::write(dir.path().join("room.camera.toml"), camera).unwrap();
    let (origin, _, err) = inspected_eye_ray(&["room.toml"], dir.path());
    assert!(close3(origin, [1.0, 2.0, 7.0]), "{origin:?}");
    assert!(
        err.contains("note: the camera is from room.camera.toml"),
        "{err}"
    );
    // The flags win over it, key by key.
    let (origin, dir_, _) = inspected_eye_ray(&["room.toml", "--eye", "0,0,-9"], dir.path());
    assert!(close3(origin, [0.0, 0.0, -9.0]), "{origin:?}");
    // Still looking at the origin, at the file's 30°: pixel 0 is 2·tan(15°) to the side.
    let side = 2.0 * 15f64.to_radians().tan();
    let length = (side * side + 1.0).sqrt();
    assert!(close3(dir_, [side / length, 0.0, 1.0 / length]), "{dir_:?}");
    // A file that leaves keys out keeps the scene's for them.
    std::fs::write(
        dir.path().join("room.camera.toml"),
        "[camera]\nview_angle = 60\n",
    )
    .unwrap();
    let (origin, _, _) = inspected_eye_ray(&["room.toml"], dir.path());
    assert!(close3(origin, [0.0, 0.0, 5.0]), "{origin:?}");
    // Render reads it too: from behind the sphere, still a sphere in the middle.
    std::fs::write(dir.path().join("room.camera.toml"), camera).unwrap();
    let out = raylab(
        &["render", "room.toml", "-o", "r.png", "--size", "8"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("note: the camera is from room.camera.toml"));
}

#[test]
fn every_scene_file_format_takes_a_camera_file() {
    let dir = tempfile::tempdir().unwrap();
    let nff = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\n\
               l 1 1 1\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
    std::fs::write(dir.path().join("ball.nff"), nff).unwrap();
    std::fs::write(
        dir.path().join("ball.camera.toml"),
        "[camera]\neye = [0, 3, 4]\n",
    )
    .unwrap();
    let (origin, _, err) = inspected_eye_ray(&["ball.nff"], dir.path());
    assert!(close3(origin, [0.0, 3.0, 4.0]), "{origin:?}");
    assert!(
        err.contains("note: the camera is from ball.camera.toml"),
        "{err}"
    );
    // A built-in SPD scene has no file to be beside, so even a file of that name is not read.
    std::fs::write(
        dir.path().join("spd:balls:1.camera.toml"),
        "[camera]\nbroken",
    )
    .unwrap();
    let out = raylab(
        &["inspect", "spd:balls:1", "--pixel", "0,0", "--size", "4"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(!stderr(&out).contains("note:"), "{}", stderr(&out));
}

#[test]
fn a_broken_camera_file_reports_its_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("room.toml"), ROOM).unwrap();
    for (camera, message) in [
        (
            "[camera]\neye = [0, 0, 5]\nview_angle = 500\n",
            "room.camera.toml:3:14: view angle must be between 0 and 180 degrees, got 500",
        ),
        (
            "[camera]\nlook_at = [0, 0, 5]\n",
            "room.camera.toml:2:11: the eye and the look-at point coincide",
        ),
        (
            "[camera]\nfov = 30\n",
            "room.camera.toml:2:1: unknown field `fov`",
        ),
        ("[camera]\neye = [0, 0]\n", "room.camera.toml:2:7:"),
        (
            "eye = [0, 0, 1]\n",
            "room.camera.toml:1:1: unknown field `eye`",
        ),
        ("[camera\n", "room.camera.toml:1:"),
    ] {
        std::fs::write(dir.path().join("room.camera.toml"), camera).unwrap();
        for command in [
            &["render", "room.toml", "-o", "a.png"][..],
            &["inspect", "room.toml", "--pixel", "0,0"],
        ] {
            let out = raylab(command, dir.path());
            assert_eq!(out.status.code(), Some(1), "{camera}");
            assert!(stderr(&out).contains(message), "{camera}: {}", stderr(&out));
        }
    }
    assert!(!dir.path().join("a.png").exists());
}

/// Renders the default scene at 40×30 with `extra` flags into `name`.
fn render_small(name: &str, extra: &[&str], dir: &Path) -> Output {
    let mut args = vec!["render", "-o", name, "--size", "40x30", "--threads", "1"];
    args.extend_from_slice(extra);
    raylab(&args, dir)
}

#[test]
fn render_exposure_doubles_the_linear_values_before_the_curve() {
    use raylab::tone::{Tone, ToneCurve};
    use strum::IntoEnumIterator;
    let dir = tempfile::tempdir().unwrap();
    let out = render_small("linear.exr", &[], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let linear = image::open(dir.path().join("linear.exr"))
        .unwrap()
        .to_rgb32f();
    let mut brightened = 0;
    for curve in ToneCurve::iter() {
        let name = format!("{curve}.png");
        let out = render_small(
            &name,
            &["--exposure", "1", "--tonemap", &curve.to_string()],
            dir.path(),
        );
        assert!(out.status.success(), "{curve}: {}", stderr(&out));
        let shown = image::open(dir.path().join(&name)).unwrap().to_rgb8();
        let doubled = Tone::new(0.0, curve).unwrap();
        for (got, linear) in shown.pixels().zip(linear.pixels()) {
            let expected = linear.0.map(|v| doubled.srgb8(2.0 * v));
            assert_eq!(got.0, expected, "{curve}");
        }
        let plain = Tone::default();
        brightened += shown
            .pixels()
            .zip(linear.pixels())
            .filter(|(s, l)| s.0 != l.0.map(|v| plain.srgb8(v)))
            .count();
    }
    assert!(brightened > 0, "one stop changes the picture");
}

#[test]
fn render_without_exposure_or_curve_writes_the_plain_encoding() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("plain.png", &[][..]),
        ("explicit.png", &["--exposure", "0", "--tonemap", "clamp"]),
    ] {
        let out = render_small(name, extra, dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let out = render_small("linear.exr", &[], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let linear = image::open(dir.path().join("linear.exr"))
        .unwrap()
        .to_rgb32f();
    let encoded: Vec<u8> = linear
        .pixels()
        .flat_map(|p| p.0.map(raylab::color::srgb8))
        .collect();
    for name in ["plain.png", "explicit.png"] {
        let png = image::open(dir.path().join(name)).unwrap().to_rgb8();
        assert_eq!(png.into_raw(), encoded, "{name}");
    }
}

#[test]
fn bad_exposures_and_tone_curves_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    // Clap refuses what is not a curve or a number (code 2), raylab an exposure out of range (1).
    for (extra, code, message) in [
        (
            &["--tonemap", "aces"][..],
            2,
            "unknown tone curve `aces` (use one of: clamp, reinhard, filmic)",
        ),
        (&["--exposure", "bright"], 2, "invalid value 'bright'"),
        (
            &["--exposure", "40"],
            1,
            "exposure must be from -16 to 16 stops",
        ),
        (
            &["--exposure", "nan"],
            1,
            "exposure must be from -16 to 16 stops",
        ),
    ] {
        let out = render_small("a.png", extra, dir.path());
        assert_eq!(out.status.code(), Some(code), "{extra:?}");
        assert!(
            stderr(&out).contains(message),
            "{extra:?}: {}",
            stderr(&out)
        );
    }
    assert!(!dir.path().join("a.png").exists());
    let out = render_small("a.exr", &["--exposure", "1"], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("shape 8-bit images only; a.exr keeps the linear values"),
        "{}",
        stderr(&out)
    );
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

/// The names of the files in `dir`, sorted.
fn file_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_turntable_writes_numbered_frames_from_0_the_first_a_plain_render() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("frames")).unwrap();
    let size = ["--size", "32x24"];
    let out = raylab(
        &[
            &["render", "--turntable", "4", "-o", "frames/%04d.png"],
            &size[..],
        ]
        .concat(),
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        file_names(&dir.path().join("frames")),
        ["0000.png", "0001.png", "0002.png", "0003.png"]
    );
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.starts_with("4 frames of 32×24"), "{summary}");
    let out = raylab(
        &[&["render", "-o", "plain.png"], &size[..]].concat(),
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("frames/0000.png"), read("plain.png"));
    assert_ne!(
        read("frames/0001.png"),
        read("plain.png"),
        "the camera turns"
    );
}

#[test]
fn a_path_through_a_views_file_starts_and_ends_on_its_views() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("room.views.toml"),
        "[view.2]\neye = [4.0, 1.0, 6.0]\nlook_at = [0.0, 0.5, 0.0]\n\n\
         [view.1]\neye = [-3.0, 2.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n",
    )
    .unwrap();
    let size = ["--size", "24x16"];
    let args = [
        "render",
        "--path",
        "room.views.toml",
        "--frames",
        "3",
        "-o",
        "p%d.png",
    ];
    let out = raylab(&[&args[..], &size[..]].concat(), dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        file_names(dir.path()),
        ["p0.png", "p1.png", "p2.png", "room.views.toml"]
    );
    // The views go in the order of their numbers: view 1 first.
    for (eye, look_at, name) in [
        ("-3,2,5", "0,0,0", "first.png"),
        ("4,1,6", "0,0.5,0", "last.png"),
    ] {
        let args = ["render", "--eye", eye, "--look-at", look_at, "-o", name];
        let out = raylab(&[&args[..], &size[..]].concat(), dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("p0.png"), read("first.png"));
    assert_eq!(read("p2.png"), read("last.png"));
    assert_ne!(read("p1.png"), read("first.png"));
}

#[test]
fn bad_sequences_are_clear_errors_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("one.views.toml"),
        "[view.1]\neye = [0, 1, 5]\n",
    )
    .unwrap();
    std::fs::write(dir.path().join("bad.views.toml"), "[view.0]\n").unwrap();
    for (args, expected) in [
        (
            &["--turntable", "0", "-o", "%d.png"][..],
            "--turntable: a turntable takes 1 to 10000 frames, got 0",
        ),
        (&["--turntable", "20000", "-o", "%d.png"], "got 20000"),
        (
            &["--turntable", "3", "-o", "out.png"],
            "-o out.png names one file, but the sequence has 3 images",
        ),
        (
            &["--turntable", "3", "-o", "%s.png"],
            "a frame number pattern is %d or %0Nd",
        ),
        (
            &["--turntable", "3", "-o", "%d-%d.png"],
            "more than one frame number pattern",
        ),
        (
            &["--path", "one.views.toml", "--frames", "5", "-o", "%d.png"],
            "--path one.views.toml: a camera path needs at least 2 views, got 1",
        ),
        (
            &["--path", "bad.views.toml", "--frames", "5", "-o", "%d.png"],
            "bad.views.toml:1:7: views are numbered 1 to 9, got `0`",
        ),
        (
            &["--path", "none.views.toml", "--frames", "5", "-o", "%d.png"],
            "none.views.toml:1:1: cannot read the views file",
        ),
        (&["--path", "one.views.toml", "-o", "%d.png"], "--frames"),
        (&["--frames", "4", "-o", "%d.png"], "--path"),
        (
            &[
                "--turntable",
                "3",
                "--path",
                "one.views.toml",
                "--frames",
                "3",
            ],
            "cannot be used with",
        ),
    ] {
        let out = raylab(&[&["render", "--size", "8"][..], args].concat(), dir.path());
        let err = stderr(&out);
        assert!(!out.status.success(), "{args:?}");
        assert!(err.contains(expected), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    assert_eq!(
        file_names(dir.path()),
        ["bad.views.toml", "one.views.toml"],
        "no image written"
    );
    // A frame that cannot be saved (a folder has its name) takes the frames before it away.
    std::fs::create_dir(dir.path().join("f2.png")).unwrap();
    let args = ["render", "--size", "8", "--turntable", "3", "-o", "f%d.png"];
    let out = raylab(&args, dir.path());
    assert!(!out.status.success());
    assert!(stderr(&out).contains("f2.png"), "{}", stderr(&out));
    assert_eq!(
        file_names(dir.path()),
        ["bad.views.toml", "f2.png", "one.views.toml"]
    );
}

#[test]
fn render_help_names_the_sequence_flags() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(&["render", "--help"], dir.path());
    let help = String::from_utf8_lossy(&out.stdout);
    for flag in [
        "--turntable <FRAMES>",
        "--path <FILE>",
        "--frames <N|A..B>",
        "--frame <K|auto>",
        "--tile <K/N|auto>",
        "--crop <X0,Y0,X1,Y1>",
        "half-open",
        "%04d",
    ] {
        assert!(help.contains(flag), "{flag}: {help}");
    }
}

#[test]
fn render_writes_the_image_a_pass_by_pass_render_ends_with() {
    // `raylab render` traces every pixel in one sweep, not block size by block size as the
    // viewer does: the same pixels to the bit, with uniform or adaptive anti-aliasing.
    use raylab::bvh::Bvh;
    use raylab::formats::toml::default_scene;
    use raylab::progressive::render_image;
    use raylab::whitted::Tracer;
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
        let bvh = Bvh::build(&scene.geometry);
        let (pixels, stats) = render_image(&Tracer::new(&scene, &bvh));
        assert!(stats.passes.len() > 5, "block passes and more samples");
        let expected: Vec<f32> = pixels.iter().flat_map(|c| c.to_array()).collect();
        assert!(
            written.as_raw() == &expected,
            "{samples} samples, threshold {threshold}"
        );
    }
}
