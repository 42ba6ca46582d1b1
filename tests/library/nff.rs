//! The NFF reader end to end: every entity becomes the expected part of a `Scene`, SPD's own
//! files load, every kind of mistake is reported at its line and column, no mutation of a file
//! makes the reader panic, and large files parse whole (how fast: `cargo bench --bench nff`).

use std::path::{Path, PathBuf};

use crate::common::fuzz::mutate;
use crate::common::random::Rng;
use glam::Vec3;
use raylab::formats::nff::{NffLighting, SPD_MAX_DEPTH, load_nff, parse_nff, parse_nff_document};
use raylab::formats::spd::Database;
use raylab::formats::toml::DEFAULT_MATERIAL;
use raylab::formats::{SceneError, load_any, load_any_with};
use raylab::light::Light;
use raylab::scene::Scene;
use raylab::shapes::Shape;

/// A file with every entity, one of each form.
const EVERY_ENTITY: &str = "\
# every entity of NFF
b 0.1 0.2 0.3
v
from 0 -5 2
at 0 0 0.5
up 0 0 1
angle 40
hither 0.5
resolution 64 48
l 2 -3 4
l -2 -3 4 0.5 0.4 0.3
f 1 0 0 0.7 0.3 20 0 1
s 0 0 1 0.5
c 0 0 0 0.2 0 0 1 0.1   # a cone on one line
c
1 0 0 0.1
1 0 1 0.3
f 0.2 0.9 0.2 0.5 0.1 10 0.8 1.5
p 4
-3 -3 0
3 -3 0
3 3 0
-3 3 0
pp 3
0 0 2 0 0 1
1 0 2 0 0 1
0 1 2 0 0 1
";

fn parse(text: &str) -> Result<Scene, SceneError> {
    parse_nff(text, Path::new("test.nff"), NffLighting::Readme)
}

fn nff_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/nff")
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

/// `text` must fail at `line`:`column` with a message containing `part`.
fn assert_error(text: &str, line: usize, column: usize, part: &str) -> SceneError {
    let error = match parse(text) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(error) => error,
    };
    assert_eq!(error.file, Path::new("test.nff"), "{error}");
    assert_eq!((error.line, error.column), (line, column), "{error}");
    assert!(
        error.message.contains(part),
        "expected the message to contain {part:?}:\n{error}"
    );
    error
}

/// A valid head (view and light) followed by `body`; errors in `body` are on line 9 on.
fn with_head(body: &str) -> String {
    format!(
        "v\nfrom 0 -5 0\nat 0 0 0\nup 0 0 1\nangle 45\nhither 1\nresolution 8 8\nl 1 1 1\n{body}"
    )
}

// ---- every entity --------------------------------------------------------------------------

#[test]
fn the_view_becomes_the_camera_and_the_image_size() {
    let scene = parse(EVERY_ENTITY).unwrap_or_else(|e| panic!("{e}"));
    let camera = &scene.camera;
    assert!(close(camera.eye, Vec3::new(0.0, -5.0, 2.0)));
    assert!(close(camera.spec.look_at, Vec3::new(0.0, 0.0, 0.5)));
    // Up is made perpendicular to the view, keeping its side.
    assert!(camera.v.dot(camera.n).abs() < 1e-6 && camera.v.z > 0.9);
    assert_eq!(camera.near, 0.5, "hither is the near plane");
    assert_eq!((scene.settings.width, scene.settings.height), (64, 48));
    assert!(close(scene.settings.background, Vec3::new(0.1, 0.2, 0.3)));
}

#[test]
fn the_angle_spans_the_width_of_a_wide_image() {
    let scene = parse(EVERY_ENTITY).unwrap();
    let (w, h) = (64, 48);
    let camera = &scene.camera;
    // From the middle of the left edge to the middle of the right edge: 40°.
    let left = camera.dir_rc(h as f32 / 2.0, 0.0, h, w).normalize();
    let right = camera.dir_rc(h as f32 / 2.0, w as f32, h, w).normalize();
    let angle = left.angle_between(right).to_degrees();
    assert!((angle - 40.0).abs() < 1e-3, "{angle}");
    let bottom = camera.dir_rc(0.0, w as f32 / 2.0, h, w).normalize();
    let top = camera.dir_rc(h as f32, w as f32 / 2.0, h, w).normalize();
    let vertical = bottom.angle_between(top).to_degrees();
    let expected = 2.0 * (20f32.to_radians().tan() * 0.75).atan().to_degrees();
    assert!(
        (vertical - expected).abs() < 1e-3,
        "{vertical} vs {expected}"
    );
}

