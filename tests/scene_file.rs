//! The TOML scene format end to end: the shipped scenes load, a full-feature file becomes the
//! expected `Scene`, OBJ and image files are found relative to the scene file, every kind of
//! mistake is reported at its line and column, and no input makes the reader panic.

mod common;

use std::path::{Path, PathBuf};

use common::fuzz::mutate;
use common::random::Rng;
use glam::{Vec2, Vec3};
use raylab::color::Color;
use raylab::formats::SceneError;
use raylab::formats::toml::{DEFAULT_MATERIAL, load_scene, parse_scene};
use raylab::light::Light;
use raylab::material::Material;
use raylab::medium::{Atmosphere, Medium};
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::Shape;
use raylab::texture::{Texture, WOOD_COLORS, Wrap};

fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets")
}

fn scenes_dir() -> PathBuf {
    assets().join("scenes")
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    parse_scene(text, Path::new("test.toml"), &scenes_dir())
}

/// Parses `text`, which must fail, and checks where and why.
fn assert_error(text: &str, line: usize, column: usize, message_part: &str) -> SceneError {
    let error = match parse(text) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(error) => error,
    };
    assert_eq!(error.file, Path::new("test.toml"), "{error}");
    assert_eq!((error.line, error.column), (line, column), "{error}");
    assert!(
        error.message.contains(message_part),
        "expected the message to contain {message_part:?}:\n{error}"
    );
    error
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

// ---- the shipped scenes ----------------------------------------------------------------------

fn shipped_scene(name: &str) -> Scene {
    let path = scenes_dir().join(name);
    load_scene(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn shadows_scene_has_a_sphere_over_a_plane_and_one_light() {
    let scene = shipped_scene("shadows.toml");
    let shapes: Vec<&Shape> = scene.geometry.objects.iter().map(|o| &o.shape).collect();
    assert!(matches!(shapes[..], [Shape::Plane(_), Shape::Sphere(_)]));
    assert_eq!(scene.lights.len(), 1);
    assert!(scene.settings.shadows);
}

#[test]
fn mirrors_scene_has_two_facing_mirrors() {
    let scene = shipped_scene("mirrors.toml");
    let mirrors: Vec<_> = scene
        .geometry
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            Shape::Polygon(p) => Some((p.normal(), o.material)),
            _ => None,
        })
        .collect();
    assert_eq!(mirrors.len(), 2);
    for (_, material) in &mirrors {
        assert_eq!(scene.materials[*material as usize].reflectivity, 0.9);
    }
    assert!(
        (mirrors[0].0 + mirrors[1].0).length() < 1e-6,
        "they face each other"
    );
    assert_eq!(scene.settings.max_depth, 8);
}

#[test]
fn glass_scene_has_a_refracting_sphere_over_a_checkerboard() {
    let scene = shipped_scene("glass.toml");
    let sphere = &scene.geometry.objects[1];
    let glass = &scene.materials[sphere.material as usize];
    assert_eq!(
        (glass.ior, glass.transparency, glass.fresnel),
        (1.5, 0.9, true)
    );
    let floor = &scene.materials[scene.geometry.objects[0].material as usize];
    let texture = &scene.textures[floor.texture.expect("the floor is textured") as usize];
    assert!(matches!(texture, Texture::Checker3d { size: 1.0, .. }));
}

#[test]
fn textures_scene_loads_the_image_relative_to_the_scene_file() {
    let scene = shipped_scene("textures.toml");
    // Textures are numbered in name order: grid, squares.
    match &scene.textures[0] {
        Texture::Image {
            image, wrap, scale, ..
        } => {
            assert_eq!((image.width, image.height), (64, 64));
            assert_eq!(*wrap, Wrap::Repeat);
            assert_eq!(*scale, Vec2::new(2.0, 1.0));
        }
        other => panic!("expected the grid image, got {other:?}"),
    }
    assert!(matches!(
        scene.textures[1],
        Texture::CheckerUv {
            u_count: 16.0,
            v_count: 8.0,
            ..
        }
    ));
    let right = &scene.geometry.objects[2];
    assert!(right.transform.is_some());
    assert_eq!(scene.materials[right.material as usize].texture, Some(1));
}

