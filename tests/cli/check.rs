//! `raylab check`: "student" images made by raylab's library with one thing changed (each made
//! here its own way, not with `check`'s), each of which `check` must name; an identical image
//! exits 0; its exit codes are `diff`'s.

use std::path::Path;

use raylab::bvh::Bvh;
use raylab::color::{Color, srgb8};
use raylab::formats::load_any;
use raylab::progressive::render_image;
use raylab::scene::Scene;
use raylab::stats::RayCounts;
use raylab::whitted::Tracer;

use crate::common::run::{raylab, stderr};

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

/// The scene's image as the renderer makes it (linear colours, row by row).
fn rendered(scene: &Scene) -> Vec<Color> {
    let bvh = Bvh::build(&scene.geometry);
    render_image(&Tracer::new(scene, &bvh)).0
}

/// The lecture's tracer taken literally: the eye ray of pixel (x, y) is `dir_rc` at whole
/// `c = x` and `r` = the row counted from the bottom, a corner of the pixel, not its centre.
fn rendered_through_corners(scene: &Scene) -> Vec<Color> {
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(scene, &bvh);
    let (width, height) = SIZE;
    let mut counts = RayCounts::default();
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let r = (height - 1 - y) as f32;
            let ray = scene.camera.ray(r, x as f32, height, width);
            tracer.trace_eye(&ray, &mut counts)
        })
        .collect()
}

/// `pixels` (an image of [`SIZE`]) with its rows in the other order.
fn flipped(pixels: &[[u8; 3]]) -> Vec<[u8; 3]> {
    pixels
        .chunks(SIZE.0 as usize)
        .rev()
        .flatten()
        .copied()
        .collect()
}

fn levels(colors: &[Color]) -> Vec<[u8; 3]> {
    colors.iter().map(|c| c.to_array().map(srgb8)).collect()
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
    let glass = |scene: &mut Scene| {
        for m in &mut scene.materials {
            if m.ior == 1.5 {
                m.ior = 1.0;
            }
        }
    };
    let colors = rendered(&scene(|_| {}));
    let reference = levels(&colors);
    let flipped = flipped(&reference);
    // Gamma applied again, as 1/2.2, to levels already encoded with the sRGB curve.
    let gamma_twice: Vec<[u8; 3]> = reference
        .iter()
        .map(|p| p.map(|l| (255.0 * (f32::from(l) / 255.0).powf(1.0 / 2.2)).round() as u8))
        .collect();
    // Linear values written as levels.
    let no_gamma: Vec<[u8; 3]> = colors
        .iter()
        .map(|c| {
            c.to_array()
                .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
        })
        .collect();
    // The sRGB curve past 1, the level cast to a byte as C does: it wraps around.
    let wrapped = |v: f32| {
        let encoded = if v <= 0.0031308 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        ((encoded.max(0.0) * 255.0).round() as i64).rem_euclid(256) as u8
    };
    let no_clamping: Vec<[u8; 3]> = colors.iter().map(|c| c.to_array().map(wrapped)).collect();
    let students: [(&str, Vec<[u8; 3]>, &str); 10] = [
        (
            "no-shadows.png",
            levels(&rendered(&scene(|s| s.settings.shadows = false))),
            "likely cause: shadows are missing",
        ),
        (
            "no-specular.png",
            levels(&rendered(&scene(|s| {
                s.materials.iter_mut().for_each(|m| m.specular = 0.0)
            }))),
            "likely cause: the specular (Phong) term is missing",
        ),
        (
            "no-reflection.png",
            levels(&rendered(&scene(|s| s.settings.reflections = false))),
            "likely cause: reflections are missing",
        ),
        (
            "no-transmission.png",
            levels(&rendered(&scene(|s| s.settings.transmission = false))),
            "likely cause: transmission is missing",
        ),
        (
            "ior-1.png",
            levels(&rendered(&scene(glass))),
            "likely cause: a wrong index of refraction: 1.0",
        ),
        (
            "corners.png",
            levels(&rendered_through_corners(&scene(|_| {}))),
            "likely cause: a camera offset: eye rays through pixel corners",
        ),
        (
            "flipped.png",
            flipped,
            "likely cause: the image is flipped vertically",
        ),
        (
            "gamma-twice.png",
            gamma_twice,
            "likely cause: gamma applied twice",
        ),
        ("no-gamma.png", no_gamma, "likely cause: gamma not applied"),
        (
            "no-clamping.png",
            no_clamping,
            "likely cause: colours over 1 are not clamped",
        ),
    ];
    assert_each_said(dir.path(), students);
}

/// Saves each student's image (a name, its pixels) in `dir` and checks that `check` says what is
/// expected of it, and that it differs.
fn assert_each_said<const N: usize>(dir: &Path, students: [(&str, Vec<[u8; 3]>, &str); N]) {
    for (name, pixels, expected) in students {
        save(dir, name, &pixels);
        let (code, text) = check(dir, name);
        assert_eq!(code, Some(1), "{name}: {text}");
        assert!(
            text.contains(expected),
            "{name}: expected {expected:?}:\n{text}"
        );
        assert!(text.ends_with("different\n"), "{name}: {text}");
    }
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
    let colors = rendered(&scene(|_| {}));
    let reference = levels(&colors);
    let view = |change: fn(&mut CameraSpec)| {
        move |s: &mut Scene| {
            let mut spec = s.camera.spec;
            change(&mut spec);
            s.camera = Camera::new(spec).unwrap();
        }
    };
    let pixels = (SIZE.0 * SIZE.1) as usize;
    // One pixel to the right: column x shows raylab's column x − 1, the first column repeated.
    let shifted: Vec<[u8; 3]> = reference
        .chunks(SIZE.0 as usize)
        .flat_map(|row| std::iter::once(row[0]).chain(row[..row.len() - 1].iter().copied()))
        .collect();
    let students: [(&str, Vec<[u8; 3]>, &str); 6] = [
        (
            "darker.png",
            levels(&colors.iter().map(|c| *c * 0.8).collect::<Vec<_>>()),
            "likely cause: every colour is scaled by one factor",
        ),
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
        (
            "shifted.png",
            shifted,
            "likely cause: the image is shifted one pixel to the right",
        ),
    ];
    assert_each_said(dir.path(), students);
}

#[test]
fn a_mistake_of_the_whole_image_leaves_no_pixel_blamed_on_a_term() {
    let dir = tempfile::tempdir().unwrap();
    let reference = levels(&rendered(&scene(|_| {})));
    let flipped = flipped(&reference);
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