#[test]
fn lights_without_a_colour_share_the_readme_intensity() {
    let scene = parse(EVERY_ENTITY).unwrap();
    let share = 2f32.sqrt() / 4.0;
    assert_eq!(scene.lights.len(), 2);
    assert_eq!(
        scene.lights[0],
        Light::Point {
            position: Vec3::new(2.0, -3.0, 4.0),
            color: Vec3::splat(share)
        }
    );
    assert!(
        matches!(scene.lights[1], Light::Point { color, .. } if close(color, Vec3::new(0.5, 0.4, 0.3)))
    );
    assert!(close(scene.settings.ambient, Vec3::splat(share)));
}

#[test]
fn povray_lighting_is_brighter_and_its_ambient_light_white() {
    let scene = parse_nff(EVERY_ENTITY, Path::new("t.nff"), NffLighting::Povray).unwrap();
    let share = 1.0 / 2f32.sqrt();
    assert!(
        matches!(scene.lights[0], Light::Point { color, .. } if close(color, Vec3::splat(share)))
    );
    assert_eq!(scene.settings.ambient, Vec3::ONE);
}

#[test]
fn the_ray_tree_follows_spd_rules() {
    let scene = parse(EVERY_ENTITY).unwrap();
    assert_eq!(scene.settings.max_depth, SPD_MAX_DEPTH);
    assert_eq!(scene.settings.max_depth, 5);
    assert_eq!(scene.settings.min_weight, 0.0, "no adaptive cut-off");
}