#[test]
fn wood_and_marble_scene_names_the_books_solid_textures_and_a_background_image() {
    let scene = shipped_scene("wood_and_marble.toml");
    // Textures by name: carrara, oak, verde, walnut. Left out, a colour is the book's.
    assert_eq!(
        scene.textures[1],
        Texture::Wood {
            a: WOOD_COLORS.0,
            b: WOOD_COLORS.1
        }
    );
    assert_eq!(
        scene.textures[3],
        Texture::Wood {
            a: Color::new(0.35, 0.2, 0.1),
            b: Color::new(0.55, 0.33, 0.16)
        }
    );
    assert!(matches!(scene.textures[0], Texture::Marble { .. }));
    assert_eq!(
        scene.textures[2],
        Texture::Marble {
            color: Color::new(0.3, 0.7, 0.45)
        }
    );
    let sky = scene.background_image.as_ref().expect("a background image");
    assert_eq!((sky.width, sky.height), (192, 96));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn a_background_image_that_cannot_be_loaded_is_an_error_at_its_name() {
    assert_error(
        "[render]\nbackground_image = \"missing.png\"\n",
        2,
        20,
        "cannot load background image",
    );
    assert_error(
        "[render]\nbackground_image = \"wood_and_marble.toml\"\n",
        2,
        20,
        "cannot load background image",
    );
    assert_error(
        "[textures.t]\ntype = \"wood\"\nc = [1, 1, 1]\n",
        3,
        1,
        "unexpected keys in table: c",
    );
}

#[test]
fn meshes_scene_reads_the_obj_file_and_its_materials() {
    let scene = shipped_scene("meshes.toml");
    // Triangle, pyramid, then the OBJ's two groups.
    let triangles: Vec<usize> = scene
        .geometry
        .meshes
        .iter()
        .map(|m| m.faces.len())
        .collect();
    assert_eq!(triangles, [1, 4, 3, 1]);
    assert_eq!(scene.geometry.triangle_count(), 9);
    let copper = &scene.materials[scene.geometry.meshes[2].material as usize];
    assert_eq!(copper.color, Color::new(0.72, 0.45, 0.2));
    assert_eq!(copper.shininess, 64.0);
    let slate = &scene.materials[scene.geometry.meshes[3].material as usize];
    assert_eq!(slate.color, Color::new(0.25, 0.27, 0.3));
    assert!(
        scene.geometry.meshes[2..]
            .iter()
            .all(|m| !m.normals.is_empty())
    );
}

// ---- a full-feature file ---------------------------------------------------------------------

const FULL: &str = r#"
[render]
width = 320
height = 200
max_depth = 7
min_weight = 0.05
block_size = 8
samples = 4
aa_threshold = 0.05
background = [0.1, 0.2, 0.3]
ambient = [0.3, 0.3, 0.3]
shadows = false
reflections = false
transmission = false
textures = false
fog_steps = 12
caustic_photons = 1000
caustic_gather = 20

[camera]
eye = [0, 2, 8]
look_at = [0, 1, 0]
up = [0, 1, 0]
view_angle = 30
near = 0.5

[[lights]]
type = "point"
position = [5, 8, 5]
color = [1, 0.5, 0.25]
intensity = 2

[[lights]]
type = "directional"
direction = [0, 3, 4]

[textures.checks]
type = "checker3d"
a = [1, 0, 0]
b = [0, 0, 1]
size = 0.5

[textures.stripes]
type = "checker_uv"
u_count = 4
v_count = 1

[textures.tiles]
type = "image"
file = "../textures/grid.png"
wrap = "clamp"
scale = [3, 2]

[materials.red]
color = [0.8, 0.1, 0.1]
texture = "checks"
emission = [0.05, 0.1, 0]
ambient = 0.2
diffuse = 0.7
specular = 0.5
specular_color = [1, 1, 0]
shininess = 10
reflectivity = 0.25
transparency = 0.5
ior = 1.33
fresnel = true

[materials.blue]
color = [0, 0, 1]

[materials.stripy]
texture = "stripes"

[materials.tiled]
texture = "tiles"

[[objects]]
type = "sphere"
center = [0, 1, 0]
radius = 2
material = "red"
transform = [ { translate = [0, 1, 0] }, { rotate = { axis = [0, 1, 0], degrees = 90 } }, { scale = [1, 2, 1] } ]

[[objects]]
type = "plane"
point = [0, -1, 0]
normal = [0, 2, 0]

[[objects]]
type = "triangle"
vertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
normals = [[0, 0, 1], [0, 0, 1], [0, 0, 1]]
uvs = [[0, 0], [1, 0], [0, 1]]
material = "blue"

[[objects]]
type = "mesh"
positions = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
faces = [[0, 1, 2], [0, 2, 3]]
uvs = [[0, 0], [1, 0], [1, 1], [0, 1]]
transform = [ { scale = [2, 2, 2] } ]

[[objects]]
type = "obj"
file = "../models/tetra.obj"
material = "blue"
"#;

#[test]
fn full_feature_file_sets_every_setting() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        scene.settings,
        RenderSettings {
            width: 320,
            height: 200,
            max_depth: 7,
            min_weight: 0.05,
            block_size: 8,
            samples: 4,
            aa_threshold: 0.05,
            background: Color::new(0.1, 0.2, 0.3),
            ambient: Color::splat(0.3),
            shadows: false,
            reflections: false,
            transmission: false,
            textures: false,
            fog_steps: 12,
            caustic_photons: 1000,
            caustic_gather: 20,
        }
    );
    let spec = scene.camera.spec;
    assert_eq!(
        (spec.eye, spec.look_at),
        (Vec3::new(0.0, 2.0, 8.0), Vec3::Y)
    );
    assert_eq!((spec.view_angle, spec.near), (30.0, 0.5));
}

#[test]
fn transmission_is_also_read_under_its_old_name_refractions() {
    for key in ["transmission", "refractions"] {
        let scene = parse(&format!("[render]\n{key} = false\n")).unwrap();
        assert!(!scene.settings.transmission, "{key}");
    }
    assert!(parse("").unwrap().settings.transmission);
    // Both names at once is one setting given twice.
    assert_error(
        "[render]\ntransmission = false\nrefractions = true\n",
        3,
        1,
        "`refractions` is the old name of `transmission`",
    );
}

#[test]
fn full_feature_file_scales_light_colours_and_normalises_directions() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        scene.lights,
        [
            Light::Point {
                position: Vec3::new(5.0, 8.0, 5.0),
                color: Color::new(2.0, 1.0, 0.5),
            },
            Light::Directional {
                direction: Vec3::new(0.0, 0.6, 0.8),
                color: Color::ONE,
            },
        ]
    );
}

