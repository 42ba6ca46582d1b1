//! Rendering apart and merging (`raylab render --tile/--crop/--frame`, `raylab merge`), as a
//! scheduler's tasks run them: the merged image is the single render's, bit for bit; merge
//! refuses parts that do not fit together and then writes nothing.

use std::path::Path;
use std::process::{Command, Output};

use crate::common::run::stderr;

fn raylab_with(args: &[&str], dir: &Path, env: &[(&str, &str)]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_raylab"));
    for name in [
        "SLURM_ARRAY_TASK_ID",
        "SLURM_ARRAY_TASK_COUNT",
        "JOB_COMPLETION_INDEX",
        "PARALLEL_SEQ",
    ] {
        command.env_remove(name);
    }
    command
        .args(args)
        .envs(env.iter().copied())
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// Runs raylab in `dir` and asserts it succeeded.
fn raylab(args: &[&str], dir: &Path) {
    let out = raylab_with(args, dir, &[]);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
}

/// Runs raylab in `dir` and asserts it failed with a message (not a panic); returns the message.
fn raylab_fails(args: &[&str], dir: &Path) -> String {
    let out = raylab_with(args, dir, &[]);
    assert!(!out.status.success(), "{args:?} should fail");
    assert_ne!(out.status.code(), Some(101), "{args:?}: a panic");
    let err = stderr(&out);
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    err
}

fn scene(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/scenes")
        .join(name)
        .to_str()
        .unwrap()
        .to_owned()
}

fn read(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// A small image with adaptive anti-aliasing: four rounds (2, 4, 8, 16 samples).
const AA: [&str; 6] = [
    "--size",
    "37x23",
    "--samples",
    "16",
    "--aa-threshold",
    "0.03",
];

/// Renders `scene` whole and as `n` tiles with `settings`, merges the tiles, and asserts the
/// merged image is the whole render's, as linear floats and as 8-bit PNG.
fn assert_tiles_merge_to_the_single_render(scene: &str, settings: &[&str], n: u32) {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for ext in ["exr", "png"] {
        raylab(
            &[&["render", scene, "-o", &format!("whole.{ext}")], settings].concat(),
            d,
        );
    }
    let mut parts = Vec::new();
    for k in 0..n {
        let part = format!("part{k}.exr");
        let tile = format!("{k}/{n}");
        raylab(
            &[&["render", scene, "--tile", &tile, "-o", &part], settings].concat(),
            d,
        );
        parts.push(part);
    }
    let parts: Vec<&str> = parts.iter().map(String::as_str).collect();
    for ext in ["exr", "png"] {
        let merged = format!("merged.{ext}");
        raylab(&[&["merge"], &parts[..], &["-o", &merged]].concat(), d);
        assert!(
            read(d, &format!("whole.{ext}")) == read(d, &merged),
            "{scene}, {n} tiles: the merged {ext} differs from the single render"
        );
    }
}

#[test]
fn merged_tiles_equal_the_single_render_bit_for_bit() {
    // 7 and 3 divide neither side; 4 is a 2 × 2 grid.
    for n in [1, 3, 4, 7] {
        assert_tiles_merge_to_the_single_render(&scene("glass.toml"), &AA, n);
    }
}

#[test]
fn merged_tiles_of_a_caustic_equal_the_single_render_bit_for_bit() {
    let settings = [&AA[..], &["--caustic-photons", "20000"]].concat();
    assert_tiles_merge_to_the_single_render(&scene("caustic_glass_ball.toml"), &settings, 6);
}

#[test]
fn crops_merge_like_tiles() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let glass = scene("glass.toml");
    raylab(
        &[&["render", &glass, "-o", "whole.png"], &AA[..]].concat(),
        d,
    );
    for (crop, name) in [
        ("0,0,20,23", "left.exr"),
        ("20,0,37,9", "top.exr"),
        ("20,9,37,23", "rest.exr"),
    ] {
        raylab(
            &[&["render", &glass, "--crop", crop, "-o", name], &AA[..]].concat(),
            d,
        );
    }
    raylab(
        &[
            "merge",
            "left.exr",
            "top.exr",
            "rest.exr",
            "-o",
            "merged.png",
        ],
        d,
    );
    assert!(read(d, "whole.png") == read(d, "merged.png"));
    // The tone of 8-bit output is chosen at the merge, as at a render.
    let tone = ["--exposure", "1.5", "--tonemap", "filmic"];
    raylab(
        &[&["render", &glass, "-o", "toned.png"], &AA[..], &tone[..]].concat(),
        d,
    );
    let parts = [
        "merge",
        "left.exr",
        "top.exr",
        "rest.exr",
        "-o",
        "merged-toned.png",
    ];
    raylab(&[&parts[..], &tone[..]].concat(), d);
    assert!(read(d, "toned.png") == read(d, "merged-toned.png"));
    assert!(read(d, "toned.png") != read(d, "whole.png"));
    // Any EXR reader opens a part: the whole image, the part at its place.
    let part = image::open(d.join("top.exr")).unwrap();
    assert_eq!((part.width(), part.height()), (37, 23));
}

#[test]
fn frames_rendered_one_by_one_equal_the_whole_turntable() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let size = [
        "--size",
        "24x16",
        "--samples",
        "4",
        "--aa-threshold",
        "0.03",
    ];
    raylab(
        &[
            &["render", "--turntable", "5", "-o", "all%d.png"],
            &size[..],
        ]
        .concat(),
        d,
    );
    for k in ["0", "3"] {
        let name = format!("one{k}.png");
        raylab(
            &[
                &["render", "--turntable", "5", "--frame", k, "-o", &name],
                &size[..],
            ]
            .concat(),
            d,
        );
        assert!(
            read(d, &format!("all{k}.png")) == read(d, &name),
            "frame {k}"
        );
    }
    // A range writes each frame under its own number, and nothing else.
    std::fs::create_dir(d.join("range")).unwrap();
    raylab(
        &[
            &[
                "render",
                "--turntable",
                "5",
                "--frames",
                "2..4",
                "-o",
                "range/%d.png",
            ],
            &size[..],
        ]
        .concat(),
        d,
    );
    let mut names: Vec<String> = std::fs::read_dir(d.join("range"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["2.png", "3.png"]);
    assert!(read(d, "all2.png") == read(d, "range/2.png"));
    assert!(read(d, "all3.png") == read(d, "range/3.png"));
    // Frames and tiles combine: the tiles of frame 4 merge to frame 4.
    for k in ["0/2", "1/2"] {
        let name = format!("f4-{}.exr", &k[..1]);
        raylab(
            &[
                &[
                    "render",
                    "--turntable",
                    "5",
                    "--frame",
                    "4",
                    "--tile",
                    k,
                    "-o",
                    &name,
                ],
                &size[..],
            ]
            .concat(),
            d,
        );
    }
    raylab(&["merge", "f4-0.exr", "f4-1.exr", "-o", "f4.png"], d);
    assert!(read(d, "all4.png") == read(d, "f4.png"));
    // Parts of different frames do not merge.
    raylab(
        &[
            &[
                "render",
                "--turntable",
                "5",
                "--frame",
                "3",
                "--tile",
                "1/2",
                "-o",
                "f3-1.exr",
            ],
            &size[..],
        ]
        .concat(),
        d,
    );
    let err = raylab_fails(&["merge", "f4-0.exr", "f3-1.exr", "-o", "mixed.png"], d);
    assert!(err.contains("are parts of different frames"), "{err}");
}

#[test]
fn tile_auto_takes_the_index_from_the_scheduler() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let size = ["--size", "20x12"];
    raylab(
        &[&["render", "--tile", "1/3", "-o", "named.exr"], &size[..]].concat(),
        d,
    );
    for (env, name) in [
        (
            &[
                ("SLURM_ARRAY_TASK_ID", "1"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
            ][..],
            "slurm.exr",
        ),
        (&[("JOB_COMPLETION_INDEX", "1")][..], "k8s.exr"),
        (&[("PARALLEL_SEQ", "2")][..], "parallel.exr"),
    ] {
        let of = if name == "slurm.exr" {
            &[][..]
        } else {
            &["--of", "3"][..]
        };
        let args = [&["render", "--tile", "auto", "-o", name], of, &size[..]].concat();
        let out = raylab_with(&args, d, env);
        assert!(out.status.success(), "{env:?}: {}", stderr(&out));
        assert!(
            read(d, "named.exr") == read(d, name),
            "{env:?} is tile 1 of 3"
        );
    }
    let out = raylab_with(
        &["render", "--tile", "auto", "--of", "3", "-o", "x.exr"],
        d,
        &[],
    );
    assert!(stderr(&out).contains("none is set"), "{}", stderr(&out));
    let out = raylab_with(
        &["render", "--tile", "auto", "--of", "3", "-o", "x.exr"],
        d,
        &[("PARALLEL_SEQ", "4")],
    );
    assert!(
        stderr(&out).contains("task index 3 (from PARALLEL_SEQ) is out of range"),
        "{}",
        stderr(&out)
    );
    assert!(!d.join("x.exr").exists());
}

/// Whether `dir` holds a file named `name` or any temporary file.
fn leaves(dir: &Path, name: &str) -> bool {
    std::fs::read_dir(dir).unwrap().any(|e| {
        let file = e.unwrap().file_name().to_string_lossy().into_owned();
        file == name || file.ends_with(".tmp")
    })
}

#[test]
fn merge_refuses_parts_that_do_not_fit_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let glass = scene("glass.toml");
    let size = ["--size", "20x12"];
    let render = |extra: &[&str]| raylab(&[&["render", &glass], extra, &size[..]].concat(), d);
    for k in 0..4 {
        render(&["--tile", &format!("{k}/4"), "-o", &format!("t{k}.exr")]);
    }
    render(&["--tile", "3/4", "--samples", "2", "-o", "samples.exr"]);
    // The same scene but for one colour of its checkerboard, or for its background.
    let text = std::fs::read_to_string(&glass).unwrap();
    let other = text.replace("b = [0.1, 0.1, 0.1]", "b = [0.1, 0.1, 0.2]");
    std::fs::write(d.join("other.toml"), other).unwrap();
    let dark = text.replace("[0.6, 0.7, 0.9]", "[0.1, 0.7, 0.9]");
    std::fs::write(d.join("dark.toml"), dark).unwrap();
    for (file, part) in [("other.toml", "other.exr"), ("dark.toml", "dark.exr")] {
        let args = ["render", file, "--tile", "3/4", "-o", part];
        raylab(&[&args[..], &size[..]].concat(), d);
    }
    raylab(
        &[
            "render",
            &glass,
            "--tile",
            "3/4",
            "--size",
            "20x13",
            "-o",
            "taller.exr",
        ],
        d,
    );
    render(&["--crop", "5,5,15,12", "-o", "crop.exr"]);
    std::fs::write(d.join("garbage.exr"), b"not an image").unwrap();
    for (parts, expected) in [
        (
            &["t0.exr", "t1.exr", "t2.exr", "other.exr"][..],
            "different scenes or cameras",
        ),
        (
            &["t0.exr", "t1.exr", "t2.exr", "dark.exr"][..],
            "different settings: background (0.6 and 0.1)",
        ),
        (
            &["t0.exr", "t1.exr", "t2.exr", "samples.exr"],
            "different settings: samples (1 and 2)",
        ),
        (
            &["t0.exr", "t1.exr", "t2.exr", "taller.exr"],
            "t0.exr is a part of a 20×12 image, taller.exr of a 20×13",
        ),
        (
            &["t0.exr", "t2.exr"],
            "missing tile 1/4 (pixels 10,0,20,6), tile 3/4 (pixels 10,6,20,12)",
        ),
        (
            &["t0.exr", "t1.exr", "t2.exr", "t3.exr", "t1.exr"],
            "t1.exr (tile 1/4) and t1.exr (tile 1/4) overlap",
        ),
        (
            &["t0.exr", "t1.exr", "t2.exr", "t3.exr", "crop.exr"],
            "overlap",
        ),
        (
            &["t0.exr", "t1.exr", "t2.exr", "garbage.exr"],
            "garbage.exr: not a readable OpenEXR file",
        ),
        (&["t0.exr", "t1.exr", "t2.exr", "gone.exr"], "gone.exr"),
    ] {
        let err = raylab_fails(&[&["merge"], parts, &["-o", "out.png"]].concat(), d);
        assert!(err.contains(expected), "{parts:?}: {err}");
        assert!(
            !leaves(d, "out.png"),
            "{parts:?}: no output, not even a temporary file"
        );
    }
    raylab(
        &[
            "merge", "t0.exr", "t1.exr", "t2.exr", "t3.exr", "-o", "out.png",
        ],
        d,
    );
    assert!(leaves(d, "out.png"));
}

