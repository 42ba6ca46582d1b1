//! Instances: a model stored once and placed many times must be what its copies are. The BVH's
//! walk into instances finds exactly what testing every placed triangle finds; an image of a
//! model placed a thousand times is, bit for bit, the image of a thousand copies moved into the
//! world by the test itself; the memory is one model and a record per instance; a scene file
//! shares a model file placed twice, and places any object again by `type = "instance"`.

use std::collections::BTreeSet;
use std::mem::size_of;
use std::ops::ControlFlow;
use std::path::Path;

use crate::bvh::{brute_force, random_ray};
use crate::common::instances::{balls_scene, lumpy_ball};
use crate::common::random::{Rng, in_cube, in_range};
use crate::models::load_written;
use glam::{Mat4, Quat, Vec3};
use raylab::bvh::Bvh;
use raylab::bvh::packet::PACKET_SIZE;
use raylab::color::to_srgb8;
use raylab::formats::load_any;
use raylab::mesh::Mesh;
use raylab::primitive::{Geometry, Instance, PrimId, PrimKind};
use raylab::progressive::render_image;
use raylab::ray::Ray;
use raylab::render::assemble;
use raylab::scene::Scene;
use raylab::shapes::{Shape, Sphere};
use raylab::transform::Transform;

/// The 8-bit image of `scene` at its size.
fn image(scene: Scene) -> Vec<u8> {
    let assembled = assemble(scene).unwrap();
    to_srgb8(&render_image(&assembled.tracer()).0)
}

#[test]
fn a_model_placed_a_thousand_times_renders_as_its_thousand_copies_bit_for_bit() {
    let copies = balls_scene(1000, false);
    let instances = balls_scene(1000, true);
    assert_eq!(instances.geometry.instances().len(), 1000);
    assert!(instances.geometry.meshes.is_empty());
    assert_eq!(copies.geometry.meshes.len(), 1000);

    // Memory: one model and a record per instance, against a thousand copies.
    let model = &instances.geometry.models()[0];
    let per_instance = size_of::<Instance>() + size_of::<u32>();
    let records = instances.geometry.memory_bytes() - model.memory_bytes();
    assert!(
        records <= 2 * 1000 * per_instance + 4096,
        "{records} bytes beside the model for 1000 instances of {per_instance} bytes"
    );
    let copied = copies.geometry.memory_bytes();
    assert!(
        copied > 500 * model.memory_bytes(),
        "the copies hold {copied} bytes, the model {}",
        model.memory_bytes()
    );
    let (copies_bvh, instances_bvh) = (
        Bvh::build(&copies.geometry),
        Bvh::build(&instances.geometry),
    );
    let model_tree = instances_bvh.models[0].memory_bytes();
    let top = instances_bvh.memory_bytes() - model_tree;
    // The top tree holds 1000 entries: 1000 instances in leaves of up to 8, nodes of 256 bytes.
    assert!(top < 1000 * 128, "the instances' tree takes {top} bytes");
    assert!(copies_bvh.memory_bytes() > 100 * instances_bvh.memory_bytes() / 2);

    let (copied_image, placed_image) = (image(copies), image(instances));
    let lit = copied_image
        .chunks(3)
        .filter(|p| p.iter().any(|&c| c > 40))
        .count();
    assert!(
        lit > 160 * 120 / 2,
        "the balls and the floor show: {lit} lit pixels"
    );
    let differing = copied_image
        .chunks(3)
        .zip(placed_image.chunks(3))
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differing, 0, "pixels differ between copies and instances");
}

