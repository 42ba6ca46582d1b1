//! Boolean objects (CSG) end to end, read from TOML: first hits known analytically for each
//! operation (a lens, the hole of a difference, the seam, rays from inside and from the
//! surface), normals facing out of the result, each operand's material, nested nodes, errors at
//! their line and column, the BVH against brute force, and a glass lens that focuses as
//! thin-lens optics predicts.

use std::path::Path;

use crate::common::random::{Rng, direction, in_cube, in_range};
use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::formats::toml::parse_scene;
use raylab::inspect::trace_ray_tree;
use raylab::primitive::{Hit, PrimId, SurfacePoint};
use raylab::ray::{Ray, offset_origin};
use raylab::scene::Scene;
use raylab::whitted::{RayKind, Tracer};

fn parse(text: &str) -> Scene {
    parse_scene(text, Path::new("test.toml"), Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// The materials every test scene names: `red` is 1, `blue` 2, `green` 3 (name order after the
/// default material).
const MATERIALS: &str = r#"
[materials.blue]
color = [0, 0, 1]
[materials.green]
color = [0, 1, 0]
[materials.red]
color = [1, 0, 0]
"#;
const BLUE: u32 = 1;
const GREEN: u32 = 2;
const RED: u32 = 3;

fn scene_of(objects: &str) -> Scene {
    parse(&format!("{MATERIALS}\n{objects}"))
}

/// The first hit along `ray` beyond `t_min`, and the surface there.
fn first_hit(scene: &Scene, ray: &Ray, t_min: f32) -> Option<(Hit, SurfacePoint)> {
    let bvh = Bvh::build(&scene.geometry);
    let hit = bvh.closest_hit(&scene.geometry, ray, t_min, f32::INFINITY)?;
    Some((hit, scene.geometry.surface(ray, &hit)))
}

#[track_caller]
fn assert_near(actual: Vec3, expected: Vec3, tolerance: f32) {
    assert!(
        actual.abs_diff_eq(expected, tolerance),
        "{actual} is not within {tolerance} of {expected}"
    );
}

/// Two unit spheres whose centres are 1.2 apart along z: the lens between z = −0.4 and 0.4,
/// with its rim at radius 0.8 in the plane z = 0.
const LENS: &str = r#"
[[objects]]
type = "csg"
operation = "intersection"
material = "red"
children = [
    { type = "sphere", center = [0, 0, 0.6], radius = 1 },
    { type = "sphere", center = [0, 0, -0.6], radius = 1, material = "blue" },
]
"#;

#[test]
fn a_ray_enters_the_lens_where_both_spheres_overlap() {
    let scene = scene_of(LENS);
    for x in [0.0, 0.3, 0.6] {
        let ray = Ray::new(Vec3::new(x, 0.0, -5.0), Vec3::Z);
        let (hit, surface) = first_hit(&scene, &ray, 0.0).expect("the lens is hit");
        // On the sphere around (0, 0, 0.6): z = 0.6 − √(1 − x²).
        let z = 0.6 - (1.0 - x * x).sqrt();
        assert!((hit.t - (z + 5.0)).abs() < 1e-5, "x = {x}: t = {}", hit.t);
        assert_near(surface.normal, Vec3::new(x, 0.0, z - 0.6), 1e-5);
        assert_eq!(
            surface.material, RED,
            "the child without a material takes the node's"
        );
        // Leaving through the other sphere, which has its own material.
        let inside = Ray::new(offset_origin(surface.point, -surface.normal), Vec3::Z);
        let (exit, back) = first_hit(&scene, &inside, 0.0).expect("the lens is left");
        assert!((inside.at(exit.t).z + z).abs() < 1e-3, "x = {x}");
        assert_eq!(back.material, BLUE);
        assert!(back.normal.z > 0.0, "the exit normal faces out of the lens");
    }
    // Beyond the rim both spheres are hit, but never together.
    assert!(first_hit(&scene, &Ray::new(Vec3::new(0.85, 0.0, -5.0), Vec3::Z), 0.0).is_none());
}

#[test]
fn a_ray_grazing_the_seam_meets_the_rim() {
    let scene = scene_of(LENS);
    let mut hits = 0;
    for dz in [-1e-3, 0.0, 1e-3] {
        let ray = Ray::new(Vec3::new(-5.0, 0.0, dz), Vec3::X);
        let (hit, _) = first_hit(&scene, &ray, 0.0).expect("the rim is hit");
        let rim = (1.0 - (0.6 + dz.abs()).powi(2)).sqrt();
        assert!(
            (hit.t - (5.0 - rim)).abs() < 1e-3,
            "dz = {dz}: t = {}",
            hit.t
        );
        hits += 1;
    }
    assert_eq!(hits, 3);
}

/// The issue's example: a box minus a sphere that pokes out of its faces.
const HOLLOW_BOX: &str = r#"
[[objects]]
type = "csg"
operation = "difference"
material = "red"
children = [
    { type = "box", min = [-1, -1, -1], max = [1, 1, 1] },
    { type = "sphere", center = [0, 0, 0], radius = 1.2, material = "blue" },
]
"#;

#[test]
fn a_difference_shows_its_hole_in_the_subtracted_material() {
    let scene = scene_of(HOLLOW_BOX);
    // Through the middle of a face: the sphere has taken it away, and nothing is left on the
    // axis.
    assert!(first_hit(&scene, &Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X), 0.0).is_none());
    // Near an edge the face is left: at y = 0.9 the sphere reaches x = ±√(1.44 − 0.81).
    let ray = Ray::new(Vec3::new(-5.0, 0.9, 0.0), Vec3::X);
    let (hit, surface) = first_hit(&scene, &ray, 0.0).expect("the box's face");
    assert!((hit.t - 4.0).abs() < 1e-5, "{}", hit.t);
    assert_near(surface.normal, -Vec3::X, 1e-6);
    assert_eq!(surface.material, RED);
    // From inside the wall the ray reaches the hole: the sphere's surface, its material, its
    // normal turned round to face out of the box's material (towards the sphere's centre).
    let from_wall = Ray::new(Vec3::new(-0.95, 0.9, 0.0), Vec3::X);
    let (hit, surface) = first_hit(&scene, &from_wall, 0.0).expect("the hole");
    let hole = (1.44f32 - 0.81).sqrt();
    assert!((from_wall.at(hit.t).x + hole).abs() < 1e-5);
    assert_eq!(surface.material, BLUE);
    assert_near(surface.normal, -Vec3::new(-hole, 0.9, 0.0) / 1.2, 1e-5);
    // Starting in the hole, the far wall is met where the sphere ends, normal towards the ray.
    let in_hole = Ray::new(Vec3::new(0.0, 0.9, 0.0), Vec3::X);
    let (hit, surface) = first_hit(&scene, &in_hole, 0.0).expect("the far wall");
    assert!((hit.t - hole).abs() < 1e-5);
    assert_eq!(surface.material, BLUE);
    assert!(surface.normal.x < 0.0);
}

#[test]
fn a_union_has_no_inner_surfaces() {
    let scene = scene_of(
        r#"
[[objects]]
type = "csg"
operation = "union"
children = [
    { type = "sphere", center = [-0.5, 0, 0], radius = 1, material = "green" },
    { type = "box", min = [0, -0.5, -0.5], max = [2, 0.5, 0.5] },
]
"#,
    );
    let ray = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
    let (hit, surface) = first_hit(&scene, &ray, 0.0).expect("the sphere");
    assert!((hit.t - 3.5).abs() < 1e-5);
    assert_eq!(surface.material, GREEN);
    // From inside the sphere, where the box begins too, the ray goes on to the box's far end.
    let inside = Ray::new(Vec3::new(-0.2, 0.0, 0.0), Vec3::X);
    let (hit, surface) = first_hit(&scene, &inside, 0.0).expect("the box's end");
    assert!((hit.t - 2.2).abs() < 1e-5, "{}", hit.t);
    assert_eq!(surface.material, 0, "the box takes the default material");
    assert_near(surface.normal, Vec3::X, 1e-6);
}

#[test]
fn a_plane_is_the_half_space_behind_it() {
    let scene = scene_of(
        r#"
[[objects]]
type = "csg"
operation = "intersection"
children = [
    { type = "sphere", radius = 1 },
    { type = "plane", point = [0, 0.5, 0], normal = [0, 1, 0], material = "green" },
]
"#,
    );
    let down = Ray::new(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y);
    let (hit, surface) = first_hit(&scene, &down, 0.0).expect("the cut face");
    assert!((hit.t - 4.5).abs() < 1e-5);
    assert_eq!(surface.material, GREEN);
    assert_near(surface.normal, Vec3::Y, 1e-6);
    let up = Ray::new(Vec3::new(0.0, -5.0, 0.0), Vec3::Y);
    let (hit, _) = first_hit(&scene, &up, 0.0).expect("the sphere's bottom");
    assert!((hit.t - 4.0).abs() < 1e-5);
}

#[test]
fn nested_nodes_keep_their_transforms_and_materials() {
    // A hollow box, moved up by 3 inside a union with a green sphere, the whole turned 90°
    // about z: the hollow box ends up at x = −3.
    let scene = scene_of(
        r#"
[[objects]]
type = "csg"
operation = "union"
transform = [ { rotate = { axis = [0, 0, 1], degrees = 90 } } ]
children = [
    { type = "sphere", radius = 0.5, material = "green" },
    { type = "csg", operation = "difference", material = "red", transform = [ { translate = [0, 3, 0] } ], children = [
        { type = "box", min = [-1, -1, -1], max = [1, 1, 1] },
        { type = "sphere", radius = 1.2, material = "blue" },
    ] },
]
"#,
    );
    let (hit, surface) = first_hit(&scene, &Ray::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z), 0.0)
        .expect("the sphere at the centre");
    assert!((hit.t - 4.5).abs() < 1e-5);
    assert_eq!(surface.material, GREEN);
    // Down onto the moved box, near its edge (turned: the box's y = 0.9 is x = −0.9 − 3 + …).
    let down = Ray::new(Vec3::new(-3.0 - 0.9, 5.0, 0.0), -Vec3::Y);
    let (hit, surface) = first_hit(&scene, &down, 0.0).expect("the hollow box");
    assert!((hit.t - 4.0).abs() < 1e-4, "{}", hit.t);
    assert_eq!(surface.material, RED);
    assert_near(surface.normal, Vec3::Y, 1e-5);
    // Through its hole.
    let through = Ray::new(Vec3::new(-3.0, 5.0, 0.0), -Vec3::Y);
    assert!(first_hit(&scene, &through, 0.0).is_none());
}

