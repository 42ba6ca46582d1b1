//! `raylab check`: "student" images made by raylab's library with one thing changed (each made
//! here its own way, not with `check`'s), each of which `check` must name; an identical image
//! exits 0; its exit codes are `diff`'s.

use std::path::Path;

use raylab::formats::load_any;
use raylab::scene::Scene;

use crate::common::run::{raylab, stderr};
use crate::common::students::{flipped, levels, mistaken, rendered};

const SIZE: (u32, u32) = (160, 120);

fn default_scene_path() -> String {
    format!("{}/assets/scenes/default.toml", env!("CARGO_MANIFEST_DIR"))
}

/// The default scene at [`SIZE`], changed by `change`.
fn scene(change: impl FnOnce(&mut Scene)) -> Scene {
    let mut scene = load_any(&default_scene_path()).unwrap();
    (scene.settings.width, scene.settings.height) = SIZE;
    change(&mut scene);
    scene
}

fn save(dir: &Path, name: &str, pixels: &[[u8; 3]]) {
    let bytes: Vec<u8> = pixels.iter().flatten().copied().collect();
    image::RgbImage::from_raw(SIZE.0, SIZE.1, bytes)
        .unwrap()
        .save(dir.join(name))
        .unwrap();
}

fn check(dir: &Path, image: &str) -> (Option<i32>, String) {
    let out = raylab(&["check", &default_scene_path(), image], dir);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    (out.status.code(), format!("{text}{}", stderr(&out)))
}

#[test]
fn each_mistake_of_a_students_tracer_is_named() {
    let dir = tempfile::tempdir().unwrap();
    for student in mistaken(&scene(|_| {})) {
        assert_said(
            dir.path(),
            &format!("{}.png", student.name),
            &student.pixels,
            student.says,
        );
    }
}

/// Saves a student's image `name` in `dir` and checks that `check` says `expected` of it, and
/// that it differs.
fn assert_said(dir: &Path, name: &str, pixels: &[[u8; 3]], expected: &str) {
    save(dir, name, pixels);
    let (code, text) = check(dir, name);
    assert_eq!(code, Some(1), "{name}: {text}");
    assert!(
        text.contains(expected),
        "{name}: expected {expected:?}:\n{text}"
    );
    assert!(text.ends_with("different\n"), "{name}: {text}");
}

#[test]
fn an_identical_image_exits_0() {
    let dir = tempfile::tempdir().unwrap();
    save(dir.path(), "same.png", &levels(&rendered(&scene(|_| {}))));
    let (code, text) = check(dir.path(), "same.png");
    assert_eq!(code, Some(0), "{text}");
    assert!(text.contains("within tolerance"), "{text}");
}

#[test]
fn the_worst_pixels_are_explained_from_the_ray_tree() {
    let dir = tempfile::tempdir().unwrap();
    let student = levels(&rendered(&scene(|s| s.settings.shadows = false)));
    save(dir.path(), "mine.png", &student);
    let (code, text) = check(dir.path(), "mine.png");
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("region 1 of "), "{text}");
    assert!(text.contains("raylab's eye ray hits "), "{text}");
    assert!(text.contains("shadow ray blocked by"), "{text}");
    // Each region's explanation says the student's pixel is brighter, because of shadow rays.
    let sentences: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("  your pixel is"))
        .collect();
    assert!(!sentences.is_empty(), "{text}");
    for sentence in sentences {
        assert!(
            sentence.contains("brighter by") && sentence.contains("shadow ray"),
            "{sentence}"
        );
    }
    let out = raylab(
        &["check", &default_scene_path(), "mine.png", "--json"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["causes"][0]["mistake"], "no-shadows", "{json}");
    assert_eq!(json["causes"][0]["over_tolerance"], 0, "{json}");
    assert!(json["regions"][0]["explanation"]["accounted_for"].is_string());
}

#[test]
fn trouble_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    save(
        dir.path(),
        "mine.png",
        &vec![[0; 3]; (SIZE.0 * SIZE.1) as usize],
    );
    for (args, expected) in [
        (vec!["check", "none.toml", "mine.png"], "none.toml"),
        (vec!["check", "SCENE", "none.png"], "none.png"),
        (
            vec!["check", "SCENE", "mine.png", "--size", "64"],
            "leave out --size",
        ),
    ] {
        let scene = default_scene_path();
        let args: Vec<&str> = args
            .iter()
            .map(|a| if *a == "SCENE" { scene.as_str() } else { a })
            .collect();
        let out = raylab(&args, dir.path());
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains(expected),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}

#[test]
fn an_anti_aliased_reference_says_to_take_one_sample() {
    let dir = tempfile::tempdir().unwrap();
    save(dir.path(), "mine.png", &levels(&rendered(&scene(|_| {}))));
    let out = raylab(
        &["check", &default_scene_path(), "mine.png", "--samples", "4"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("takes up to 4 samples per pixel") && text.contains("add --samples 1"),
        "{text}"
    );
}

#[test]
fn what_no_common_mistake_explains_is_pointed_at() {
    use raylab::camera::{Camera, CameraSpec};
    let dir = tempfile::tempdir().unwrap();
    let view = |change: fn(&mut CameraSpec)| {
        move |s: &mut Scene| {
            let mut spec = s.camera.spec;
            change(&mut spec);
            s.camera = Camera::new(spec).unwrap();
        }
    };
    let pixels = (SIZE.0 * SIZE.1) as usize;
    let students: [(&str, Vec<[u8; 3]>, &str); 4] = [
        (
            "narrow.png",
            levels(&rendered(&scene(view(|c| c.view_angle *= 0.7)))),
            "Look at the camera",
        ),
        (
            "moved.png",
            levels(&rendered(&scene(view(|c| c.eye.x += 1.0)))),
            "Look at the camera",
        ),
        ("black.png", vec![[0; 3]; pixels], "your image is all black"),
        (
            "grey.png",
            vec![[90, 100, 110]; pixels],
            "every pixel of your image is (90, 100, 110)",
        ),
    ];
    for (name, pixels, expected) in students {
        assert_said(dir.path(), name, &pixels, expected);
    }
}

#[test]
fn a_mistake_of_the_whole_image_leaves_no_pixel_blamed_on_a_term() {
    let dir = tempfile::tempdir().unwrap();
    let reference = levels(&rendered(&scene(|_| {})));
    let flipped = flipped(&reference, SIZE.0);
    save(dir.path(), "flipped.png", &flipped);
    let (code, text) = check(dir.path(), "flipped.png");
    assert_eq!(code, Some(1), "{text}");
    assert!(
        text.contains("likely cause: the image is flipped vertically"),
        "{text}"
    );
    assert!(text.contains("with the mistakes found made"), "{text}");
    assert!(
        !text.contains("region 1"),
        "no region is left to explain:\n{text}"
    );
    assert!(!text.contains("specular"), "{text}");
}