/// A geometry of spheres, a world mesh, and a soup of triangles placed `count` times by
/// turns, squashes, shears and mirrors.
fn placed_soup(seed: u64, count: usize) -> Geometry {
    let mut rng = Rng::with_seed(seed);
    let mut geometry = Geometry::default();
    for _ in 0..20 {
        geometry.objects.push(raylab::primitive::Object {
            shape: Shape::Sphere(Sphere {
                center: in_cube(&mut rng, -10.0, 10.0),
                radius: in_range(&mut rng, 0.2, 1.0),
            }),
            transform: None,
            material: 0,
        });
    }
    let soup = |rng: &mut Rng, triangles: u32, size: f32| {
        let mut mesh = Mesh::default();
        for i in 0..triangles {
            let c = in_cube(rng, -size, size);
            mesh.positions
                .extend([c, c + in_cube(rng, -1.0, 1.0), c + in_cube(rng, -1.0, 1.0)]);
            mesh.faces.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        mesh
    };
    geometry.add_mesh(soup(&mut rng, 100, 10.0));
    let mut model = Geometry::default();
    model.add_mesh(soup(&mut rng, 150, 2.0));
    let model = geometry.add_model(model);
    for k in 0..count {
        let turn = Quat::from_axis_angle(in_cube(&mut rng, -1.0, 1.0).normalize(), k as f32);
        let squash = in_cube(&mut rng, 0.3, 1.5) * if k % 4 == 0 { -1.0 } else { 1.0 };
        let shear = Mat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, 0.4, 1.0, 0.0, 0.0, 0.0, 0.2, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ]);
        let matrix =
            Mat4::from_scale_rotation_translation(squash, turn, in_cube(&mut rng, -8.0, 8.0))
                * if k % 3 == 0 { shear } else { Mat4::IDENTITY };
        let instance = Instance {
            model,
            transform: Transform::from_matrix(matrix).unwrap(),
            material: None,
        };
        geometry.add_instance(instance).unwrap();
    }
    geometry
}

/// Every triangle a ray may hit: the world's own and each instance's, placed.
fn every_triangle(geometry: &Geometry) -> impl Iterator<Item = PrimId> + '_ {
    let all = geometry.triangle_count() + geometry.placed_triangle_count();
    (0..all).map(PrimId::triangle)
}

#[test]
fn the_walk_into_instances_finds_what_testing_every_placed_triangle_finds() {
    for seed in 0..4 {
        let geometry = placed_soup(seed, 40);
        let bvh = Bvh::build(&geometry);
        let mut rng = Rng::with_seed(seed + 77);
        let mut placed_hits = 0;
        for _ in 0..1500 {
            let ray = random_ray(&mut rng);
            let expected = brute_force(&geometry, &ray);
            let got = bvh.closest_hit(&geometry, &ray, 0.0, f32::INFINITY);
            assert_eq!(got, expected, "seed {seed}, {ray:?}");
            // An instance tested as a primitive answers as its closest triangle.
            if let Some(hit) = got
                && let PrimKind::Triangle(t) = hit.prim.kind()
                && let Some((i, _)) = geometry.instance_of(t)
            {
                placed_hits += 1;
                let whole = geometry.intersect(PrimId::instance(i), &ray, 0.0, f32::INFINITY);
                assert_eq!(whole, Some(hit));
            }
            // Every hit on a segment, each once.
            let t_max = in_range(&mut rng, 1.0, 20.0);
            let expected: BTreeSet<PrimId> = every_triangle(&geometry)
                .chain((0..geometry.objects.len()).map(PrimId::object))
                .filter(|&id| geometry.intersect(id, &ray, 0.0, t_max).is_some())
                .collect();
            let mut found = BTreeSet::new();
            bvh.any_hit(&geometry, &ray, 0.0, t_max, |hit| {
                assert!(found.insert(hit.prim), "{:?} met twice", hit.prim);
                ControlFlow::Continue(())
            });
            assert_eq!(found, expected, "seed {seed}, {ray:?} to {t_max}");
        }
        assert!(placed_hits > 200, "only {placed_hits} rays hit an instance");
    }
}

#[test]
fn a_packet_of_eye_rays_meets_instances_as_each_ray_alone() {
    let geometry = placed_soup(9, 60);
    let bvh = Bvh::build(&geometry);
    let eye = Vec3::new(0.0, 3.0, 22.0);
    let rays: Vec<Ray> = (0..PACKET_SIZE)
        .map(|k| {
            let (x, y) = ((k % 8) as f32 - 3.5, (k / 8) as f32 - 3.5);
            Ray::new(eye, Vec3::new(x * 0.06, y * 0.06 - 0.1, -1.0))
        })
        .collect();
    let mut hits = vec![None; PACKET_SIZE];
    bvh.closest_hits(&geometry, &rays, 0.0, f32::INFINITY, &mut hits);
    let mut met = 0;
    for (ray, hit) in rays.iter().zip(&hits) {
        assert_eq!(*hit, bvh.closest_hit(&geometry, ray, 0.0, f32::INFINITY));
        met += usize::from(hit.is_some());
    }
    assert!(met > PACKET_SIZE / 4, "only {met} rays hit");
}