#[test]
fn fills_become_materials_for_the_objects_after_them() {
    let scene = parse(EVERY_ENTITY).unwrap();
    // The default material, then one per `f`.
    assert_eq!(scene.materials.len(), 3);
    let red = &scene.materials[1];
    assert_eq!(red.color, Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(
        (red.diffuse, red.specular, red.reflectivity),
        (0.7, 0.3, 0.3)
    );
    assert_eq!((red.shininess, red.transparency, red.ior), (20.0, 0.0, 1.0));
    assert_eq!(
        red.ambient, red.diffuse,
        "ambient light is reflected like diffuse light"
    );
    let glass = &scene.materials[2];
    assert_eq!(
        (glass.transparency, glass.ior, glass.fresnel),
        (0.8, 1.5, false)
    );
    let materials: Vec<u32> = scene.geometry.objects.iter().map(|o| o.material).collect();
    assert_eq!(materials, [1, 1, 1, 2]);
    assert_eq!(scene.geometry.meshes[0].material, 2);
    assert_ne!(DEFAULT_MATERIAL, 1);
}

#[test]
fn spheres_cones_and_polygons_become_shapes() {
    let scene = parse(EVERY_ENTITY).unwrap();
    let shapes: Vec<&Shape> = scene.geometry.objects.iter().map(|o| &o.shape).collect();
    match shapes[..] {
        [
            Shape::Sphere(s),
            Shape::TaperedCylinder(c1),
            Shape::TaperedCylinder(c2),
            Shape::Polygon(p),
        ] => {
            assert_eq!((s.center, s.radius), (Vec3::Z, 0.5));
            assert!(!c1.is_capped() && !c2.is_capped(), "NFF cones are open");
            assert!(close(p.normal(), Vec3::Z), "counter-clockwise from above");
        }
        _ => panic!("unexpected shapes {shapes:?}"),
    }
    assert!(scene.geometry.objects.iter().all(|o| o.transform.is_none()));
}

#[test]
fn cones_take_their_radii_in_either_order() {
    let scene = parse(EVERY_ENTITY).unwrap();
    let bounds: Vec<_> = (1..3)
        .map(|i| scene.geometry.objects[i].shape.bounds().unwrap())
        .collect();
    // Widest at the base (0.2) in the first, at the apex (0.3) in the second.
    assert!((bounds[0].max.x - 0.2).abs() < 1e-5, "{:?}", bounds[0]);
    assert!((bounds[1].max.x - 1.3).abs() < 1e-5, "{:?}", bounds[1]);
}

#[test]
fn patches_become_smooth_triangles() {
    let scene = parse(EVERY_ENTITY).unwrap();
    assert_eq!(scene.geometry.meshes.len(), 1);
    let mesh = &scene.geometry.meshes[0];
    assert_eq!(mesh.faces, [[0, 1, 2]]);
    assert_eq!(mesh.normals, [Vec3::Z; 3]);
    assert_eq!(scene.geometry.triangle_count(), 1);
}

#[test]
fn patches_with_more_vertices_are_fanned_and_share_their_material_mesh() {
    let scene = parse(&with_head(
        "pp 4\n0 0 0 0 0 1\n1 0 0 0 0 1\n1 1 0 0 0 1\n0 1 0 0 0 1\npp 3\n0 0 1 0 0 1\n1 0 1 0 0 1\n0 1 1 0 0 1\n",
    ))
    .unwrap();
    assert_eq!(scene.geometry.meshes.len(), 1);
    assert_eq!(
        scene.geometry.meshes[0].faces,
        [[0, 1, 2], [0, 2, 3], [4, 5, 6]]
    );
}

#[test]
fn objects_before_any_fill_are_matte_white() {
    let scene = parse(&with_head("s 0 0 0 1\n")).unwrap();
    let material = &scene.materials[scene.geometry.objects[0].material as usize];
    assert_eq!(material.color, Vec3::ONE);
    assert_eq!((material.diffuse, material.reflectivity), (1.0, 0.0));
}

#[test]
fn a_file_without_a_background_has_a_black_one() {
    let scene = parse(&with_head("s 0 0 0 1\n")).unwrap();
    assert_eq!(scene.settings.background, Vec3::ZERO);
}

#[test]
fn negative_radii_mean_the_inside_and_are_shown_from_both_sides() {
    let scene = parse(&with_head("s 0 0 0 -2\nc 0 0 0 -1 0 0 1 -0.5\n")).unwrap();
    match &scene.geometry.objects[0].shape {
        Shape::Sphere(s) => assert_eq!(s.radius, 2.0),
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        scene.geometry.objects[1].shape,
        Shape::TaperedCylinder(_)
    ));
}

#[test]
fn numbers_are_read_as_c_writes_them() {
    let scene = parse(&with_head("s 1e-1 +2 -3.5E+0 .25\n")).unwrap();
    match &scene.geometry.objects[0].shape {
        Shape::Sphere(s) => {
            assert!(close(s.center, Vec3::new(0.1, 2.0, -3.5)));
            assert_eq!(s.radius, 0.25);
        }
        other => panic!("{other:?}"),
    }
}

// ---- SPD's own files -------------------------------------------------------------------------

#[test]
fn spd_files_load_with_the_primitives_their_generators_promise() {
    let balls = load_nff(&nff_dir().join("balls-2.nff"), NffLighting::Readme).unwrap();
    let spheres = balls
        .geometry
        .objects
        .iter()
        .filter(|o| matches!(o.shape, Shape::Sphere(_)))
        .count();
    assert_eq!((spheres, balls.geometry.objects.len()), (91, 92));
    assert_eq!(balls.lights.len(), 3);

    let tree = load_nff(&nff_dir().join("tree-6.nff"), NffLighting::Readme).unwrap();
    let cones = tree
        .geometry
        .objects
        .iter()
        .filter(|o| matches!(o.shape, Shape::TaperedCylinder(_)))
        .count();
    assert_eq!((cones, tree.geometry.objects.len()), (127, 255));
    assert_eq!(tree.lights.len(), 7);
}