#[test]
fn full_feature_file_numbers_materials_and_textures_by_name() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    // Default material first, then by name: blue, red, stripy, tiled. Textures by name: checks,
    // stripes, tiles.
    assert_eq!(scene.materials.len(), 5);
    let texture_of = |m: usize| scene.materials[m].texture;
    assert_eq!((texture_of(3), texture_of(4)), (Some(1), Some(2)));
    assert_eq!(
        scene.materials[DEFAULT_MATERIAL as usize],
        Material::default()
    );
    assert_eq!(scene.materials[1].color, Color::new(0.0, 0.0, 1.0));
    assert_eq!(
        scene.materials[2],
        Material {
            color: Color::new(0.8, 0.1, 0.1),
            texture: Some(0),
            emission: Color::new(0.05, 0.1, 0.0),
            ambient: 0.2,
            diffuse: 0.7,
            specular: 0.5,
            specular_color: Color::new(1.0, 1.0, 0.0),
            shininess: 10.0,
            reflectivity: 0.25,
            transparency: 0.5,
            ior: 1.33,
            fresnel: true,
            medium: None,
        }
    );
    assert!(matches!(
        scene.textures[0],
        Texture::Checker3d { size: 0.5, .. }
    ));
    assert!(matches!(
        scene.textures[1],
        Texture::CheckerUv {
            u_count: 4.0,
            v_count: 1.0,
            ..
        }
    ));
    assert!(matches!(
        &scene.textures[2],
        Texture::Image { wrap: Wrap::Clamp, scale, .. } if *scale == Vec2::new(3.0, 2.0)
    ));
    let objects = &scene.geometry.objects;
    assert_eq!(
        (objects[0].material, objects[1].material),
        (2, DEFAULT_MATERIAL)
    );
}

#[test]
fn full_feature_file_composes_transforms_in_file_order() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    let sphere = &scene.geometry.objects[0];
    assert_eq!(
        sphere.shape,
        Shape::Sphere(raylab::shapes::Sphere {
            center: Vec3::Y,
            radius: 2.0,
        })
    );
    let transform = sphere
        .transform
        .as_ref()
        .expect("the sphere has a transform");
    // Translate by +y, then rotate 90° about y, then scale y by 2: (1, 0, 0) → (1, 1, 0) →
    // (0, 1, -1) → (0, 2, -1).
    let p = transform.point_to_world(Vec3::X);
    assert!(close(p, Vec3::new(0.0, 2.0, -1.0)), "{p}");
    // No transform key: no transform.
    assert_eq!(scene.geometry.objects[1].transform, None);
    match &scene.geometry.objects[1].shape {
        Shape::Plane(plane) => assert_eq!((plane.point, plane.normal), (-Vec3::Y, Vec3::Y)),
        other => panic!("expected the plane, got {other:?}"),
    }
}

#[test]
fn full_feature_file_turns_triangles_meshes_and_obj_files_into_meshes() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    let meshes = &scene.geometry.meshes;
    assert_eq!(meshes.len(), 4, "triangle, quad and the OBJ's two groups");
    assert_eq!(scene.geometry.triangle_count(), 1 + 2 + 4);
    assert_eq!(meshes[0].normals, [Vec3::Z; 3]);
    assert_eq!(meshes[0].material, 1);
    // The quad was scaled by 2 into the world and took the default material.
    assert_eq!(meshes[1].positions[2], Vec3::new(2.0, 2.0, 0.0));
    assert_eq!(meshes[1].uvs.len(), 4);
    assert_eq!(meshes[1].material, DEFAULT_MATERIAL);
    // A `material` key overrides the OBJ's MTL materials, which are then not added.
    assert!(meshes[2..].iter().all(|m| m.material == 1));
    assert_eq!(scene.materials.len(), 5);
}

#[test]
fn an_empty_file_is_a_scene_with_every_default() {
    let scene = parse("").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.settings, RenderSettings::default());
    assert!(scene.lights.is_empty() && scene.geometry.objects.is_empty());
    assert_eq!(scene.materials, [Material::default()]);
}

#[test]
fn objects_may_be_written_as_inline_tables() {
    let scene =
        parse("objects = [ { type = \"sphere\", radius = 3 } ]").unwrap_or_else(|e| panic!("{e}"));
    assert!(matches!(
        scene.geometry.objects[0].shape,
        Shape::Sphere(s) if s.radius == 3.0 && s.center == Vec3::ZERO
    ));
}

// ---- OBJ files and relative paths ------------------------------------------------------------

#[test]
fn obj_files_keep_their_normals_and_texture_coordinates() {
    let text = "[[objects]]\ntype = \"obj\"\nfile = \"../models/tetra.obj\"\n";
    let scene = parse(text).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.geometry.triangle_count(), 4);
    for mesh in &scene.geometry.meshes {
        assert_eq!(mesh.normals.len(), mesh.positions.len());
        assert_eq!(mesh.uvs.len(), mesh.positions.len());
        assert!(mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
    }
    // Without a `material` key, the two MTL materials join the scene after the default one.
    assert_eq!(scene.materials.len(), 3);
    let used: Vec<u32> = scene.geometry.meshes.iter().map(|m| m.material).collect();
    assert_eq!(used, [1, 2]);
}

#[test]
fn obj_files_without_normals_or_materials_load_flat_with_the_default_material() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("quad.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    )
    .unwrap();
    let text = "[[objects]]\ntype = \"obj\"\nfile = \"quad.obj\"\n";
    let scene = parse_scene(text, Path::new("test.toml"), dir.path()).unwrap();
    assert_eq!(
        scene.geometry.triangle_count(),
        2,
        "the quad is triangulated"
    );
    assert!(scene.geometry.meshes[0].normals.is_empty());
    assert_eq!(scene.geometry.meshes[0].material, DEFAULT_MATERIAL);
}

/// A unit square in the plane z = 0, one quad face.
const QUAD_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

/// A scene of one OBJ object, `quad.obj`, with `material` if given.
fn quad_scene(material: Option<&str>) -> String {
    let material = material.map_or(String::new(), |m| format!("material = \"{m}\"\n"));
    format!(
        "[materials.red]\ncolor = [1, 0, 0]\n\n[[objects]]\ntype = \"obj\"\nfile = \"quad.obj\"\n{material}"
    )
}

/// Reads `scene` from a folder that holds `files` (names and contents).
fn with_files(scene: &str, files: &[(&str, &[u8])]) -> Result<Scene, SceneError> {
    let dir = tempfile::tempdir().unwrap();
    for (name, bytes) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
    }
    parse_scene(scene, Path::new("test.toml"), dir.path())
}

