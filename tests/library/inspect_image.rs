//! The ray tree of a pixel against the image: its colour is the rendered pixel, its objects are
//! what [`object_ids`] sees, and its rays project back onto the pixel.

use std::path::Path;

use glam::{Vec2, Vec3};
use raylab::bvh::Bvh;
use raylab::camera::PIXEL_CENTRE;
use raylab::formats::toml::{default_scene, load_scene};
use raylab::inspect::{object_ids, trace_ray_tree};
use raylab::progressive;
use raylab::scene::Scene;
use raylab::whitted::Tracer;

fn close(a: Vec3, b: Vec3, tolerance: f32) -> bool {
    (a - b).abs().max_element() <= tolerance
}

fn shipped(name: &str) -> Scene {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut scene = match name {
        "default" => default_scene().unwrap(),
        _ => load_scene(&dir.join(format!("{name}.toml"))).unwrap(),
    };
    scene.settings.width = 48;
    scene.settings.height = 36;
    scene.settings.samples = 1;
    scene
}

#[test]
fn the_tree_gives_the_rendered_pixel_on_the_shipped_scenes() {
    for name in ["default", "glass", "mirrors"] {
        let scene = shipped(name);
        let bvh = Bvh::build(&scene.geometry);
        let tracer = Tracer::new(&scene, &bvh);
        let (pixels, _) = progressive::render_image(&tracer);
        let (width, height) = (scene.settings.width, scene.settings.height);
        let mut deep = 0;
        for y in 0..height {
            for x in 0..width {
                let tree = trace_ray_tree(&tracer, x, y);
                let pixel = pixels[(y * width + x) as usize];
                assert_eq!(tree.color, pixel, "{name} ({x}, {y})");
                let sum = tree.sum_of_contributions();
                assert!(
                    close(sum, pixel, 1e-6),
                    "{name} ({x}, {y}): contributions add up to {sum}, pixel {pixel}"
                );
                deep += usize::from(tree.nodes.len() > 2);
            }
        }
        assert!(deep > 0, "{name}: some trees are more than two rays deep");
    }
}

#[test]
fn object_ids_name_what_each_eye_ray_hits() {
    let scene = crate::common::spheres_on_a_floor(32, 24);
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let ids = object_ids(&tracer);
    assert_eq!(ids.len(), 32 * 24);
    for (i, &id) in ids.iter().enumerate() {
        let (x, y) = (i as u32 % 32, i as u32 / 32);
        let tree = trace_ray_tree(&tracer, x, y);
        let expected = tree.nodes[0].hit.as_ref().map_or(u32::MAX, |h| h.object);
        assert_eq!(id, expected, "({x}, {y})");
    }
    let distinct: std::collections::BTreeSet<_> = ids.iter().collect();
    assert!(
        distinct.len() >= 4,
        "the floor, three spheres: {distinct:?}"
    );
}

#[test]
fn projecting_a_point_of_a_pixels_eye_ray_gives_the_pixels_centre() {
    let scene = crate::common::spheres_on_a_floor(64, 48);
    for (x, y) in [(0, 0), (63, 0), (10, 40), (32, 24)] {
        let ray = scene.camera.eye_ray((x, y), PIXEL_CENTRE, (64, 48));
        for t in [1.0, 3.5, 20.0] {
            let p = scene.camera.project(ray.at(t), 64, 48).unwrap();
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            assert!((p - centre).abs().max_element() < 1e-3, "{p} != {centre}");
        }
    }
    let behind = scene.camera.eye + scene.camera.n;
    assert_eq!(scene.camera.project(behind, 64, 48), None);
}

#[test]
fn a_segment_from_behind_the_eye_is_clipped_at_the_image_plane() {
    let scene = crate::common::spheres_on_a_floor(64, 48);
    let camera = scene.camera;
    let ahead = camera.eye - 10.0 * camera.n;
    let behind = camera.eye + 10.0 * camera.n + camera.u;
    let (a, b) = camera.project_segment(behind, ahead, 64, 48).unwrap();
    let centre = Vec2::new(32.0, 24.0);
    assert!((b - centre).length() < 1e-3, "{b}");
    assert!(a.x > 32.0, "the clipped end lies towards +u: {a}");
    assert_eq!(
        camera.project_segment(behind, behind + camera.n, 64, 48),
        None
    );
}