#[test]
fn load_any_tells_nff_files_by_their_extension() {
    let path = nff_dir().join("balls-2.nff");
    let scene = load_any(path.to_str().unwrap()).unwrap();
    assert_eq!(scene.geometry.objects.len(), 92);
    // Upper-case extensions too; a file that is not NFF is read as TOML and fails as TOML.
    let dir = tempfile::tempdir().unwrap();
    let upper = dir.path().join("BALLS.NFF");
    std::fs::copy(&path, &upper).unwrap();
    assert!(load_any(upper.to_str().unwrap()).is_ok());
    let toml = dir.path().join("balls.toml");
    std::fs::copy(&path, &toml).unwrap();
    assert!(load_any(toml.to_str().unwrap()).is_err());
}

#[test]
fn load_any_passes_the_lighting_on() {
    let path = nff_dir().join("balls-2.nff");
    let readme = load_any_with(path.to_str().unwrap(), NffLighting::Readme).unwrap();
    let povray = load_any_with(path.to_str().unwrap(), NffLighting::Povray).unwrap();
    assert_ne!(readme.lights, povray.lights);
}

#[test]
fn a_missing_file_is_an_error_naming_it() {
    let error = load_nff(Path::new("no/such.nff"), NffLighting::Readme).unwrap_err();
    assert_eq!(error.file, Path::new("no/such.nff"));
    assert!(error.message.contains("cannot read"), "{error}");
}

// ---- errors ----------------------------------------------------------------------------------

#[test]
fn truncated_entities_are_errors_at_their_keyword() {
    let text = with_head("s 0 0 0 1\ns 0 0");
    assert_error(&text, 10, 1, "cut short");
    assert_error(
        &with_head("p 3\n0 0 0\n1 0 0\n"),
        9,
        1,
        "the file ends before a vertex",
    );
    assert_error("v\nfrom 0 0 0\nat", 1, 1, "cut short");
}

#[test]
fn bad_numbers_are_errors_at_the_number() {
    assert_error(
        &with_head("s 0 0 x 1\n"),
        9,
        7,
        "expected a number for the centre of `s`, found `x`",
    );
    assert_error(&with_head("s 0 0 1e999 1\n"), 9, 7, "found `1e999`");
    assert_error(
        &with_head("s 0 0 0 1e300\n"),
        9,
        9,
        "too large for single precision",
    );
    assert_error(&with_head("s 0 0 nan 1\n"), 9, 7, "found `nan`");
    // A keyword where a number belongs: the entity before it is cut short.
    assert_error(
        &with_head("c 0 0 0 1 0 0 1\ns 0 0 0 1\n"),
        10,
        1,
        "apex radius of `c`, found `s`",
    );
    assert_error(&with_head("p 3.0\n"), 9, 3, "whole number of vertices");
}

#[test]
fn polygons_need_three_vertices() {
    assert_error(
        &with_head("p 2\n0 0 0\n1 0 0\n"),
        9,
        3,
        "at least 3 vertices, got 2",
    );
    assert_error(&with_head("pp 0\n"), 9, 4, "at least 3 vertices, got 0");
}

#[test]
fn degenerate_shapes_are_errors_at_their_keyword() {
    assert_error(
        &with_head("s 0 0 0 1\nc 1 2 3 1 1 2 3 0.5\n"),
        10,
        1,
        "axis",
    );
    assert_error(&with_head("s 0 0 0 0\n"), 9, 1, "radius must be a positive");
    assert_error(&with_head("c 0 0 0 -1 0 0 1 1\n"), 9, 1, "same sign");
    assert_error(&with_head("p 3\n0 0 0\n1 1 1\n2 2 2\n"), 9, 1, "zero area");
    let bowtie = "p 4\n0 0 0\n1 1 0\n1 0 0\n0 1 0\n";
    let error = assert_error(&with_head(bowtie), 9, 1, "self-intersecting");
    assert!(!error.message.contains("collinear"), "{error}");
    let tiny = "p 3\n0 0 0\n1e-30 0 0\n0 1e-30 0\n";
    let error = assert_error(&with_head(tiny), 9, 1, "too small");
    assert!(!error.message.contains("collinear"), "{error}");
    assert_error(
        &with_head("p 4\n0 0 0\n1 0 0\n1 1 0\n0 1 1\n"),
        9,
        1,
        "one plane",
    );
}

#[test]
fn unknown_entities_list_the_known_ones() {
    let error = assert_error(
        &with_head("sphere 0 0 0 1\n"),
        9,
        1,
        "unknown entity `sphere`",
    );
    assert!(error.message.contains("`pp`"), "{error}");
}

