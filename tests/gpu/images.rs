//! The GPU's images against the CPU's: every shipped scene (CSG, fog, media and caustics
//! included) and the SPD scenes rendered by both tracers at 160 × 120, compared as they are
//! saved (8-bit sRGB): mean absolute difference at most 0.5 levels and at least 99 % of pixels
//! within 3 levels, with one sample per pixel (with each layout of the BVH's nodes), with
//! adaptive anti-aliasing (16 samples, threshold 0.03, at 80 × 60), with textures switched off,
//! and in the first-hit debug views; a model placed a thousand times by instances. These tests
//! need a GPU adapter: without one they fail, saying what to install (Mesa's lavapipe will do).

use std::path::Path;
use std::sync::Arc;

use crate::common::instances::balls_scene;
use crate::gpu;
use glam::Vec3;
use raylab::camera::Camera;
use raylab::color::{Color, to_srgb8};
use raylab::film::Film;
use raylab::formats::load_any;

use raylab::gpu::bvh::NodeLayout;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::frame::{GpuView, ViewKind};
use raylab::inspect::DebugView;
use raylab::progressive::gpu::GpuRenderer;
use raylab::progressive::{
    RenderControl, RenderStats, SampleColoring, Shaded, render_image, render_image_with,
};
use raylab::render::{FirstHit, assemble};
use raylab::scene::Scene;
use raylab::whitted::Tracer;
use strum::IntoEnumIterator;

const SIZE: (u32, u32) = (160, 120);

/// A scene of `tests/gpu_scenes/`, made for these tests: each puts together what the GPU must
/// trace as the CPU does, whatever the shipped scenes need besides.
fn made_here(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/gpu_scenes")
        .join(name);
    load_any(path.to_str().unwrap()).unwrap()
}

/// Every shipped scene, every SPD scene at its standard size, and the scenes of
/// `tests/gpu_scenes/`, by name.
fn all_scenes() -> Vec<(String, Scene)> {
    let made_here = crate::common::scene_files("tests/gpu_scenes");
    crate::common::shipped_and_spd_scenes()
        .into_iter()
        .chain(made_here)
        .collect()
}

