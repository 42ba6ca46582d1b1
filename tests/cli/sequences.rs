//! Image sequences from `render`: a turntable's numbered frames, a camera path through a views
//! file, their mistakes, and the help that names their flags.

use std::path::Path;

use crate::common::run::{raylab, stderr};

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
fn a_path_through_a_gltf_models_cameras_starts_on_its_first_camera() {
    let dir = tempfile::tempdir().unwrap();
    let seed = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/gltf/seed_cubes.gltf");
    let mut model: serde_json::Value =
        serde_json::from_slice(&std::fs::read(seed).unwrap()).unwrap();
    // A second camera, up and to the side, after the model's own.
    let nodes = model["nodes"].as_array_mut().unwrap();
    nodes.push(
        serde_json::json!({"camera": 0, "translation": [3.0, 2.0, 4.0],
        "rotation": [-0.1, 0.3, 0.0, 0.95]}),
    );
    let second = nodes.len() - 1;
    model["scenes"][0]["nodes"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!(second));
    std::fs::write(dir.path().join("cubes.gltf"), model.to_string()).unwrap();
    let size = ["--size", "24x16"];
    let args = [
        "render",
        "cubes.gltf",
        "--path",
        "cubes.gltf",
        "--frames",
        "3",
        "-o",
        "p%d.png",
    ];
    let out = raylab(&[&args[..], &size[..]].concat(), dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let args = ["render", "cubes.gltf", "-o", "first.png"];
    let out = raylab(&[&args[..], &size[..]].concat(), dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(
        read("p0.png"),
        read("first.png"),
        "the path starts on camera 1"
    );
    assert_ne!(
        read("p2.png"),
        read("first.png"),
        "the path ends on camera 2"
    );
}
