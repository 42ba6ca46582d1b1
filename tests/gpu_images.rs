//! The GPU's images against the CPU's: every shipped scene and the SPD scenes rendered by both
//! tracers at 160 × 120, compared as they are saved (8-bit sRGB): mean absolute difference at
//! most 0.5 levels and at least 99 % of pixels within 3 levels, with one sample per pixel, with
//! adaptive anti-aliasing (16 samples, threshold 0.03), and with textures switched off. A scene that needs what the GPU
//! tracer does not trace yet is listed with the reason it gives, and the test checks that it
//! still refuses it with that reason (so the list cannot go stale). These tests need a GPU
//! adapter: without one they fail, saying what to install (Mesa's lavapipe will do).

use std::path::Path;
use std::sync::Arc;

use raylab::color::to_srgb8;
use raylab::film::Film;
use raylab::formats::load_any;
use raylab::formats::spd::{Database, load_spd};
use raylab::formats::toml::parse_scene;
use raylab::gpu::device::GpuDevice;
use raylab::progressive::gpu::GpuRenderer;
use raylab::progressive::{RenderControl, render_image};
use raylab::render::assemble;
use raylab::scene::Scene;
use strum::IntoEnumIterator;

const SIZE: (u32, u32) = (160, 120);

/// Scenes the GPU tracer does not trace yet, with the words of its refusal.
const NOT_YET_ON_GPU: &[(&str, &str)] = &[
    ("caustic_glass_ball.toml", "caustics"),
    ("caustic_ring.toml", "caustics"),
    ("fog_spot.toml", "fog"),
    ("smoky_glass.toml", "media inside objects"),
];

fn gpu() -> Arc<GpuDevice> {
    Arc::new(GpuDevice::new().unwrap_or_else(|e| panic!("these tests run on a GPU: {e}")))
}

/// A scene made here: a glass ball, a mirror ball and a matte one on a great ball for a floor,
/// a smooth-shaded mesh and a flat one, lit by a directional, a point and a spot light.
fn balls_and_meshes() -> Scene {
    let text = r#"
        [render]
        max_depth = 6
        background = [0.6, 0.7, 0.9]
        [camera]
        eye = [0, 2.5, 7]
        look_at = [0, 1, 0]
        view_angle = 40
        [[lights]]
        type = "directional"
        direction = [-1, 3, 2]
        color = [0.8, 0.8, 0.8]
        [[lights]]
        type = "point"
        position = [3, 5, 3]
        color = [0.5, 0.4, 0.3]
        [[lights]]
        type = "spot"
        position = [-3, 6, 4]
        direction = [0.4, -1, -0.5]
        angle = 30
        falloff = 10
        color = [30, 30, 30]
        [materials.floor]
        color = [0.8, 0.3, 0.2]
        specular = 0.3
        [materials.mirror]
        color = [0.9, 0.9, 0.9]
        reflectivity = 0.7
        specular = 0.5
        shininess = 50
        [materials.glass]
        color = [1, 1, 1]
        ambient = 0
        diffuse = 0.05
        specular = 0.8
        shininess = 200
        reflectivity = 0.1
        transparency = 0.9
        ior = 1.5
        fresnel = true
        [[objects]]
        type = "sphere"
        center = [0, -1000, 0]
        radius = 1000
        material = "floor"
        [[objects]]
        type = "sphere"
        center = [0, 1.2, 0]
        radius = 1.2
        material = "glass"
        [[objects]]
        type = "sphere"
        center = [-2.5, 1, -1]
        radius = 1
        material = "mirror"
        [[objects]]
        type = "obj"
        file = "torus.obj"
        material = "floor"
        transform = [{ translate = [2.5, 0.6, -1] }]
        [[objects]]
        type = "obj"
        file = "tetra.obj"
        transform = [{ scale = [0.8, 0.8, 0.8] }, { translate = [1.5, 0.5, 1.5] }]
    "#;
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/models");
    parse_scene(text, Path::new("balls_and_meshes"), &models).unwrap()
}

/// A scene made here: a ball of every kind of texture on a checkered great ball for a floor, a
/// marble glass ball (its texture tints the light through it), an image wrapped around a mesh by
/// its texture coordinates, and a background image behind them.
fn textured_balls() -> Scene {
    let text = r#"
        [render]
        max_depth = 5
        background = [0.1, 0.1, 0.15]
        background_image = "../textures/sky.bmp"
        [camera]
        eye = [0, 2.2, 7]
        look_at = [0, 0.8, 0]
        view_angle = 45
        [[lights]]
        type = "point"
        position = [4, 6, 5]
        [[lights]]
        type = "directional"
        direction = [-1, 2, 1]
        color = [0.3, 0.3, 0.3]
        [textures.floor]
        type = "checker3d"
        a = [0.82, 0.8, 0.74]
        b = [0.12, 0.14, 0.18]
        size = 0.7
        [textures.squares]
        type = "checker_uv"
        a = [0.9, 0.8, 0.2]
        b = [0.2, 0.3, 0.7]
        u_count = 16
        v_count = 8
        [textures.oak]
        type = "wood"
        [textures.verde]
        type = "marble"
        color = [0.3, 0.7, 0.45]
        [textures.grid]
        type = "image"
        file = "../textures/grid.png"
        wrap = "repeat"
        scale = [2, 1]
        [textures.bricks]
        type = "image"
        file = "../textures/bricks.png"
        wrap = "clamp"
        scale = [1.5, 1.5]
        [materials.floor]
        texture = "floor"
        [materials.squares]
        texture = "squares"
        [materials.oak]
        texture = "oak"
        specular = 0.3
        [materials.verde]
        texture = "verde"
        specular = 0.5
        reflectivity = 0.2
        [materials.grid]
        texture = "grid"
        [materials.bricks]
        texture = "bricks"
        [materials.marble_glass]
        texture = "verde"
        ambient = 0
        diffuse = 0.1
        specular = 0.8
        transparency = 0.8
        ior = 1.3
        [[objects]]
        type = "sphere"
        center = [0, -1000, 0]
        radius = 1000
        material = "floor"
        [[objects]]
        type = "sphere"
        center = [-2.4, 0.8, 0]
        radius = 0.8
        material = "squares"
        [[objects]]
        type = "sphere"
        center = [0, 0, 0]
        radius = 0.8
        material = "oak"
        transform = [{ rotate = { axis = [1, 0, 0], degrees = 60 } }, { translate = [-0.8, 0.8, -1.5] }]
        [[objects]]
        type = "sphere"
        center = [0.9, 0.8, -1.5]
        radius = 0.8
        material = "verde"
        [[objects]]
        type = "sphere"
        center = [2.4, 0.8, 0]
        radius = 0.8
        material = "grid"
        [[objects]]
        type = "sphere"
        center = [0, 0.6, 1.2]
        radius = 0.6
        material = "marble_glass"
        [[objects]]
        type = "obj"
        file = "torus.obj"
        material = "bricks"
        transform = [{ scale = [0.7, 0.7, 0.7] }, { translate = [1.4, 0.4, 1.6] }]
    "#;
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/models");
    parse_scene(text, Path::new("textured_balls"), &models).unwrap()
}