/// The mean absolute difference of two 8-bit images, in levels, and the share of pixels where
/// every channel is within 3 levels.
pub fn difference(a: &[u8], b: &[u8]) -> (f64, f64) {
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

/// Renders every scene that `keep` keeps on both tracers with `adjust`ed settings, the GPU's
/// BVH nodes in `nodes`, and compares them.
fn compare_all(nodes: NodeLayout, keep: impl Fn(&Scene) -> bool, adjust: impl Fn(&mut Scene)) {
    compare_all_from(FirstHit::Rays, nodes, keep, adjust);
}

/// [`compare_all`] with the GPU's eye rays finding their first hits as `first_hit` says.
fn compare_all_from(
    first_hit: FirstHit,
    nodes: NodeLayout,
    keep: impl Fn(&Scene) -> bool,
    adjust: impl Fn(&mut Scene),
) {
    let gpu = gpu();
    let mut failures = Vec::new();
    let mut compared = 0;
    for (name, mut scene) in all_scenes().into_iter().filter(|(_, scene)| keep(scene)) {
        (scene.settings.width, scene.settings.height) = SIZE;
        adjust(&mut scene);
        let assembled = assemble(scene).unwrap();
        let mut renderer = GpuRenderer::with_nodes(Arc::clone(&gpu), &assembled, nodes)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        renderer.set_first_hit(first_hit);
        let (on_gpu, stats) = gpu_render(&renderer, &assembled.tracer());
        let (cpu_pixels, cpu_stats) = render_image(&assembled.tracer());
        let on_cpu = to_srgb8(&cpu_pixels);
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
        // From the item buffer, nearly every eye ray that hits finds its pixel's item first.
        let r = &stats.rays;
        let from_items = r.from_item_buffer as f64 / r.primary_hits.max(1) as f64;
        if first_hit == FirstHit::Raster && from_items < 0.95 {
            failures.push(format!(
                "{name}: {} of {} eye rays that hit came from the item buffer",
                r.from_item_buffer, r.primary_hits
            ));
        }
        compared += 1;
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(compared > 0, "no scene compared");
}

#[test]
fn every_scene_renders_on_the_gpu_as_on_the_cpu() {
    compare_all(NodeLayout::default(), |_| true, |_| {});
}

#[test]
fn every_scene_renders_on_the_gpu_as_on_the_cpu_with_the_other_node_layout() {
    let other = NodeLayout::iter()
        .find(|&nodes| nodes != NodeLayout::default())
        .unwrap();
    compare_all(other, |_| true, |_| {});
}

#[test]
fn every_scene_renders_on_the_gpu_from_the_item_buffer_as_on_the_cpu() {
    compare_all_from(FirstHit::Raster, NodeLayout::default(), |_| true, |_| {});
}

#[test]
fn every_scene_renders_on_the_gpu_as_on_the_cpu_with_adaptive_anti_aliasing() {
    compare_all(
        NodeLayout::default(),
        |_| true,
        |scene| {
            // A quarter of the pixels: up to 16 samples each on a software GPU.
            (scene.settings.width, scene.settings.height) = (SIZE.0 / 2, SIZE.1 / 2);
            scene.settings.samples = 16;
            scene.settings.aa_threshold = 0.03;
        },
    );
}

#[test]
fn a_model_placed_a_thousand_times_renders_on_the_gpu_as_on_the_cpu_in_both_layouts_and_rasters() {
    let gpu = gpu();
    let assembled = assemble(balls_scene(1000, true)).unwrap();
    let on_cpu = to_srgb8(&render_image(&assembled.tracer()).0);
    for (nodes, first_hit) in [
        (NodeLayout::Wide, FirstHit::Rays),
        (NodeLayout::Binary, FirstHit::Rays),
        (NodeLayout::Wide, FirstHit::Raster),
    ] {
        let mut renderer = GpuRenderer::with_nodes(Arc::clone(&gpu), &assembled, nodes).unwrap();
        renderer.set_first_hit(first_hit);
        let (on_gpu, stats) = gpu_render(&renderer, &assembled.tracer());
        let (mean, close) = difference(&on_gpu, &on_cpu);
        assert!(
            mean <= 0.5 && close >= 0.99,
            "{nodes:?}, {first_hit:?}: mean {mean:.3} levels, {:.2} % within 3",
            close * 100.0
        );
        if first_hit == FirstHit::Raster {
            let r = &stats.rays;
            assert!(
                r.from_item_buffer as f64 >= 0.95 * r.primary_hits as f64,
                "{} of {} eye rays that hit came from the item buffer",
                r.from_item_buffer,
                r.primary_hits
            );
        }
    }
}

#[test]
fn a_gpu_that_runs_few_workgroups_a_dispatch_renders_the_same_image_in_more_dispatches() {
    // 16 workgroups of 64: a dispatch of at most 1024 samples, fewer than a row of 160 pixels
    // takes at 16 samples each.
    let small = GpuDevice::with_limits(|offered| wgpu::Limits {
        max_compute_workgroups_per_dimension: 16,
        ..offered
    })
    .unwrap_or_else(|e| panic!("these tests run on a GPU: {e}"));
    let mut scene = load_any(&format!(
        "{}/assets/scenes/default.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    (scene.settings.width, scene.settings.height) = SIZE;
    scene.settings.samples = 16;
    scene.settings.aa_threshold = 0.0;
    let assembled = assemble(scene).unwrap();
    let renderer = GpuRenderer::new(Arc::new(small), &assembled).unwrap();
    let (on_gpu, stats) = gpu_render(&renderer, &assembled.tracer());
    let (cpu_pixels, cpu_stats) = render_image(&assembled.tracer());
    let (mean, close) = difference(&on_gpu, &to_srgb8(&cpu_pixels));
    assert!(
        mean <= 0.5 && close >= 0.99,
        "mean {mean}, {close} within 3"
    );
    assert_eq!(stats.rays.primary, cpu_stats.rays.primary);
}

#[test]
fn every_textured_scene_renders_on_the_gpu_as_on_the_cpu_with_textures_off() {
    let textured = |scene: &Scene| {
        scene.background_image.is_some() || scene.materials.iter().any(|m| m.texture.is_some())
    };
    compare_all(NodeLayout::default(), textured, |scene| {
        scene.settings.textures = false
    });
}

/// `tracer`'s scene rendered by `renderer` (which holds it on the GPU), as 8-bit sRGB, and what
/// it traced.
pub fn gpu_render(renderer: &GpuRenderer, tracer: &Tracer) -> (Vec<u8>, RenderStats) {
    gpu_render_view(renderer, tracer, (GpuView::Shaded, &Shaded))
}

/// [`gpu_render`] in `view` (on the GPU, and on the CPU for the samples the driver cuts short).
fn gpu_render_view(
    renderer: &GpuRenderer,
    tracer: &Tracer,
    view: (GpuView, &dyn SampleColoring),
) -> (Vec<u8>, RenderStats) {
    let settings = &tracer.scene.settings;
    let film = Film::new(settings.width, settings.height);
    let stats = renderer
        .render(tracer, view, &film, &RenderControl::default(), |_| {})
        .unwrap()
        .unwrap();
    (to_srgb8(&film.pixels()), stats)
}

/// The first-hit debug views on the GPU against the CPU's, on scenes with every kind of
/// primitive (meshes, CSG solids, textures), and the heat maps refused.
#[test]
fn the_first_hit_debug_views_render_on_the_gpu_as_on_the_cpu() {
    let gpu = gpu();
    let scenes = [
        made_here("balls_and_meshes.toml"),
        made_here("textured_balls.toml"),
        load_any(&format!(
            "{}/assets/scenes/csg_die.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap(),
    ];
    let mut compared = 0;
    let mut kinds_seen: Vec<ViewKind> = Vec::new();
    for mut scene in scenes {
        (scene.settings.width, scene.settings.height) = SIZE;
        let assembled = assemble(scene).unwrap();
        let renderer = GpuRenderer::new(Arc::clone(&gpu), &assembled).unwrap();
        let tracer = assembled.tracer();
        for view in DebugView::iter() {
            let on_gpu = match view.on_gpu(&tracer) {
                Ok(on_gpu) => on_gpu,
                Err(why) => {
                    let cpu_only = matches!(
                        view,
                        DebugView::TreeDepth
                            | DebugView::RayCount
                            | DebugView::BvhCost
                            | DebugView::ItemBuffer
                    );
                    assert!(cpu_only && why.contains("CPU only"), "{view}: {why}");
                    continue;
                }
            };
            kinds_seen.push(ViewKind::from(on_gpu));
            let (gpu_pixels, stats) = gpu_render_view(&renderer, &tracer, (on_gpu, &view));
            let (cpu_pixels, cpu_stats) = render_image_with(&tracer, &view);
            let (mean, close) = difference(&gpu_pixels, &to_srgb8(&cpu_pixels));
            assert!(
                mean <= 0.5 && close >= 0.99,
                "{view}: mean {mean} levels, {close} within 3"
            );
            // The eye rays hit the same (but for a few at the edges, in f32 against the CPU's
            // f64 where it has it), and a view casts nothing after them.
            let hits = |stats: &RenderStats| stats.rays.primary_hits as f64;
            let pixels = f64::from(SIZE.0 * SIZE.1);
            assert!(
                (hits(&stats) - hits(&cpu_stats)).abs() <= 0.005 * pixels,
                "{view}: {} eye rays hit on the GPU, {} on the CPU",
                hits(&stats),
                hits(&cpu_stats)
            );
            if view != DebugView::Shaded {
                assert_eq!(stats.rays.shadow, 0, "{view}");
            }
            compared += 1;
        }
    }
    assert_eq!(compared, 3 * 6);
    // Every kind of view the GPU draws was drawn.
    let missing: Vec<ViewKind> = ViewKind::iter()
        .filter(|kind| !kinds_seen.contains(kind))
        .collect();
    assert!(missing.is_empty(), "views not compared: {missing:?}");
}

#[test]
fn edited_materials_lights_camera_and_settings_reach_the_scene_on_the_gpu() {
    let gpu = gpu();
    let mut scene = made_here("balls_and_meshes.toml");
    (scene.settings.width, scene.settings.height) = SIZE;
    let mut assembled = assemble(scene).unwrap();
    let renderer = GpuRenderer::new(Arc::clone(&gpu), &assembled).unwrap();
    let (before, _) = gpu_render(&renderer, &assembled.tracer());
    // Edited as the viewer edits its copy of the scene: the same renderer, no new upload.
    let scene = &mut assembled.scene;
    scene.materials[0].color = Color::new(0.1, 0.7, 0.2);
    scene.materials[1].ior = 1.33;
    scene.lights[0] = scene.lights[0].scaled(0.5);
    scene.settings.max_depth = 3;
    scene.settings.shadows = false;
    let mut camera = scene.camera.spec;
    camera.eye += Vec3::new(0.5, 0.3, 0.0);
    scene.camera = Camera::new(camera).unwrap();
    let (after, _) = gpu_render(&renderer, &assembled.tracer());
    let (cpu_pixels, _) = render_image(&assembled.tracer());
    let (mean, close) = difference(&after, &to_srgb8(&cpu_pixels));
    assert!(
        mean <= 0.5 && close >= 0.99,
        "mean {mean}, {close} within 3"
    );
    let (changed, _) = difference(&after, &before);
    assert!(
        changed > 5.0,
        "the edits changed the image: {changed} levels"
    );
}

#[test]
fn the_first_block_pass_paints_each_block_with_its_top_left_pixel_as_the_cpu_does() {
    let gpu = gpu();
    let mut scene = made_here("balls_and_meshes.toml");
    (scene.settings.width, scene.settings.height) = SIZE;
    scene.settings.block_size = 16;
    let assembled = assemble(scene).unwrap();
    let renderer = GpuRenderer::new(Arc::clone(&gpu), &assembled).unwrap();
    let (width, height) = SIZE;
    // The film as each backend leaves it after its first pass.
    let first_pass = |render: &dyn Fn(&Film, &mut dyn FnMut())| {
        let film = Film::new(width, height);
        let mut shown = None;
        render(&film, &mut || {
            shown.get_or_insert_with(|| film.pixels());
        });
        shown.unwrap()
    };
    let on_gpu = first_pass(&|film, after_pass| {
        let control = RenderControl::default();
        renderer
            .render(
                &assembled.tracer(),
                (GpuView::Shaded, &Shaded),
                film,
                &control,
                |_| after_pass(),
            )
            .unwrap()
            .unwrap();
    });
    let on_cpu = first_pass(&|film, after_pass| {
        let control = RenderControl::default();
        raylab::progressive::render(&assembled.tracer(), &Shaded, film, &control, |_| {
            after_pass()
        })
        .unwrap();
    });
    for y in 0..height {
        for x in 0..width {
            let at = |p: &[Color], x: u32, y: u32| p[(y * width + x) as usize];
            let corner = (x / 16 * 16, y / 16 * 16);
            assert_eq!(
                at(&on_gpu, x, y),
                at(&on_gpu, corner.0, corner.1),
                "block of ({x}, {y})"
            );
        }
    }
    let (mean, close) = difference(&to_srgb8(&on_gpu), &to_srgb8(&on_cpu));
    assert!(
        mean <= 0.5 && close >= 0.99,
        "mean {mean}, {close} within 3"
    );
}