#[test]
fn rays_leaving_the_surface_neither_hit_it_again_nor_slip_through() {
    // The lens is convex: a ray leaving it outwards meets nothing, one going in leaves it.
    let scene = scene_of(LENS);
    let bvh = Bvh::build(&scene.geometry);
    let mut rng = Rng::with_seed(5);
    let (mut outward, mut inward) = (0, 0);
    while outward + inward < 2000 {
        let origin = in_cube(&mut rng, -2.0, 2.0);
        let ray = Ray::new(origin, direction(&mut rng));
        let Some(hit) = bvh.closest_hit(&scene.geometry, &ray, 0.0, f32::INFINITY) else {
            continue;
        };
        let s = scene.geometry.surface(&ray, &hit);
        // Leaving outwards into the half-space in front: the surface is not met again at once.
        let out_dir = (s.normal + 0.5 * direction(&mut rng)).normalize();
        if out_dir.dot(s.normal) > 0.1 {
            let out = Ray::new(offset_origin(s.point, s.normal), out_dir);
            if let Some(again) = bvh.closest_hit(&scene.geometry, &out, 0.0, f32::INFINITY) {
                assert!(
                    again.t > 1e-3,
                    "self-hit at {} leaving {}",
                    again.t,
                    s.point
                );
            }
            outward += 1;
        }
        // Going on inwards, from a clear entry: the solid is left somewhere, not at once.
        if ray.dir.dot(s.normal) > -0.2 {
            continue;
        }
        let in_ray = Ray::new(offset_origin(s.point, -s.normal), ray.dir);
        let exit = bvh
            .closest_hit(&scene.geometry, &in_ray, 0.0, f32::INFINITY)
            .expect("a ray inside the solid leaves it");
        assert!(exit.t > 1e-4, "exit at {} from {}", exit.t, s.point);
        inward += 1;
    }
    assert!(outward > 500, "only {outward} outward rays");
}