#[test]
fn view_mistakes_point_at_the_value() {
    let view = |angle: &str, hither: &str, resolution: &str| {
        format!(
            "v\nfrom 0 -5 0\nat 0 0 0\nup 0 0 1\nangle {angle}\nhither {hither}\nresolution {resolution}\n"
        )
    };
    assert_error(&view("0", "1", "8 8"), 5, 7, "between 0 and 180");
    assert_error(&view("180", "1", "8 8"), 5, 7, "between 0 and 180");
    assert_error(
        &view("45", "-1", "8 8"),
        6,
        8,
        "hither distance must not be negative",
    );
    assert_error(
        &view("45", "1", "0 8"),
        7,
        12,
        "image width must be from 1 to 16384",
    );
    assert_error(&view("45", "1", "8 99999"), 7, 14, "image height");
    assert_error(&view("45", "1", "8 -8"), 7, 14, "whole number");
    assert_error(
        "v\nfrom 0 0 0\nlook 1 1 1\n",
        3,
        1,
        "expected `at` of `v`, found `look`",
    );
    assert_error(
        &format!("{}{}", view("45", "1", "8 8"), view("45", "1", "8 8")),
        8,
        1,
        "second view",
    );
}

#[test]
fn hither_0_means_no_clipping() {
    // SPD's `lattice` writes `hither 0`, BRL-CAD's exporter `hither 0.0`.
    for hither in ["0", "0.0"] {
        let text = format!(
            "v\nfrom 0 -5 0\nat 0 0 0\nup 0 0 1\nangle 45\nhither {hither}\nresolution 8 8\n\
             s 0 0 0 1\n"
        );
        let scene = parse(&text).unwrap_or_else(|e| panic!("hither {hither}: {e}"));
        let near = scene.camera.near;
        // Eye rays start at the near distance: now close to the eye, 5 away from the look-at point.
        assert!(near > 0.0 && near < 0.01, "hither {hither}: near {near}");
        let document = parse_nff_document(&text, Path::new("test.nff")).unwrap();
        assert!(document.to_nff_string().contains("\nhither 0\n"));
    }
}

#[test]
fn a_camera_that_cannot_be_built_is_an_error_at_the_view() {
    let text = "s 0 0 0 1\nv\nfrom 1 1 1\nat 1 1 1\nup 0 0 1\nangle 45\nhither 1\nresolution 8 8\n";
    assert_error(text, 2, 1, "coincide");
    let text = "v\nfrom 0 0 5\nat 0 0 0\nup 0 0 1\nangle 45\nhither 1\nresolution 8 8\n";
    assert_error(text, 1, 1, "parallel");
}

#[test]
fn a_file_without_a_view_is_an_error() {
    let error = assert_error("s 0 0 0 1\n", 1, 1, "no view");
    assert_eq!(error.source_line, None);
}

#[test]
fn material_mistakes_point_at_the_value() {
    assert_error(
        &with_head("f 1 1 1 -0.5 0 0 0 1\n"),
        9,
        9,
        "Kd must not be negative",
    );
    assert_error(
        &with_head("f 1 1 1 0.5 0 0 0.5 0\n"),
        9,
        21,
        "positive index of refraction",
    );
    assert_error(
        &with_head("f 1 1 1 0.5 0 0 0\ns 0 0 0 1\n"),
        10,
        1,
        "index of refraction of `f`",
    );
}

#[test]
fn a_light_colour_needs_three_numbers() {
    assert_error(
        &with_head("l 1 2 3 0.5 0.5\ns 0 0 0 1\n"),
        10,
        1,
        "the light colour of `l`",
    );
    assert_error(&with_head("l 1 2 3 -1 0 0\n"), 9, 9, "must not be negative");
}

#[test]
fn errors_read_like_compiler_messages() {
    let error = assert_error(&with_head("s 0 0 x 1\n"), 9, 7, "found `x`");
    assert_eq!(
        error.to_string(),
        "test.nff:9:7: expected a number for the centre of `s`, found `x`\n  |\n9 | s 0 0 x 1\n  |       ^"
    );
}

