//! The camera from the command line: the `--eye`, `--look-at`, `--up` and `--view-angle` flags of
//! `render`, `inspect` and `view`, their errors, and the camera file beside a scene, which the
//! flags win over.

use std::path::Path;

use crate::common::run::{raylab, stderr};
use crate::harness::{assert_every_help_names, raylab_without_display};

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

/// A TOML scene with its own camera at (0, 0, 5) and one sphere.
const ROOM: &str = "[camera]\neye = [0, 0, 5]\nview_angle = 40\n\n[[objects]]\ntype = \"sphere\"\n";

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