#[test]
fn open_surfaces_and_absurd_nesting_are_errors_at_their_place() {
    let cases = [
        (
            r#"{ type = "polygon", vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]] }"#,
            "polygon is an open surface",
        ),
        (
            r#"{ type = "cylinder", capped = false }"#,
            "tapered cylinder is an open surface",
        ),
        (
            r#"{ type = "triangle", vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]] }"#,
            "triangle is an open surface",
        ),
    ];
    for (child, message) in cases {
        let text = format!(
            "[[objects]]\ntype = \"csg\"\noperation = \"union\"\nchildren = [\n  {{ type = \"sphere\" }},\n  {child},\n]\n"
        );
        let error = parse_scene(&text, Path::new("test.toml"), Path::new("."))
            .err()
            .unwrap_or_else(|| panic!("{child} was accepted"));
        assert_eq!((error.line, error.column), (6, 3), "{error}");
        assert!(error.message.contains(message), "{error}");
    }
    // Seventeen nodes, one inside the other.
    let mut node = r#"{ type = "sphere" }"#.to_string();
    for _ in 0..17 {
        node = format!(r#"{{ type = "csg", operation = "union", children = [{node}] }}"#);
    }
    let text = format!("objects = [{node}]\n");
    let error = parse_scene(&text, Path::new("test.toml"), Path::new("."))
        .expect_err("nesting 17 deep is refused");
    assert_eq!(error.line, 1, "{error}");
    assert!(
        error.message.contains("nested more than 16 deep"),
        "{error}"
    );
    // Far deeper, the TOML reader stops first: its limit is named, and the CSG's beside it.
    for _ in 17..100 {
        node = format!(r#"{{ type = "csg", operation = "union", children = [{node}] }}"#);
    }
    let text = format!("objects = [{node}]\n");
    let error = parse_scene(&text, Path::new("test.toml"), Path::new("."))
        .expect_err("nesting 100 deep is refused");
    assert!(
        error
            .message
            .contains("nested more than 80 deep, the TOML reader's limit")
            && error.message.contains("csg objects nest at most 16 deep"),
        "{error}"
    );
    // The offending line, 6,000 characters long, is shown around the column.
    let shown = error
        .to_string()
        .lines()
        .nth(2)
        .map(|line| line.chars().count());
    assert!(shown.is_some_and(|count| count < 120), "{error}");
    let bad_operation = "[[objects]]\ntype = \"csg\"\noperation = \"xor\"\nchildren = []\n";
    let error = parse_scene(bad_operation, Path::new("test.toml"), Path::new("."))
        .expect_err("xor is no operation");
    assert_eq!((error.line, error.column), (3, 13), "{error}");
}

/// Random CSG objects (each kind of operation, a nested one, random turns) and random rays: the
/// BVH finds the same first hit as testing every object.
#[test]
fn bvh_equals_brute_force_on_random_csg_scenes() {
    let mut rng = Rng::with_seed(13);
    let operations = ["union", "intersection", "difference"];
    let mut hits = 0;
    for _ in 0..5 {
        let mut objects = String::new();
        for i in 0..12 {
            let c = in_cube(&mut rng, -6.0, 6.0);
            let r = in_range(&mut rng, 0.5, 1.5);
            let degrees = in_range(&mut rng, 0.0, 180.0);
            objects += &format!(
                r#"
[[objects]]
type = "csg"
operation = "{}"
transform = [ {{ rotate = {{ axis = [1, 1, 0], degrees = {degrees} }} }}, {{ translate = [{}, {}, {}] }} ]
children = [
    {{ type = "box", min = [-{r}, -{r}, -{r}], max = [{r}, {r}, {r}] }},
    {{ type = "sphere", center = [{}, 0, 0], radius = {} }},
    {{ type = "csg", operation = "difference", children = [
        {{ type = "cylinder", base = [0, -2, 0], top = [0, 2, 0], radius = {} }},
        {{ type = "ellipsoid", radii = [0.3, 3, 0.3] }},
    ] }},
]
"#,
                operations[i % 3],
                c.x,
                c.y,
                c.z,
                r * 0.5,
                r * 1.1,
                r * 0.6,
            );
        }
        let scene = parse(&objects);
        let g = &scene.geometry;
        let bvh = Bvh::build(g);
        for _ in 0..2000 {
            let ray = Ray::new(in_cube(&mut rng, -9.0, 9.0), direction(&mut rng));
            let got = bvh.closest_hit(g, &ray, 0.0, f32::INFINITY);
            let expected = g
                .prim_ids()
                .filter_map(|id| g.intersect(id, &ray, 0.0, f32::INFINITY))
                .min_by(|a, b| a.t.total_cmp(&b.t));
            assert_eq!(got.map(|h| (h.t, h.part)), expected.map(|h| (h.t, h.part)));
            hits += usize::from(got.is_some());
        }
    }
    assert!(hits > 1000, "only {hits} of 10000 rays hit");
}

/// A biconvex glass lens (two spheres of radius R = 10 whose centres are 19.6 apart: d = 0.4
/// thick) focuses a ray parallel to its axis, near the axis, where the lensmaker's equation
/// says: 1/f = (n − 1)·(2/R − (n − 1)·d / (n·R²)), and the focus lies f·(1 − (n − 1)·d / (n·R))
/// behind the back face.
#[test]
fn a_glass_lens_focuses_where_the_lensmaker_says() {
    let (radius, half_gap, ior) = (10.0f32, 9.8f32, 1.5f32);
    let thickness = 2.0 * (radius - half_gap);
    let inverse_f =
        (ior - 1.0) * (2.0 / radius - (ior - 1.0) * thickness / (ior * radius * radius));
    let focal_length = 1.0 / inverse_f;
    let focus = thickness / 2.0 + focal_length * (1.0 - (ior - 1.0) * thickness / (ior * radius));
    let height = 0.2;
    // One pixel, seen from the eye straight down the axis at `height`.
    let scene = parse(&format!(
        r#"
[render]
width = 1
height = 1
max_depth = 5
[camera]
eye = [{height}, 0, -20]
look_at = [{height}, 0, 0]
[materials.glass]
color = [1, 1, 1]
diffuse = 0
transparency = 1
ior = {ior}
[[objects]]
type = "csg"
operation = "intersection"
material = "glass"
children = [
    {{ type = "sphere", center = [0, 0, {half_gap}], radius = {radius} }},
    {{ type = "sphere", center = [0, 0, -{half_gap}], radius = {radius} }},
]
"#
    ));
    let bvh = Bvh::build(&scene.geometry);
    let tree = trace_ray_tree(&Tracer::new(&scene, &bvh), 0, 0);
    // Eye ray → transmitted inside the glass → transmitted out of it.
    let transmitted: Vec<_> = tree
        .nodes
        .iter()
        .filter(|n| n.kind == RayKind::Transmitted)
        .collect();
    assert!(transmitted.len() >= 2, "{tree:#?}");
    assert!(tree.nodes[0].hit.as_ref().is_some_and(|h| h.entering));
    let out = transmitted[1];
    assert!(
        out.origin.z > 0.0,
        "the second transmitted ray starts on the back face"
    );
    // Where it crosses the axis (x = 0).
    let s = -out.origin.x / out.dir.x;
    let crossing = out.origin.z + s * out.dir.z;
    assert!(
        (crossing - focus).abs() < 0.005 * focal_length,
        "crosses the axis at z = {crossing}, the lensmaker says {focus}"
    );
}

/// The BVH's box of a CSG object is tight: the overlap of an intersection's operands, the
/// first operand's for a difference.
#[test]
fn csg_bounds_are_tight() {
    let lens = scene_of(LENS);
    let b = lens.geometry.bounds(PrimId::object(0)).expect("bounded");
    assert_near(b.min, Vec3::new(-1.0, -1.0, -0.4), 1e-5);
    assert_near(b.max, Vec3::new(1.0, 1.0, 0.4), 1e-5);
    let hollow = scene_of(HOLLOW_BOX);
    let b = hollow.geometry.bounds(PrimId::object(0)).expect("bounded");
    assert_near(b.min, Vec3::splat(-1.0), 1e-6);
    assert_near(b.max, Vec3::splat(1.0), 1e-6);
}

/// The inspector names the operand a ray met, and the object-id view tells operands apart.
#[test]
fn the_inspector_names_the_operand_hit() {
    let scene = parse(&format!(
        r#"{MATERIALS}
[render]
width = 1
height = 1
[camera]
eye = [0, 0.9, -5]
look_at = [0, 0.9, 0]
[[objects]]
type = "sphere"
center = [0, 10, 0]
{HOLLOW_BOX}"#
    ));
    let bvh = Bvh::build(&scene.geometry);
    let tree = trace_ray_tree(&Tracer::new(&scene, &bvh), 0, 0);
    let hit = tree.nodes[0].hit.as_ref().expect("the box is hit");
    assert_eq!(hit.label, "csg #1 › child 1 (cuboid)");
    // Inside the hole: the sphere.
    let ray = Ray::new(Vec3::new(0.0, 0.9, 0.0), Vec3::Z);
    let (in_hole, _) = first_hit(&scene, &ray, 0.0).expect("the far wall");
    assert_eq!(
        scene.geometry.hit_label(&in_hole),
        "csg #1 › child 2 (sphere)"
    );
    let (on_box, _) =
        first_hit(&scene, &Ray::new(Vec3::new(0.0, 0.9, -5.0), Vec3::Z), 0.0).expect("the box");
    let g = &scene.geometry;
    assert_ne!(g.part_id(&in_hole), g.part_id(&on_box));
    let (plain, _) = first_hit(&scene, &Ray::new(Vec3::new(0.0, 20.0, 0.0), -Vec3::Y), 0.0)
        .expect("the plain sphere");
    assert_eq!(g.part_id(&plain), g.object_id(plain.prim));
}

/// A torus is an operand like any other: a disk with a ring-shaped groove cut through it.
#[test]
fn a_torus_cuts_a_groove() {
    let scene = scene_of(
        r#"
[[objects]]
type = "csg"
operation = "difference"
children = [
    { type = "cylinder", base = [0, -0.2, 0], top = [0, 0.2, 0], radius = 2 },
    { type = "torus", major_radius = 1.5, minor_radius = 0.3, material = "green" },
]
"#,
    );
    let down = |x: f32| first_hit(&scene, &Ray::new(Vec3::new(x, 5.0, 0.0), -Vec3::Y), 0.0);
    let (centre, _) = down(0.0).expect("the disk's middle");
    assert!((centre.t - 4.8).abs() < 1e-5);
    assert!(down(1.5).is_none(), "the groove goes right through");
    // Beside the groove's middle the tube is thinner than the disk: the top is left, and below
    // it the ray meets the groove's wall.
    let (top, _) = down(1.75).expect("the top beside the groove");
    assert!((top.t - 4.8).abs() < 1e-5);
    let inside = Ray::new(Vec3::new(1.75, 0.19, 0.0), -Vec3::Y);
    let (wall, surface) = first_hit(&scene, &inside, 0.0).expect("the groove's wall");
    let wall_y = (0.09f32 - 0.0625).sqrt();
    assert!((inside.at(wall.t).y - wall_y).abs() < 1e-4, "{}", wall.t);
    assert_eq!(surface.material, GREEN);
    assert!(
        surface.normal.y < 0.0,
        "the wall faces out of the disk, down into the groove"
    );
}

/// A shadow ray through a glass operand is tinted by the glass (once for the object), not
/// stopped by the node's material.
#[test]
fn shadows_through_a_glass_operand_are_tinted_by_it() {
    let scene = parse(
        r#"
[render]
width = 1
height = 1
[camera]
eye = [0, 1, 3]
look_at = [0, 0, 0]
[[lights]]
position = [0, 10, 0]
[materials.glass]
color = [1, 1, 1]
transparency = 0.5
[[objects]]
type = "plane"
[[objects]]
type = "csg"
operation = "intersection"
children = [
    { type = "sphere", center = [0, 5.6, 0], radius = 1, material = "glass" },
    { type = "sphere", center = [0, 4.4, 0], radius = 1, material = "glass" },
]
"#,
    );
    let bvh = Bvh::build(&scene.geometry);
    let tree = trace_ray_tree(&Tracer::new(&scene, &bvh), 0, 0);
    let shadow = &tree.nodes[0].shadows[0];
    assert_eq!(shadow.blockers.len(), 1, "{shadow:#?}");
    assert!(!shadow.blocked);
    assert_near(
        Vec3::from(shadow.light_color.to_array()),
        Vec3::splat(0.5),
        1e-6,
    );
}