/// The warning that mentions `part`, which must be there.
fn warning<'a>(scene: &'a Scene, part: &str) -> &'a str {
    let found = scene.warnings.iter().find(|w| w.contains(part));
    found.unwrap_or_else(|| panic!("no warning with {part:?} in {:?}", scene.warnings))
}

#[test]
fn obj_and_mtl_files_with_latin1_comments_a_byte_order_mark_or_a_dos_end_of_file_load() {
    let quad = QUAD_OBJ.as_bytes();
    let cases = [
        (
            "a Latin-1 comment",
            [b"# caf\xe9\n".as_slice(), quad].concat(),
        ),
        (
            "a byte-order mark",
            [b"\xef\xbb\xbf".as_slice(), quad].concat(),
        ),
        // Right after the last face, where a reader that keeps it sees a 4th index `4^Z`.
        (
            "a DOS end-of-file mark",
            [quad.strip_suffix(b"\n").unwrap(), b"\x1a"].concat(),
        ),
    ];
    for (what, obj) in cases {
        let scene = with_files(&quad_scene(None), &[("quad.obj", &obj)])
            .unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(scene.geometry.triangle_count(), 2, "{what}");
        assert!(scene.warnings.is_empty(), "{what}: {:?}", scene.warnings);
    }
    // An MTL file with a Latin-1 comment gives its materials.
    let obj = format!("mtllib quad.mtl\nusemtl rouge\n{QUAD_OBJ}");
    let mtl = b"# rouge fonc\xe9\nnewmtl rouge\nKd 0.5 0 0\n";
    let scene = with_files(
        &quad_scene(None),
        &[("quad.obj", obj.as_bytes()), ("quad.mtl", mtl)],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let material = &scene.materials[scene.geometry.meshes[0].material as usize];
    assert_eq!(material.color, Color::new(0.5, 0.0, 0.0));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn a_missing_mtl_file_and_an_undefined_material_are_warnings_at_their_line() {
    let obj = format!("mtllib gone.mtl\nusemtl red\n{QUAD_OBJ}usemtl red\nf 1 2 3\nf 1 2\n");
    let scene = with_files(&quad_scene(None), &[("quad.obj", obj.as_bytes())]).unwrap();
    assert!(warning(&scene, "quad.obj:1: ").contains("cannot read the MTL file"));
    assert!(warning(&scene, "gone.mtl").contains("quad.obj:1: "));
    assert!(warning(&scene, "quad.obj:2: ").contains("no MTL file defines the material `red`"));
    // Once per material, and in line order with the other warnings.
    let places: Vec<&str> = scene
        .warnings
        .iter()
        .map(|w| w.split(' ').next().unwrap())
        .collect();
    assert_eq!(places.len(), 3, "{:?}", scene.warnings);
    for (place, line) in places.iter().zip(["1", "2", "10"]) {
        assert!(place.ends_with(&format!("quad.obj:{line}:")), "{places:?}");
    }
    assert!(
        scene
            .geometry
            .meshes
            .iter()
            .all(|m| m.material == DEFAULT_MATERIAL)
    );

    // The MTL file is there, but does not define the material used.
    let obj = format!("mtllib quad.mtl\nusemtl bleu\n{QUAD_OBJ}");
    let mtl = b"newmtl rouge\nKd 0.5 0 0\n";
    let files: [(&str, &[u8]); 2] = [("quad.obj", obj.as_bytes()), ("quad.mtl", mtl)];
    let scene = with_files(&quad_scene(None), &files).unwrap();
    assert!(warning(&scene, "quad.obj:2: ").contains("the material `bleu`"));
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);

    // An object with a `material` key does not use the MTL materials: nothing to warn about.
    let scene = with_files(&quad_scene(Some("red")), &files).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn obj_faces_of_one_or_two_vertices_are_warnings_at_their_line() {
    let obj = format!("{QUAD_OBJ}f 1 2\nf 3\nf 1 2\n");
    let scene = with_files(&quad_scene(None), &[("quad.obj", obj.as_bytes())]).unwrap();
    let warning = warning(&scene, "quad.obj:6: ");
    assert!(warning.contains("a face of 2 vertices"), "{warning}");
    assert!(warning.contains("2 more such faces"), "{warning}");
    assert_eq!(
        scene.geometry.triangle_count(),
        2,
        "the quad is still there"
    );
}

#[test]
fn obj_face_mistakes_are_errors_at_their_line_and_column() {
    let cases = [
        ("f 1 2 x\n", 6, 7, "found `x`"),
        ("f 1 2/a 3\n", 6, 5, "found `2/a`"),
        ("f 1 2 3 # a comment\n", 6, 9, "found `#`"),
        ("f 1 2 0\n", 6, 7, "index 0"),
        (
            "f 1 2 9\n",
            6,
            7,
            "position index 9 is out of range: there are 4 `v` lines",
        ),
        ("f 1 2 -5\n", 6, 7, "position index -5 is out of range"),
        ("f\n", 6, 1, "no vertices"),
        ("usemtl\n", 6, 1, "names no material"),
        (
            "v 1 2 oops\n",
            6,
            7,
            "expected a number for `v`, found `oops`",
        ),
    ];
    for (line, row, column, part) in cases {
        let obj = format!("{QUAD_OBJ}{line}");
        let error = with_files(&quad_scene(None), &[("quad.obj", obj.as_bytes())]).unwrap_err();
        assert!(error.file.ends_with("quad.obj"), "{line:?}: {error}");
        assert_eq!(
            (error.line, error.column),
            (row, column),
            "{line:?}: {error}"
        );
        assert!(error.message.contains(part), "{line:?}: {error}");
    }
}

#[test]
fn obj_files_tobj_rejects_without_a_line_are_errors_at_the_file_name() {
    let obj = format!("{QUAD_OBJ}v 1 2 3 4 5\n");
    let error = with_files(&quad_scene(None), &[("quad.obj", obj.as_bytes())]).unwrap_err();
    assert_eq!(error.file, Path::new("test.toml"), "{error}");
    assert_eq!((error.line, error.column), (6, 8), "{error}");
    assert!(error.message.contains("cannot load OBJ file"), "{error}");
}

#[test]
fn a_scene_file_may_start_with_a_byte_order_mark_but_must_be_utf8() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, b"\xef\xbb\xbf[[objects]]\ntype = \"sphere\"\n").unwrap();
    let scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.geometry.objects.len(), 1);
    std::fs::write(&path, b"# caf\xe9\n[[objects]]\ntype = \"sphere\"\n").unwrap();
    let error = load_scene(&path).unwrap_err();
    assert_eq!((error.line, error.column), (1, 6), "{error}");
    assert!(error.message.contains("not UTF-8"), "{error}");
}