#[test]
fn comments_run_to_the_end_of_the_line_anywhere() {
    let scene = parse(&with_head(
        "# a sphere\ns 0 0 0 1 # the unit sphere\n#s 5 5 5 1\n",
    ))
    .unwrap();
    assert_eq!(scene.geometry.objects.len(), 1);
}

// ---- bytes that are not plain ASCII text --------------------------------------------------

/// Loads `bytes` as an NFF file.
fn load_bytes(bytes: &[u8]) -> Result<Scene, SceneError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bytes.nff");
    std::fs::write(&path, bytes).unwrap();
    load_nff(&path, NffLighting::Readme)
}

#[test]
fn latin1_comments_a_byte_order_mark_and_a_dos_end_of_file_are_read() {
    let text = with_head("s 0 0 0 1 # the unit sphere\n");
    let cases = [
        (
            "a Latin-1 comment",
            [b"# caf\xe9 cr\xe8me\n".as_slice(), text.as_bytes()].concat(),
        ),
        (
            "a byte-order mark",
            [b"\xef\xbb\xbf".as_slice(), text.as_bytes()].concat(),
        ),
        (
            "a DOS end-of-file mark",
            [text.as_bytes(), b"\x1a"].concat(),
        ),
    ];
    for (what, bytes) in cases {
        let scene = load_bytes(&bytes).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(scene.geometry.objects.len(), 1, "{what}");
    }
}

#[test]
fn a_byte_that_is_not_text_outside_a_comment_is_an_error_where_it_is() {
    let bytes = [with_head("").as_bytes(), b"# caf\xe9\ns 0 0 \xe9 1\n"].concat();
    let error = load_bytes(&bytes).unwrap_err();
    assert_eq!((error.line, error.column), (10, 7), "{error}");
    assert!(error.message.contains("expected a number"), "{error}");
}

// ---- robustness and speed --------------------------------------------------------------------

/// Characters that mean something to NFF, and a few that do not.
const ALPHABET: &[char] = &[
    'v', 'f', 'c', 's', 'p', 'l', 'b', '#', '\n', ' ', '\t', '-', '+', '.', 'e', '0', '1', '3',
    '9', 'x', 'é',
];

#[test]
fn mutated_files_never_panic() {
    let originals: Vec<String> = ["balls-2.nff", "tree-6.nff"]
        .iter()
        .map(|name| std::fs::read_to_string(nff_dir().join(name)).unwrap())
        .chain([EVERY_ENTITY.to_string()])
        .collect();
    let mut rng = Rng::with_seed(0x00FF_5EED_1987_0512);
    let (mut parsed, mut rejected) = (0, 0);
    for _ in 0..10_000 {
        let original = &originals[rng.usize(..originals.len())];
        let text = mutate(original, &mut rng, ALPHABET);
        let outcome = std::panic::catch_unwind(|| {
            parse_nff(&text, Path::new("fuzz.nff"), NffLighting::Readme).map(|_| ())
        });
        match outcome {
            Ok(Ok(())) => parsed += 1,
            Ok(Err(error)) => {
                assert!(error.line >= 1 && error.column >= 1, "{error}");
                rejected += 1;
            }
            Err(_) => panic!("parse_nff panicked on:\n{text}"),
        }
    }
    assert!(
        parsed > 1000 && rejected > 1000,
        "{parsed} parsed, {rejected} rejected"
    );
}

#[test]
fn the_document_survives_a_round_trip_through_text() {
    let text = std::fs::read_to_string(nff_dir().join("tree-6.nff")).unwrap();
    let document = parse_nff_document(&text, Path::new("tree-6.nff")).unwrap();
    assert_eq!(
        document.to_nff_string(),
        text,
        "SPD writes NFF as raylab does"
    );
}

#[test]
fn tens_of_thousands_of_primitives_parse_into_as_many_objects() {
    let document = Database::Rings.generate(12).unwrap();
    assert!(document.primitive_counts().total() > 39_000);
    let text = document.to_nff_string();
    let scene = parse_nff(&text, Path::new("rings-12.nff"), NffLighting::Readme).unwrap();
    assert_eq!(
        scene.geometry.objects.len(),
        document.primitive_counts().total()
    );
}