/// A scene file around `objects`, with a camera, a light and two materials.
fn scene_text(objects: &str) -> String {
    format!(
        "[camera]\neye = [4, 5, 9]\nlook_at = [0, 0.5, 0]\nview_angle = 40\n\
         [[lights]]\ntype = \"point\"\nposition = [5, 9, 6]\n\
         [materials.red]\ncolor = [0.9, 0.2, 0.1]\nspecular = 0.5\n\
         [materials.blue]\ncolor = [0.1, 0.3, 0.9]\n\
         [[objects]]\ntype = \"plane\"\nnormal = [0, 1, 0]\n\
         {objects}"
    )
}

/// The lumpy ball as an OBJ file.
fn ball_obj() -> String {
    let ball = lumpy_ball(6);
    let mut text = String::new();
    for (p, n) in ball.positions.iter().zip(&ball.normals) {
        text += &format!("v {} {} {}\nvn {} {} {}\n", p.x, p.y, p.z, n.x, n.y, n.z);
    }
    for f in &ball.faces {
        let [a, b, c] = f.map(|v| v + 1);
        text += &format!("f {a}//{a} {b}//{b} {c}//{c}\n");
    }
    text
}

/// An object of the scene file: the model `file` (or `instance` of the object `of`),
/// turned and moved to `x`, in `material`, with `extra` keys.
fn placed(kind: &str, x: f32, material: &str, extra: &str) -> String {
    format!(
        "[[objects]]\n{kind}\nmaterial = \"{material}\"\n{extra}\
         transform = [{{ rotate = {{ axis = [1, 1, 0], degrees = {} }} }}, \
         {{ translate = [{x}, 1, 0] }}]\n",
        x * 20.0
    )
}

fn load(dir: &Path, files: &[(&str, &[u8])], name: &str) -> Scene {
    load_written(dir, files, name)
}

#[test]
fn a_scene_file_stores_a_model_file_once_however_often_it_places_it() {
    let dir = tempfile::tempdir().unwrap();
    let obj = ball_obj();
    let file = "type = \"obj\"\nfile = \"ball.obj\"";
    let objects = [
        placed(file, -2.5, "red", "name = \"ball\"\n"),
        placed(file, 0.0, "blue", ""),
        placed("type = \"instance\"\nof = \"ball\"", 2.5, "blue", ""),
    ]
    .concat();
    let shared = scene_text(&objects);
    // The same three, each its own file: copies stored where they stand.
    let own_files = [
        placed("type = \"obj\"\nfile = \"a.obj\"", -2.5, "red", ""),
        placed("type = \"obj\"\nfile = \"b.obj\"", 0.0, "blue", ""),
        placed("type = \"obj\"\nfile = \"c.obj\"", 2.5, "blue", ""),
    ]
    .concat();
    let copies = scene_text(&own_files);
    let files: &[(&str, &[u8])] = &[
        ("ball.obj", obj.as_bytes()),
        ("a.obj", obj.as_bytes()),
        ("b.obj", obj.as_bytes()),
        ("c.obj", obj.as_bytes()),
        ("shared.toml", shared.as_bytes()),
        ("copies.toml", copies.as_bytes()),
    ];
    let shared = load(dir.path(), files, "shared.toml");
    let copies = load(dir.path(), files, "copies.toml");
    assert_eq!(shared.geometry.models().len(), 1);
    assert_eq!(shared.geometry.instances().len(), 3);
    assert!(shared.geometry.meshes.is_empty());
    assert_eq!(copies.geometry.meshes.len(), 3);
    assert!(copies.geometry.instances().is_empty());
    let (shared, copies) = (image(shared), image(copies));
    assert!(
        shared == copies,
        "the shared model renders otherwise than its copies"
    );
    let more = |a: u8, b: u8| u32::from(a) > 2 * u32::from(b) + 20;
    let blue = shared.chunks(3).filter(|p| more(p[2], p[0])).count();
    let red = shared.chunks(3).filter(|p| more(p[0], p[2])).count();
    assert!(
        blue > 2 * red && red > 200,
        "{red} red and {blue} blue pixels"
    );
}