#[test]
fn relative_paths_resolve_against_the_scene_files_folder() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = dir.path().join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    std::fs::copy(
        assets().join("textures/grid.png"),
        dir.path().join("grid.png"),
    )
    .unwrap();
    let text = "[textures.grid]\ntype = \"image\"\nfile = \"../grid.png\"\n\
                [materials.m]\ntexture = \"grid\"\n";
    let scene_path = scenes.join("scene.toml");
    std::fs::write(&scene_path, text).unwrap();
    let scene = load_scene(&scene_path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.textures.len(), 1);
    // The same text read against another folder does not find the image.
    let error = parse_scene(text, Path::new("elsewhere.toml"), &assets()).unwrap_err();
    assert_eq!((error.line, error.column), (3, 8), "{error}");
}

#[test]
fn a_missing_scene_file_is_an_error_naming_it() {
    let path = scenes_dir().join("no-such-scene.toml");
    let error = load_scene(&path).unwrap_err();
    assert_eq!(error.file, path);
    assert!(error.message.contains("cannot read"), "{error}");
}

// ---- errors ----------------------------------------------------------------------------------

#[test]
fn syntax_errors_point_at_the_unexpected_character() {
    assert_error(
        "[render]\nwidth = 640\nheight = [1, 2\n",
        3,
        15,
        "expected `]`",
    );
    assert_error("[render\n", 1, 8, "expected `]`");
}

#[test]
fn display_reads_like_a_compiler_message() {
    let error = assert_error("[[objects]]\ntype = \"sphere\"\nradius = -1\n", 3, 10, "");
    assert_eq!(
        error.to_string(),
        "test.toml:3:10: sphere radius must be a positive number, got -1\n  |\n3 | radius = -1\n  |          ^^"
    );
}

#[test]
fn unknown_keys_are_errors_listing_the_known_ones() {
    assert_error("[render]\nwidht = 3\n", 2, 1, "`width`");
    let error = assert_error(
        "[[objects]]\ntype = \"sphere\"\nradiuss = 1\n",
        3,
        1,
        "radius",
    );
    assert!(
        error.message.contains("`material` and `transform`"),
        "{error}"
    );
    assert_error("colour = [1, 1, 1]\n", 1, 1, "`materials`");
    assert_error("[materials.red]\ncolour = [1, 0, 0]\n", 2, 1, "`color`");
}

#[test]
fn missing_fields_point_at_their_table() {
    assert_error(
        "[[lights]]\ntype = \"point\"\n",
        1,
        1,
        "missing field `position`",
    );
    assert_error(
        "[render]\nwidth = 10\n\n[[objects]]\ntype = \"triangle\"\n",
        4,
        1,
        "missing field `vertices`",
    );
    assert_error(
        "[textures.wood]\ntype = \"image\"\n",
        1,
        1,
        "missing field `file`",
    );
}

#[test]
fn a_missing_or_unknown_type_says_which_kinds_exist() {
    assert_error("[[objects]]\nradius = 1\n", 1, 1, "missing field `type`");
    assert_error(
        "[[objects]]\ntype = \"cube\"\n",
        2,
        8,
        "expected one of `sphere`",
    );
    assert_error(
        "[[lights]]\ntype = \"area\"\n",
        2,
        8,
        "expected one of `point`, `directional`, `spot`",
    );
    assert_error("[textures.t]\ntype = 3\n", 2, 8, "expected a string");
}

#[test]
fn wrong_types_say_what_was_expected() {
    assert_error("[render]\nwidth = \"wide\"\n", 2, 9, "expected u32");
    assert_error("[render]\nshadows = 1\n", 2, 11, "expected a boolean");
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ncenter = [0, \"up\", 0]\n",
        3,
        14,
        "expected f32",
    );
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ncenter = [0, 1]\n",
        3,
        10,
        "expected 3 values, got 2",
    );
}

#[test]
fn out_of_range_numbers_point_at_the_value() {
    assert_error(
        "[[objects]]\ntype = \"sphere\"\nradius = -2.5\n",
        3,
        10,
        "positive",
    );
    assert_error("[materials.m]\nreflectivity = 1.5\n", 2, 16, "from 0 to 1");
    assert_error("[materials.m]\ncolor = [1, -1, 0]\n", 2, 9, "non-negative");
    assert_error(
        "[textures.t]\ntype = \"checker3d\"\nsize = 0\n",
        3,
        8,
        "positive",
    );
    assert_error(
        "[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 0]\n",
        3,
        13,
        "not all zero",
    );
    // An element of an array is pointed at on its own.
    assert_error(
        "[[objects]]\ntype = \"mesh\"\npositions = [[0, 0, 0], [0, nan, 0]]\nfaces = []\n",
        3,
        25,
        "finite",
    );
}

