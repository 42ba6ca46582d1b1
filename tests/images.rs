//! Small renders of the shipped scenes against reference images checked into
//! `tests/reference/` (each looked at by a person before it was committed), within a tolerance
//! that absorbs floating-point differences between machines but not a changed picture.
//!
//! To update the references after an intended change of the pictures:
//! `RAYLAB_BLESS=1 cargo test --test images`, then look at every file before committing.

use std::path::{Path, PathBuf};

use raylab::bvh::Bvh;
use raylab::color::to_srgb8;
use raylab::formats::image::save_image;
use raylab::formats::nff::NffLighting;
use raylab::formats::toml::{default_scene, load_scene};
use raylab::formats::{load_any, load_any_with};
use raylab::progressive;
use raylab::scene::Scene;
use raylab::whitted::Tracer;

/// The size of the teaching scenes' pictures.
const SIZE: (u32, u32) = (160, 120);
/// The size of the SPD scenes' pictures: square, as SPD renders them.
const SPD_SIZE: (u32, u32) = (128, 128);

fn reference_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/reference/{name}.png"))
}

fn render_small(mut scene: Scene, (width, height): (u32, u32)) -> Vec<u8> {
    scene.settings.width = width;
    scene.settings.height = height;
    let bvh = Bvh::build(&scene.geometry);
    let (pixels, _) = progressive::render_image(&Tracer::new(&scene, &bvh));
    to_srgb8(&pixels)
}

/// How far two 8-bit images are apart: the mean absolute difference per channel, and the share
/// of pixels where some channel differs by more than 24 levels.
fn difference(a: &[u8], b: &[u8]) -> (f64, f64) {
    let mean = a
        .iter()
        .zip(b)
        .map(|(x, y)| x.abs_diff(*y) as f64)
        .sum::<f64>()
        / a.len() as f64;
    let far = a
        .chunks(3)
        .zip(b.chunks(3))
        .filter(|(p, q)| p.iter().zip(*q).any(|(x, y)| x.abs_diff(*y) > 24))
        .count();
    (mean, far as f64 / (a.len() / 3) as f64)
}

fn check(name: &str, scene: Scene, size: (u32, u32)) {
    let image = render_small(scene, size);
    let path = reference_path(name);
    if std::env::var_os("RAYLAB_BLESS").is_some() {
        let linear: Vec<_> = image
            .chunks(3)
            .map(|c| glam::Vec3::from_array([c[0], c[1], c[2]].map(srgb_decode)))
            .collect();
        save_image(&path, size.0, size.1, &linear).unwrap();
    }
    let reference = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (RAYLAB_BLESS=1 makes it)", path.display()))
        .to_rgb8();
    assert_eq!(reference.dimensions(), size, "{name}");
    let (mean, far) = difference(&image, reference.as_raw());
    assert!(
        mean < 1.0 && far < 0.005,
        "{name}: mean difference {mean:.3} levels, {:.2}% of pixels far off",
        far * 100.0
    );
}

/// Inverse of the 8-bit sRGB encoding, so that blessing writes exactly the rendered bytes.
fn srgb_decode(v: u8) -> f32 {
    raylab::color::srgb_to_linear(v as f32 / 255.0)
}

fn shipped(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("assets/scenes/{name}.toml"));
    load_scene(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn default_scene_matches_its_reference() {
    check("default", default_scene().unwrap(), SIZE);
}

#[test]
fn teaching_scenes_match_their_references() {
    for name in [
        "shadows", "mirrors", "glass", "textures", "meshes", "quadrics",
    ] {
        check(name, shipped(name), SIZE);
    }
}

#[test]
fn the_comparison_notices_a_changed_picture() {
    let scene = default_scene().unwrap();
    let mut darker = scene.clone();
    darker.lights.truncate(1);
    let (a, b) = (render_small(scene, SIZE), render_small(darker, SIZE));
    let (mean, far) = difference(&a, &b);
    assert!(
        mean >= 1.0 || far >= 0.005,
        "losing a light must fail the check"
    );
}

#[test]
fn spd_scenes_match_their_references() {
    for name in [
        "spd:balls:3",
        "spd:gears:3",
        "spd:mount:5",
        "spd:rings:3",
        "spd:teapot:6",
        "spd:tetra:5",
        "spd:tree:8",
    ] {
        let scene = load_any(name).unwrap_or_else(|e| panic!("{e}"));
        check(&name.replace(':', "-"), scene, SPD_SIZE);
    }
}

#[test]
fn povray_lighting_matches_its_reference() {
    let scene = load_any_with("spd:mount:5", NffLighting::Povray).unwrap();
    check("spd-mount-5-povray", scene, SPD_SIZE);
}

#[test]
fn an_spd_file_looks_like_the_generated_scene() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/nff/tree-6.nff");
    let from_file = load_any(path.to_str().unwrap()).unwrap();
    let generated = load_any("spd:tree:6").unwrap();
    // The file holds six significant digits, so a few edges may fall differently.
    let (mean, far) = difference(
        &render_small(from_file, SPD_SIZE),
        &render_small(generated, SPD_SIZE),
    );
    assert!(
        mean < 1.0 && far < 0.005,
        "{mean:.3} levels, {far:.4} far off"
    );
}