#[test]
fn an_instance_of_a_shape_or_a_mesh_is_that_object_written_again() {
    let dir = tempfile::tempdir().unwrap();
    let ball = "type = \"sphere\"\nradius = 0.8";
    let quad = "type = \"mesh\"\npositions = [[-1, 0, -1], [1, 0, -1], [1, 0.5, 1], [-1, 0, 1]]\n\
                faces = [[0, 2, 1], [0, 3, 2]]";
    let instanced = scene_text(
        &[
            placed(ball, -2.0, "red", "name = \"ball\"\n"),
            placed("type = \"instance\"\nof = \"ball\"", 0.0, "blue", ""),
            placed(quad, 2.0, "red", "name = \"quad\"\n"),
            placed("type = \"instance\"\nof = \"quad\"", 3.5, "blue", ""),
            placed("type = \"instance\"\nof = \"quad\"", 5.0, "red", ""),
        ]
        .concat(),
    );
    let written = scene_text(
        &[
            placed(ball, -2.0, "red", ""),
            placed(ball, 0.0, "blue", ""),
            placed(quad, 2.0, "red", ""),
            placed(quad, 3.5, "blue", ""),
            placed(quad, 5.0, "red", ""),
        ]
        .concat(),
    );
    let files: &[(&str, &[u8])] = &[
        ("instanced.toml", instanced.as_bytes()),
        ("written.toml", written.as_bytes()),
    ];
    let instanced = load(dir.path(), files, "instanced.toml");
    let written = load(dir.path(), files, "written.toml");
    // The quad placed three times is one model; the ball is an object like any other.
    assert_eq!(instanced.geometry.models().len(), 1);
    assert_eq!(instanced.geometry.instances().len(), 3);
    assert_eq!(instanced.geometry.objects.len(), 3);
    assert!(image(instanced) == image(written));
}

#[test]
fn an_instance_of_no_object_or_two_objects_of_one_name_are_errors_that_say_where() {
    let dir = tempfile::tempdir().unwrap();
    let ball = "type = \"sphere\"";
    let cases = [
        (
            scene_text(&placed(
                "type = \"instance\"\nof = \"ball\"",
                0.0,
                "red",
                "",
            )),
            "no object above this one is named `ball`",
        ),
        (
            scene_text(
                &[
                    placed(ball, 0.0, "red", "name = \"ball\"\n"),
                    placed(ball, 1.0, "red", "name = \"ball\"\n"),
                ]
                .concat(),
            ),
            "is named `ball` already",
        ),
        (
            scene_text(
                "[[objects]]\nname = \"ball\"\ntype = \"sphere\"\n\
                 [[objects]]\ntype = \"csg\"\noperation = \"union\"\n\
                 children = [{ type = \"sphere\" }, { type = \"instance\", of = \"ball\" }]\n",
            ),
            "an instance cannot be a csg operand",
        ),
    ];
    for (k, (text, expected)) in cases.iter().enumerate() {
        let name = format!("bad{k}.toml");
        std::fs::write(dir.path().join(&name), text).unwrap();
        let error = match load_any(dir.path().join(&name).to_str().unwrap()) {
            Ok(_) => panic!("{name} loaded"),
            Err(e) => e.to_string(),
        };
        assert!(error.contains(expected), "{name}: {error}");
        // The first of two names is pointed to by its line.
        if let Some(line) = text.lines().position(|l| l.starts_with("name")) {
            assert!(
                !expected.contains("already") || error.contains(&format!("(line {})", line + 1)),
                "{error}"
            );
        }
        assert!(
            error.contains(&format!("{name}:")),
            "{name} names no place: {error}"
        );
    }
}