#[test]
fn transform_steps_are_checked_where_they_are_written() {
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ntransform = [{ translate = [1, 0, 0] }, { scale = [1, 0, 1] }]\n",
        3,
        51,
        "non-zero",
    );
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ntransform = [{ rotate = { axis = [0, 0, 0], degrees = 5 } }]\n",
        3,
        34,
        "not all zero",
    );
    assert_error(
        "[[objects]]\ntype = \"plane\"\ntransform = [{ shear = [1, 0, 0] }]\n",
        3,
        16,
        "`translate`, `rotate`, `scale`",
    );
}

#[test]
fn unknown_names_list_the_names_defined() {
    assert_error(
        "[materials.red]\n[materials.blue]\n[[objects]]\ntype = \"sphere\"\nmaterial = \"green\"\n",
        5,
        12,
        "unknown material `green`; expected one of `blue`, `red`",
    );
    assert_error(
        "[materials.red]\ntexture = \"wood\"\n",
        2,
        11,
        "unknown texture `wood`; the scene defines no textures",
    );
}

#[test]
fn missing_files_point_at_the_file_name() {
    assert_error(
        "[textures.t]\ntype = \"image\"\nfile = \"no-such.png\"\n[materials.m]\ntexture = \"t\"\n",
        3,
        8,
        "cannot load texture image",
    );
    assert_error(
        "[[objects]]\ntype = \"obj\"\nfile = \"no-such.obj\"\n",
        3,
        8,
        "cannot load OBJ file",
    );
    // A file that is there but is not an image.
    assert_error(
        "[textures.t]\ntype = \"image\"\nfile = \"../models/tetra.obj\"\n\
         [materials.m]\ntexture = \"t\"\n",
        3,
        8,
        "cannot load texture image",
    );
}

#[test]
fn camera_errors_point_at_the_key_or_the_camera_table() {
    assert_error(
        "[camera]\neye = [1, 2, 3]\nlook_at = [1, 2, 3]\n",
        3,
        11,
        "coincide",
    );
    assert_error(
        "[camera]\neye = [0, 5, 0]\nup = [0, 2, 0]\n",
        3,
        6,
        "parallel",
    );
    // The default up vector is parallel: only the table can be blamed.
    assert_error("\n[camera]\neye = [0, 5, 0]\n", 2, 1, "parallel");
    assert_error("[camera]\nview_angle = 180\n", 2, 14, "view angle");
    assert_error("[camera]\nnear = 0\n", 2, 8, "near distance");
}

#[test]
fn render_settings_errors_point_at_the_key() {
    assert_error("[render]\nwidth = 0\n", 2, 9, "at least 1×1");
    assert_error("[render]\nheight = 100000\n", 2, 10, "at most");
    assert_error("[render]\nmax_depth = 0\n", 2, 13, "max_depth");
    assert_error("[render]\nmin_weight = 2\n", 2, 14, "min_weight");
    assert_error("[render]\nsamples = 0\n", 2, 11, "samples");
}

#[test]
fn block_size_must_be_a_power_of_two() {
    assert_error(
        "[render]\nblock_size = 12\n",
        2,
        14,
        "block_size must be a power of two",
    );
    assert_error("[render]\nblock_size = 128\n", 2, 14, "from 1 to 64");
}

#[test]
fn mesh_errors_point_at_the_part_at_fault() {
    let quad = "[[objects]]\ntype = \"mesh\"\npositions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n";
    assert_error(
        &format!("{quad}faces = [[0, 1, 3]]\n"),
        4,
        9,
        "vertex 3, which does not exist",
    );
    assert_error(
        &format!("{quad}faces = [[0, 1, 2]]\nnormals = [[0, 0, 1]]\n"),
        5,
        11,
        "1 normals for 3 vertices",
    );
    assert_error(
        "[[objects]]\ntype = \"triangle\"\nvertices = [[0, 0, 0], [1, 1, 1], [2, 2, 2]]\n",
        3,
        12,
        "no area",
    );
}

// ---- robustness ------------------------------------------------------------------------------

/// Characters that mean something to TOML or to the schema, and a few that do not.
const ALPHABET: &[char] = &[
    '[', ']', '{', '}', '=', '"', '\'', ',', '.', '#', '\n', ' ', '-', '+', '0', '1', '9', 'e',
    'a', 'z', '_', 'é', '\t', '\\',
];

#[test]
fn mutated_scene_files_never_panic() {
    let mut rng = Rng::with_seed(0x5EED_CAFE_F00D_1234);
    let mut originals: Vec<String> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .map(|path| std::fs::read_to_string(path).unwrap())
        .collect();
    originals.sort();
    assert!(originals.len() >= 5);
    originals.push(FULL.to_string());
    let (mut parsed, mut rejected) = (0, 0);
    for _ in 0..20_000 {
        let original = &originals[rng.usize(..originals.len())];
        let text = mutate(original, &mut rng, ALPHABET);
        let outcome = std::panic::catch_unwind(|| {
            parse_scene(&text, Path::new("fuzz.toml"), &scenes_dir()).map(|_| ())
        });
        match outcome {
            Ok(Ok(())) => parsed += 1,
            Ok(Err(error)) => {
                assert!(error.line >= 1 && error.column >= 1, "{error}");
                rejected += 1;
            }
            Err(_) => panic!("parse_scene panicked on:\n{text}"),
        }
    }
    // Both outcomes must be common, or the mutations are too mild or too wild to test much.
    assert!(
        parsed > 1000 && rejected > 1000,
        "{parsed} parsed, {rejected} rejected"
    );
}