#[test]
fn merge_status_lists_the_tiles_there_are_and_those_missing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("parts")).unwrap();
    for k in [0, 2] {
        raylab(
            &[
                "render",
                "--size",
                "20x12",
                "--tile",
                &format!("{k}/3"),
                "-o",
                &format!("parts/{k}.exr"),
            ],
            d,
        );
    }
    let out = raylab_with(&["merge", "--status", "parts"], d, &[]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("parts/0.exr (tile 0/3)") && text.contains("parts/2.exr (tile 2/3)"),
        "{text}"
    );
    assert!(
        text.contains("missing tile 1/3 (pixels 6,0,13,12)"),
        "{text}"
    );
    assert!(!text.contains("missing tile 0/3"), "{text}");
    // A tile of another render among them: named, and no count of pixels past the image's.
    raylab(
        &[
            "render",
            "--size",
            "40x12",
            "--tile",
            "1/3",
            "-o",
            "parts/1.exr",
        ],
        d,
    );
    let out = raylab_with(&["merge", "--status", "parts"], d, &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains(
            "these parts do not belong together: parts/0.exr is a part of a 20×12 \
                       image, parts/1.exr of a 40×12"
        ),
        "{text}"
    );
    assert!(!text.contains("pixels in parts"), "{text}");
    assert!(
        stderr(&out).contains("the parts are not of one render"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn bad_jobs_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let size = ["--size", "20x12"];
    for (args, expected) in [
        (
            &["--tile", "4/4", "-o", "x.exr"][..],
            "tile 4 of 4 does not exist",
        ),
        (&["--tile", "0/0", "-o", "x.exr"], "at least 1"),
        (&["--tile", "1-4", "-o", "x.exr"], "is not K/N"),
        (
            &["--tile", "0/300", "-o", "x.exr"],
            "cannot be split into 300 tiles",
        ),
        (
            &["--crop", "0,0,21,12", "-o", "x.exr"],
            "reaches outside the 20×12 image",
        ),
        (&["--crop", "0,0,5", "-o", "x.exr"], "is not X0,Y0,X1,Y1"),
        (
            &["--tile", "0/2", "-o", "x.png"],
            "a part (--tile, --crop) is written as .exr",
        ),
        (
            &["--turntable", "4", "--frames", "3..3", "-o", "%d.png"],
            "A < B is needed",
        ),
        (
            &["--turntable", "4", "--frames", "2..5", "-o", "%d.png"],
            "the sequence has frames 0 to 3",
        ),
        (
            &["--turntable", "4", "--frame", "4", "-o", "x.png"],
            "frames are 0 to 3",
        ),
        (&["--frame", "1", "-o", "x.png"], "there is none"),
        (
            &["--of", "3", "-o", "x.png"],
            "--of N gives the number of tiles of --tile auto",
        ),
    ] {
        let err = raylab_fails(&[&["render"], args, &size[..]].concat(), d);
        assert!(err.contains(expected), "{args:?}: {err}");
    }
    assert!(
        std::fs::read_dir(d).unwrap().next().is_none(),
        "nothing written"
    );
}

#[test]
fn frames_of_a_camera_path_are_picked_with_its_length() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("room.views.toml"),
        "[view.1]\neye = [-3.0, 2.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n\n\
         [view.2]\neye = [4.0, 1.0, 6.0]\nlook_at = [0.0, 0.5, 0.0]\n",
    )
    .unwrap();
    let path = ["--size", "24x16", "--path", "room.views.toml"];
    raylab(
        &[
            &["render"],
            &path[..],
            &["--frames", "4", "-o", "all%d.png"],
        ]
        .concat(),
        d,
    );
    raylab(
        &[
            &["render"],
            &path[..],
            &["--path-length", "4", "--frames", "1..3", "-o", "some%d.png"],
        ]
        .concat(),
        d,
    );
    raylab(
        &[
            &["render"],
            &path[..],
            &["--frames", "4", "--frame", "3", "-o", "last.png"],
        ]
        .concat(),
        d,
    );
    for (whole, picked) in [
        ("all1.png", "some1.png"),
        ("all2.png", "some2.png"),
        ("all3.png", "last.png"),
    ] {
        assert!(read(d, whole) == read(d, picked), "{picked}");
    }
    assert!(!d.join("some0.png").exists() && !d.join("some3.png").exists());
    let err = raylab_fails(
        &[
            &["render"],
            &path[..],
            &["--frames", "1..3", "-o", "%d.png"],
        ]
        .concat(),
        d,
    );
    assert!(err.contains("--path-length N"), "{err}");
}
