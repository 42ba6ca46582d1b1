//! `raylab gen` and `raylab bench`, and the SPD scenes they share with `render`: written to
//! standard output or a file, taken by name at their own size, lit the NFF way asked for, timed
//! into JSON; and their mistakes.

use crate::common::run::{raylab, stderr};

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
            "24x16",
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
    let text = std::fs::read_to_string(dir.path().join("bench.json")).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(json["width"], 24, "{text}");
    assert_eq!(json["height"], 16, "{text}");
    let scenes = json["scenes"].as_array().expect("a list of scenes");
    let names: Vec<&str> = scenes.iter().filter_map(|s| s["scene"].as_str()).collect();
    assert_eq!(names, ["spd:tetra:1", "default"], "{text}");
    for scene in scenes {
        assert!(scene["first_pass_ms"].as_f64().is_some(), "{text}");
        assert!(scene["scaling"].as_f64().is_some(), "{text}");
    }
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