#[test]
fn every_analytic_shape_type_is_read() {
    let scene = parse(
        r#"
[[objects]]
type = "polygon"
vertices = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 0.5, 0], [0, 1, 0]]
[[objects]]
type = "box"
min = [-1, -1, -1]
max = [1, 2, 3]
[[objects]]
type = "cylinder"
base = [0, 0, 0]
top = [0, 2, 0]
radius = 0.5
capped = false
[[objects]]
type = "cone"
base_radius = 1
top_radius = 0.5
[[objects]]
type = "ellipsoid"
radii = [1, 2, 3]
[[objects]]
type = "paraboloid"
radius = 1
height = 2
capped = true
"#,
    )
    .unwrap();
    let kinds: Vec<&str> = scene
        .geometry
        .objects
        .iter()
        .map(|o| match &o.shape {
            Shape::Polygon(_) => "polygon",
            Shape::Cuboid(_) => "box",
            Shape::TaperedCylinder(c) if c.is_capped() => "capped",
            Shape::TaperedCylinder(_) => "open",
            Shape::Ellipsoid(_) => "ellipsoid",
            Shape::Paraboloid(_) => "paraboloid",
            _ => "other",
        })
        .collect();
    assert_eq!(
        kinds,
        [
            "polygon",
            "box",
            "open",
            "capped",
            "ellipsoid",
            "paraboloid"
        ]
    );
}

#[test]
fn torus_is_read_with_its_keys_and_turned_by_its_transform() {
    let scene = parse(
        r#"
[[objects]]
type = "torus"
center = [1, 2, 3]
major_radius = 2
minor_radius = 0.5
transform = [ { rotate = { axis = [1, 0, 0], degrees = 90 } } ]
"#,
    )
    .unwrap();
    let object = &scene.geometry.objects[0];
    let Shape::Torus(torus) = &object.shape else {
        panic!("expected a torus, got {:?}", object.shape);
    };
    assert_eq!(torus.center, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!((torus.major_radius, torus.minor_radius), (2.0, 0.5));
    assert!(object.transform.is_some());
    assert!(object.shape.is_closed());
}

#[test]
fn bad_torus_radii_are_errors_at_the_object() {
    let torus = |radii: &str| format!("\n[[objects]]\ntype = \"torus\"\n{radii}\n");
    assert_error(
        &torus("major_radius = 1\nminor_radius = 1"),
        2,
        1,
        "less than major_radius",
    );
    assert_error(
        &torus("major_radius = -1\nminor_radius = 0.5"),
        2,
        1,
        "major_radius must be a positive number",
    );
    assert_error(
        &torus("major_radius = 1\nminor_radius = 0"),
        2,
        1,
        "minor_radius must be a positive number",
    );
    assert_error(&torus("major_radius = 1"), 2, 1, "minor_radius");
    assert_error(
        &torus("major_radius = 1\nminor_radius = 0.5\nradius = 2"),
        6,
        1,
        "unexpected keys in table: radius",
    );
}

#[test]
fn degenerate_shapes_are_errors_at_the_object() {
    assert_error(
        "[[objects]]\ntype = \"cylinder\"\nbase = [0, 1, 0]\ntop = [0, 1, 0]\n",
        1,
        1,
        "axis",
    );
    assert_error(
        "[[objects]]\ntype = \"polygon\"\nvertices = [[0, 0, 0], [1, 0, 0]]\n",
        1,
        1,
        "3 vertices",
    );
    assert_error(
        "[[objects]]\ntype = \"box\"\nmin = [1, 0, 0]\nmax = [0, 1, 1]\n",
        1,
        1,
        "min",
    );
}

/// A spot light whose keys after `position` are `keys`, one per line from line 4.
fn spot_scene(keys: &str) -> String {
    format!("[[lights]]\ntype = \"spot\"\nposition = [0, 4, 0]\n{keys}\n")
}

#[test]
fn spot_lights_are_read_with_their_cone() {
    let scene = parse(&spot_scene(
        "direction = [0, -2, 0]\nangle = 30\nfalloff = 5\ncolor = [1, 0.5, 0]\nintensity = 2",
    ))
    .unwrap();
    let [Light::Spot(spot)] = scene.lights[..] else {
        panic!("{:?}", scene.lights)
    };
    assert_eq!(spot.position, Vec3::new(0.0, 4.0, 0.0));
    assert_eq!(spot.direction, -Vec3::Y, "the direction is normalised");
    assert_eq!(spot.cos_angle, 30f32.to_radians().cos());
    assert_eq!(spot.cos_full, 25f32.to_radians().cos());
    assert_eq!(spot.color, Color::new(2.0, 1.0, 0.0));
    // Without a falloff the edge is hard.
    let hard = parse(&spot_scene("direction = [0, -1, 0]\nangle = 90")).unwrap();
    let [Light::Spot(hard)] = hard.lights[..] else {
        panic!()
    };
    assert_eq!(hard.cos_full, hard.cos_angle);
}

#[test]
fn spot_light_mistakes_are_errors_at_their_value() {
    assert_error(
        &spot_scene("direction = [0, 0, 0]\nangle = 30"),
        4,
        13,
        "expected a direction",
    );
    for (angle, column) in [("0", 9), ("-10", 9), ("90.5", 9), ("nan", 9)] {
        assert_error(
            &spot_scene(&format!("direction = [0, -1, 0]\nangle = {angle}")),
            5,
            column,
            "angle (the half-angle of its cone, in degrees) must be more than 0 and at most 90",
        );
    }
    for falloff in ["-1", "30.5", "inf"] {
        assert_error(
            &spot_scene(&format!(
                "direction = [0, -1, 0]\nangle = 30\nfalloff = {falloff}"
            )),
            6,
            11,
            "falloff (the degrees of soft edge inside its angle) must be from 0 to the angle, 30",
        );
    }
    assert_error(&spot_scene("angle = 30"), 1, 1, "missing field `direction`");
}

#[test]
fn an_atmosphere_is_read_with_defaults_for_what_it_leaves_out() {
    let scene =
        parse("[atmosphere]\ndensity = 0.2\nalbedo = 0.5\ncolor = [1, 0.9, 0.8]\n").unwrap();
    assert_eq!(
        scene.atmosphere,
        Atmosphere {
            medium: Medium {
                density: 0.2,
                albedo: 0.5,
                color: Color::new(1.0, 0.9, 0.8),
            },
            background_distance: None,
        }
    );
    let thin = parse("[atmosphere]\ndensity = 0.1\nbackground_distance = 50\n").unwrap();
    assert_eq!(
        thin.atmosphere,
        Atmosphere {
            medium: Medium {
                density: 0.1,
                ..Medium::default()
            },
            background_distance: Some(50.0),
        }
    );
    let endless = parse("[atmosphere]\ndensity = 0.1\nbackground_distance = inf\n").unwrap();
    assert_eq!(endless.atmosphere.background_distance, Some(f32::INFINITY));
    assert!(parse("").unwrap().atmosphere.is_clear());
    assert_eq!(RenderSettings::default().fog_steps, 16);
}

#[test]
fn caustic_settings_are_read_and_checked() {
    let scene = parse("[render]\ncaustic_photons = 50000\ncaustic_gather = 32\n").unwrap();
    assert_eq!(
        (
            scene.settings.caustic_photons,
            scene.settings.caustic_gather
        ),
        (50000, 32)
    );
    let old = parse("").unwrap();
    assert_eq!(
        old.settings.caustic_photons, 0,
        "caustics are off in old scenes"
    );
    assert_error(
        "[render]\ncaustic_gather = 0\n",
        2,
        18,
        "caustic_gather must be between 1 and 512",
    );
    assert_error(
        "[render]\ncaustic_photons = 200000000\n",
        2,
        19,
        "caustic_photons must be at most 100000000",
    );
}

#[test]
fn atmosphere_mistakes_are_errors_at_their_value() {
    assert_error("[atmosphere]\ndensity = -1\n", 2, 11, "zero or more");
    assert_error(
        "[atmosphere]\ndensity = 1\nalbedo = 1.5\n",
        3,
        10,
        "from 0 to 1",
    );
    assert_error(
        "[atmosphere]\ndensity = 1\ncolor = [1, -1, 0]\n",
        3,
        9,
        "non-negative",
    );
    assert_error(
        "[atmosphere]\nalbedo = 0.5\n",
        1,
        1,
        "missing field `density`",
    );
    assert_error("[atmosphere]\ndensity = 1\ndensty = 1\n", 3, 1, "`density`");
    assert_error(
        "[atmosphere]\ndensity = 1\nbackground_distance = 0\n",
        3,
        23,
        "a positive number or inf",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, background_distance = 5 }\n",
        2,
        25,
        "unknown field `background_distance`",
    );
    assert_error(
        "[render]\nfog_steps = 0\n",
        2,
        13,
        "fog_steps must be between 1 and 1024",
    );
    assert_error("[render]\nfog_steps = 2000\n", 2, 13, "fog_steps");
}

