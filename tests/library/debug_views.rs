//! The debug views (`--view`): checked against geometry known in closed form, and against each
//! other.

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::camera::{Camera, CameraSpec, PIXEL_CENTRE};
use raylab::color::Color;
use raylab::inspect::{DebugView, MISS_COLOR, id_color, object_ids};
use raylab::large_mesh::bumpy_sphere;
use raylab::material::Material;
use raylab::progressive;
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape, Sphere};
use raylab::whitted::Tracer;
use strum::{IntoEnumIterator, VariantNames};

const WIDTH: u32 = 40;
const HEIGHT: u32 = 30;

fn scene_looking_down_z() -> Scene {
    let settings = RenderSettings {
        width: WIDTH,
        height: HEIGHT,
        ..RenderSettings::default()
    };
    let camera = Camera::new(CameraSpec {
        eye: Vec3::ZERO,
        look_at: -Vec3::Z,
        up: Vec3::Y,
        view_angle: 40.0,
        near: 1.0,
    })
    .unwrap();
    Scene::new(settings, camera)
}

fn render(scene: &Scene, view: DebugView) -> Vec<Color> {
    let bvh = Bvh::build(&scene.geometry);
    progressive::render_image_with(&Tracer::new(scene, &bvh), &view).0
}

#[test]
fn every_view_has_a_name_that_parses_back() {
    for view in DebugView::iter() {
        assert_eq!(view.to_string().parse::<DebugView>(), Ok(view));
    }
    let names = [
        "shaded",
        "normals",
        "depth",
        "uv",
        "object",
        "material",
        "item-buffer",
        "tree-depth",
        "rays",
        "bvh-cost",
    ];
    assert_eq!(DebugView::VARIANTS, names);
    let error = "sparkles".parse::<DebugView>().unwrap_err();
    assert!(
        error.contains("sparkles") && error.contains("bvh-cost"),
        "{error}"
    );
}

#[test]
fn the_depth_view_shows_the_distance_to_a_wall() {
    // A wall at z = −6 facing the eye. The depth range comes from the bounded primitives: a
    // ball out of sight whose box spans z = −8 … −2, depths 2 to 8.
    let mut scene = scene_looking_down_z();
    let m = scene.add_material(Material::default());
    scene.add_object(
        Shape::Plane(Plane {
            point: Vec3::new(0.0, 0.0, -6.0),
            normal: Vec3::Z,
        }),
        None,
        m,
    );
    scene.add_object(
        Shape::Sphere(Sphere {
            center: Vec3::new(-20.0, 15.0, -5.0),
            radius: 3.0,
        }),
        None,
        m,
    );
    let pixels = render(&scene, DebugView::Depth);
    // The wall is 6 away along the view direction: (6 − 2) / (8 − 2) of the way from white
    // (near) to black (far).
    let expected = 1.0 - (6.0 - 2.0) / (8.0 - 2.0);
    for (i, p) in pixels.iter().enumerate() {
        assert!(
            (*p - Color::splat(expected)).abs().max_element() < 1e-4,
            "pixel {i}: {p}, expected grey {expected}"
        );
    }
    let bvh = Bvh::build(&scene.geometry);
    let legend = DebugView::Depth.legend(&Tracer::new(&scene, &bvh)).unwrap();
    let labels: Vec<&str> = legend.ticks.iter().map(|(_, l)| l.as_str()).collect();
    assert_eq!(labels, ["2.000", "5.000", "8.000"]);
}

#[test]
fn the_normal_view_of_a_ball_shows_its_analytic_normals() {
    let mut scene = scene_looking_down_z();
    let m = scene.add_material(Material::default());
    let (center, radius) = (Vec3::new(0.3, -0.2, -5.0), 1.5);
    scene.add_object(Shape::Sphere(Sphere { center, radius }), None, m);
    let pixels = render(&scene, DebugView::Normals);
    let mut on_ball = 0;
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let pixel = pixels[(y * WIDTH + x) as usize];
            let ray = scene.camera.eye_ray((x, y), PIXEL_CENTRE, (WIDTH, HEIGHT));
            // The nearer root of |o + t·d − c|² = r².
            let (o, d) = (ray.origin - center, ray.dir);
            let (a, b, c) = (d.dot(d), o.dot(d), o.dot(o) - radius * radius);
            let disc = b * b - a * c;
            if disc < 1e-3 {
                assert_eq!(pixel, MISS_COLOR, "({x}, {y}) misses");
                continue;
            }
            let t = (-b - disc.sqrt()) / a;
            let normal = (ray.at(t) - center) / radius;
            let expected = normal * 0.5 + 0.5;
            assert!(
                (pixel - expected).abs().max_element() < 1e-3,
                "({x}, {y}): {pixel} != {expected}"
            );
            on_ball += 1;
        }
    }
    assert!(on_ball > 100, "{on_ball}");
}