/// Every shipped scene and every SPD scene at its standard size, and the scenes made here
/// ([`balls_and_meshes`], [`textured_balls`]), by name.
fn all_scenes() -> Vec<(String, Scene)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| {
            let name = path.file_name().unwrap().to_string_lossy();
            (name.ends_with(".toml") && !name.ends_with(".camera.toml")) || name.ends_with(".dat")
        })
        .collect();
    files.sort();
    let shipped = files.into_iter().map(|path| {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        (name, load_any(path.to_str().unwrap()).unwrap())
    });
    let spd = Database::iter().map(|database| {
        let name = format!("spd:{database}");
        let scene = load_spd(&name, Default::default()).unwrap();
        (name, scene)
    });
    let made_here = [
        ("balls_and_meshes".to_string(), balls_and_meshes()),
        ("textured_balls".to_string(), textured_balls()),
    ];
    shipped.chain(spd).chain(made_here).collect()
}

/// The mean absolute difference of two 8-bit images, in levels, and the share of pixels where
/// every channel is within 3 levels.
fn difference(a: &[u8], b: &[u8]) -> (f64, f64) {
    let mean = a
        .iter()
        .zip(b)
        .map(|(x, y)| f64::from(x.abs_diff(*y)))
        .sum::<f64>()
        / a.len() as f64;
    let close = a
        .chunks(3)
        .zip(b.chunks(3))
        .filter(|(p, q)| p.iter().zip(*q).all(|(x, y)| x.abs_diff(*y) <= 3))
        .count();
    (mean, close as f64 / (a.len() / 3) as f64)
}

/// Renders every scene on both tracers with `adjust`ed settings and compares them.
fn compare_all(adjust: impl Fn(&mut Scene)) {
    let gpu = gpu();
    let mut failures = Vec::new();
    let mut compared = 0;
    for (name, mut scene) in all_scenes() {
        (scene.settings.width, scene.settings.height) = SIZE;
        adjust(&mut scene);
        let assembled = assemble(scene).unwrap();
        let refusal = NOT_YET_ON_GPU
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, why)| *why);
        let renderer = match (GpuRenderer::new(Arc::clone(&gpu), &assembled), refusal) {
            (Ok(renderer), None) => renderer,
            (Err(e), Some(why)) => {
                assert!(e.contains(why) && e.contains("--device cpu"), "{name}: {e}");
                continue;
            }
            (Err(e), None) => panic!("{name}: {e}"),
            (Ok(_), Some(why)) => {
                panic!("{name} renders on the GPU now: take it off the list ({why})")
            }
        };
        let settings = &assembled.scene.settings;
        let film = Film::new(settings.width, settings.height);
        let stats = renderer
            .render(&assembled.scene, &film, &RenderControl::default(), |_| {})
            .unwrap()
            .unwrap();
        let (cpu_pixels, cpu_stats) = render_image(&assembled.tracer());
        let (on_gpu, on_cpu) = (to_srgb8(&film.pixels()), to_srgb8(&cpu_pixels));
        let (mean, close) = difference(&on_gpu, &on_cpu);
        eprintln!(
            "{name}: mean {mean:.4} levels, {:.3} % within 3; eye rays {} / {}, secondary {} / {}",
            close * 100.0,
            stats.rays.primary,
            cpu_stats.rays.primary,
            stats.rays.reflected + stats.rays.transmitted,
            cpu_stats.rays.reflected + cpu_stats.rays.transmitted,
        );
        if mean > 0.5 || close < 0.99 {
            failures.push(format!(
                "{name}: mean {mean:.3} levels, {:.2} % within 3",
                close * 100.0
            ));
        }
        compared += 1;
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(compared > 0, "no scene compared");
}

#[test]
fn every_scene_renders_on_the_gpu_as_on_the_cpu() {
    compare_all(|_| {});
}

#[test]
fn every_scene_renders_on_the_gpu_as_on_the_cpu_with_adaptive_anti_aliasing() {
    compare_all(|scene| {
        scene.settings.samples = 16;
        scene.settings.aa_threshold = 0.03;
    });
}

#[test]
fn every_scene_renders_on_the_gpu_as_on_the_cpu_with_textures_off() {
    compare_all(|scene| scene.settings.textures = false);
}