#[test]
fn a_material_medium_is_read_with_defaults_for_what_it_leaves_out() {
    let scene = parse(
        "[materials.smoke]\ntransparency = 1\n\
         medium = { density = 0.5, albedo = 0.25, color = [1, 0.5, 0] }\n\
         [materials.ink]\nmedium = { density = 2 }\n[materials.clear]\n",
    )
    .unwrap();
    // Materials are numbered in name order after the default: clear, ink, smoke.
    let media: Vec<_> = scene.materials.iter().map(|m| m.medium).collect();
    assert_eq!(
        media,
        [
            None,
            None,
            Some(Medium {
                density: 2.0,
                ..Medium::default()
            }),
            Some(Medium {
                density: 0.5,
                albedo: 0.25,
                color: Color::new(1.0, 0.5, 0.0),
            }),
        ]
    );
    // Ink is opaque: nothing enters it to see its medium.
    assert_eq!(
        scene.warnings,
        [
            "test.toml: material `ink` has a medium but is opaque (transparency 0): no light passes \
          into it, so the medium shows nowhere"
        ]
    );
}

#[test]
fn material_medium_mistakes_are_errors_at_their_value() {
    assert_error(
        "[materials.m]\nmedium = { density = -1 }\n",
        2,
        22,
        "zero or more",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, albedo = 2 }\n",
        2,
        34,
        "from 0 to 1",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, color = [0, -1, 0] }\n",
        2,
        33,
        "non-negative",
    );
    assert_error(
        "[materials.m]\nmedium = { albedo = 0.5 }\n",
        2,
        10,
        "missing field `density`",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, densty = 1 }\n",
        2,
        25,
        "`density`",
    );
    assert_error(
        "[materials.m]\nmedium = 0.5\n",
        2,
        10,
        "expected a medium: a table like { density = 0.5",
    );
}

#[test]
fn the_anti_aliasing_threshold_is_read_checked_and_listed() {
    let scene = parse("[render]\nsamples = 16\naa_threshold = 0.03\n").unwrap();
    assert_eq!(
        (scene.settings.samples, scene.settings.aa_threshold),
        (16, 0.03)
    );
    assert_eq!(
        parse("").unwrap().settings.aa_threshold,
        0.0,
        "uniform by default"
    );
    assert_error(
        "[render]\naa_threshold = 1.5\n",
        2,
        16,
        "aa_threshold must be between 0 (uniform sampling) and 1, got 1.5",
    );
    assert_error(
        "[render]\naa_threshold = -0.1\n",
        2,
        16,
        "aa_threshold must be",
    );
    assert_error("[render]\naa_treshold = 0.1\n", 2, 1, "`aa_threshold`");
}