#[test]
fn the_bvh_cost_view_is_hotter_where_the_geometry_is_dense() {
    // Left: one sphere. Right: a bumpy ball of 20 000 triangles, the same size.
    let mut scene = scene_looking_down_z();
    let m = scene.add_material(Material::default());
    scene.add_object(
        Shape::Sphere(Sphere {
            center: Vec3::new(-1.6, 0.0, -6.0),
            radius: 1.2,
        }),
        None,
        m,
    );
    let mut mesh = bumpy_sphere(20_000);
    for p in &mut mesh.positions {
        *p = *p * 1.2 + Vec3::new(1.6, 0.0, -6.0);
    }
    scene.geometry.add_mesh(mesh);
    scene.settings.max_depth = 1;
    let pixels = render(&scene, DebugView::BvhCost);
    let bvh = Bvh::build(&scene.geometry);
    let ids = object_ids(&Tracer::new(&scene, &bvh));
    let brightness = |object: u32| {
        let seen: Vec<f32> = ids
            .iter()
            .zip(&pixels)
            .filter(|&(&id, _)| id == object)
            .map(|(_, p)| p.element_sum())
            .collect();
        assert!(seen.len() > 20, "object {object} is seen: {}", seen.len());
        seen.iter().sum::<f32>() / seen.len() as f32
    };
    let (sphere, mesh) = (brightness(0), brightness(1));
    assert!(mesh > sphere, "mesh {mesh} vs sphere {sphere}");
}

#[test]
fn the_object_view_colours_each_pixel_by_the_object_it_sees() {
    let scene = crate::common::spheres_on_a_floor(WIDTH, HEIGHT);
    let pixels = render(&scene, DebugView::ObjectId);
    let bvh = Bvh::build(&scene.geometry);
    let ids = object_ids(&Tracer::new(&scene, &bvh));
    for (id, pixel) in ids.iter().zip(&pixels) {
        let expected = if *id == u32::MAX {
            MISS_COLOR
        } else {
            id_color(*id)
        };
        assert_eq!(*pixel, expected);
    }
    let colors: std::collections::BTreeSet<[u32; 3]> = (0..64)
        .map(|id| id_color(id).to_array().map(f32::to_bits))
        .collect();
    assert_eq!(colors.len(), 64, "distinct colours for distinct ids");
}

#[test]
fn the_tree_depth_view_is_deeper_on_the_mirror_than_on_the_matte_ball() {
    let scene = crate::common::spheres_on_a_floor(WIDTH, HEIGHT);
    let pixels = render(&scene, DebugView::TreeDepth);
    let bvh = Bvh::build(&scene.geometry);
    let ids = object_ids(&Tracer::new(&scene, &bvh));
    let on = |object: u32| {
        let i = ids.iter().position(|&id| id == object).unwrap();
        pixels[i].element_sum()
    };
    // Objects: the matte ball 0, the mirror ball 1.
    assert!(on(1) > on(0), "mirror {} vs matte {}", on(1), on(0));
}

#[test]
fn debug_views_refine_progressively_to_the_same_image() {
    let mut scene = crate::common::spheres_on_a_floor(WIDTH, HEIGHT);
    for view in DebugView::iter() {
        scene.settings.block_size = 1;
        let direct = render(&scene, view);
        scene.settings.block_size = 16;
        let progressive = render(&scene, view);
        let differ = direct
            .iter()
            .zip(&progressive)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(differ, 0, "{view}: pixels that differ");
    }
}
