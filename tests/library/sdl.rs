//! Hill & Kelley's SDL: every keyword raylab reads, the book's transform order, `def`/`use`,
//! `push`/`pop`, the lexer's quirks, and every error with its line, column and suggestion.

use std::path::Path;

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::formats::nff::NffLighting;
use raylab::formats::sdl::{MAX_EXPANDED_TOKENS, MAX_TRIANGLES, parse_sdl};
use raylab::formats::{SceneError, SceneFiles, SceneFormat, load_any, load_any_as};
use raylab::light::Light;
use raylab::ray::Ray;
use raylab::scene::Scene;
use raylab::shapes::Shape;
use raylab::whitted::Tracer;

/// A square of one face, as a `.3vn` file.
const SQUARE_3VN: &[u8] = b"4 1 1\n-1 -1 0  1 -1 0  1 1 0  -1 1 0\n0 0 1\n4\n0 1 2 3\n0 0 0 0\n";

fn read(text: &str) -> Result<Scene, SceneError> {
    let files = [("square.3vn", SQUARE_3VN)];
    parse_sdl(text, Path::new("t.dat"), SceneFiles::Builtin(&files))
}

fn scene(text: &str) -> Scene {
    read(text).unwrap_or_else(|e| panic!("{e}"))
}

fn error(text: &str) -> SceneError {
    match read(text) {
        Ok(_) => panic!("`{text}` reads"),
        Err(e) => e,
    }
}

/// Where object `i`'s transform takes the object-space point `p`.
fn placed(scene: &Scene, i: usize, p: Vec3) -> Vec3 {
    scene.geometry.objects[i]
        .transform
        .as_ref()
        .unwrap()
        .point_to_world(p)
}

fn close(a: Vec3, b: Vec3) -> bool {
    a.abs_diff_eq(b, 1e-5)
}

#[test]
fn scene_settings_and_lights() {
    let s = scene(
        "light 1 2 3 .5 .6 .7\nlight 0 9 0 1 1 1\nglobalAmbient .2 .3 .4\nbackground 1 0 0\n\
         minReflectivity .3 minTransparency .4 maxRecursionDepth 6",
    );
    assert_eq!(
        s.lights[0],
        Light::Point {
            position: Vec3::new(1.0, 2.0, 3.0),
            color: Vec3::new(0.5, 0.6, 0.7)
        }
    );
    assert_eq!(s.lights.len(), 2);
    assert_eq!(s.settings.ambient, Vec3::new(0.2, 0.3, 0.4));
    assert_eq!(s.settings.background, Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(s.settings.max_depth, 6);
    assert_eq!(s.settings.min_weight, 0.3);
}

#[test]
fn the_books_defaults() {
    let s = scene("sphere");
    assert_eq!(s.settings.background, Vec3::new(0.0, 0.0, 0.6));
    assert_eq!(s.settings.ambient, Vec3::splat(0.1));
    assert_eq!(s.settings.max_depth, 3);
    assert_eq!(s.settings.min_weight, 0.5);
    let m = &s.materials[0];
    assert_eq!(m.color, Vec3::splat(0.8));
    assert_eq!((m.specular, m.shininess, m.ior), (0.0, 1.0, 1.0));
}

#[test]
fn every_material_keyword() {
    let s = scene(
        "ambient .2 .2 .2 diffuse .4 .2 .0 specular .5 .25 0 emissive .3 .2 .1 specularExponent 30\n\
         reflectivity .3 transparency .6 speedOfLight .5 specularFraction .1 surfaceRoughness 2\n\
         sphere defaultMaterials cube",
    );
    let m = &s.materials[0];
    assert_eq!(m.color, Vec3::new(0.4, 0.2, 0.0));
    assert_eq!(m.emission, Vec3::new(0.3, 0.2, 0.1));
    assert!(
        (m.ambient - 1.0).abs() < 1e-6,
        "ambient mean .2 over diffuse mean .2"
    );
    assert_eq!(
        (m.specular, m.specular_color),
        (0.5, Vec3::new(1.0, 0.5, 0.0))
    );
    assert_eq!(
        (m.shininess, m.reflectivity, m.transparency),
        (30.0, 0.3, 0.6)
    );
    assert_eq!(m.ior, 2.0, "speedOfLight .5 is an index of refraction of 2");
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    assert_eq!(s.materials.len(), 2);
    assert_eq!(
        s.materials[1].color,
        Vec3::splat(0.8),
        "defaultMaterials resets"
    );
    assert_eq!(s.geometry.objects[1].material, 1);
}

#[test]
fn shapes_sharing_a_material_share_its_index() {
    let s = scene("diffuse 1 0 0 sphere cube diffuse 0 1 0 sphere");
    let materials: Vec<u32> = s.geometry.objects.iter().map(|o| o.material).collect();
    assert_eq!(materials, [0, 0, 1]);
}

#[test]
fn every_shape() {
    let s = scene(
        "sphere cube cylinder cone taperedCylinder .3 square plane\n\
         teapot mesh square.3vn tetrahedron octahedron dodecahedron icosahedron buckyball diamond",
    );
    let kinds: Vec<&str> = s.geometry.objects.iter().map(|o| o.shape.name()).collect();
    assert_eq!(
        kinds,
        [
            "sphere",
            "cuboid",
            "tapered cylinder",
            "tapered cylinder",
            "tapered cylinder",
            "polygon",
            "plane"
        ]
    );
    // The teapot, the mesh file and six polyhedra.
    assert_eq!(s.geometry.meshes.len(), 8);
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    // The cone's apex is at (0, 0, 1), the tapered cylinder's top radius 0.3.
    let Shape::TaperedCylinder(cone) = &s.geometry.objects[3].shape else {
        unreachable!()
    };
    let bounds = cone.bounds();
    assert!(
        close(bounds.min, Vec3::new(-1.0, -1.0, 0.0))
            && close(bounds.max, Vec3::new(1.0, 1.0, 1.0))
    );
    assert!(s.geometry.objects[3].shape.is_closed());
}

#[test]
fn the_transform_written_last_applies_first() {
    // `translate … scale … cube` scales first, then moves.
    let s =
        scene("translate 1 0 0 scale 2 2 2 cube\nidentityAffine scale 2 2 2 translate 1 0 0 cube");
    assert!(close(placed(&s, 0, Vec3::X), Vec3::new(3.0, 0.0, 0.0)));
    assert!(close(placed(&s, 1, Vec3::X), Vec3::new(4.0, 0.0, 0.0)));
}

#[test]
fn rotations_are_right_handed_about_any_axis() {
    let s = scene("rotate 90 0 0 1 sphere identityAffine rotate 180 0 180 180 sphere");
    assert!(close(placed(&s, 0, Vec3::X), Vec3::Y));
    // The axis is normalised: a half turn about (0, 1, 1) takes y to z.
    assert!(close(placed(&s, 1, Vec3::Y), Vec3::Z));
}

#[test]
fn push_and_pop_keep_transforms_but_not_materials() {
    let s = scene("push translate 5 0 0 diffuse 1 0 0 sphere pop sphere");
    assert!(close(placed(&s, 0, Vec3::ZERO), Vec3::new(5.0, 0.0, 0.0)));
    assert!(close(placed(&s, 1, Vec3::ZERO), Vec3::ZERO));
    assert_eq!(
        s.geometry.objects[1].material,
        s.geometry.objects[0].material
    );
    assert_eq!(s.materials[0].color, Vec3::X);
    assert!(s.warnings.is_empty());
}

#[test]
fn unbalanced_push_and_pop_are_warnings_given_once() {
    let s = scene("translate 1 0 0 pop pop sphere\npush push sphere");
    assert!(
        close(placed(&s, 0, Vec3::ZERO), Vec3::ZERO),
        "popping the last resets"
    );
    assert_eq!(s.warnings.len(), 2, "{:?}", s.warnings);
    assert!(
        s.warnings[0].starts_with("t.dat:1: `pop` with nothing pushed"),
        "{:?}",
        s.warnings
    );
    assert!(
        s.warnings[1].contains("2 `push` never popped"),
        "{:?}",
        s.warnings
    );
}

#[test]
fn identity_affine_resets_the_top_only() {
    let s = scene("translate 1 0 0 push translate 0 1 0 identityAffine sphere pop sphere");
    assert!(close(placed(&s, 0, Vec3::ZERO), Vec3::ZERO));
    assert!(close(placed(&s, 1, Vec3::ZERO), Vec3::X));
}

#[test]
fn def_and_use_expand_in_place() {
    let s = scene(
        "def red {diffuse 1 0 0}\ndef ball { push translate 0 2 0 sphere pop }\n\
         push translate 1 0 0 use red use ball pop use ball",
    );
    assert_eq!(s.geometry.objects.len(), 2);
    assert!(close(placed(&s, 0, Vec3::ZERO), Vec3::new(1.0, 2.0, 0.0)));
    assert!(close(placed(&s, 1, Vec3::ZERO), Vec3::new(0.0, 2.0, 0.0)));
    // The material-only macro stays in force after the `pop`.
    assert_eq!(s.materials[0].color, Vec3::X);
    assert_eq!(s.geometry.objects[1].material, 0);
}

#[test]
fn a_def_may_use_a_def_made_later() {
    let s = scene("def a { use b use b } def b { sphere } use a");
    assert_eq!(s.geometry.objects.len(), 2);
}

#[test]
fn lexer_quirks() {
    // Braces glued to words and `}def`; a `!` comment anywhere, even inside a word, which
    // glues the next line's start onto it.
    let s = scene("def a{sphere}def b{cube!note\n} use a use b ! a comment\nsph!half\nere");
    let kinds: Vec<&str> = s.geometry.objects.iter().map(|o| o.shape.name()).collect();
    assert_eq!(kinds, ["sphere", "cuboid", "sphere"]);
}

#[test]
fn numbers_as_cpp_reads_them() {
    let s = scene("translate .5 -3 +2 scale 1e-1 1E1 1 sphere");
    assert!(close(placed(&s, 0, Vec3::ONE), Vec3::new(0.6, 7.0, 3.0)));
    for (text, column) in [
        ("translate 1,2 3 4 sphere", 11),
        ("scale 3f 1 1", 7),
        ("scale 1 inf 1", 9),
    ] {
        let e = error(text);
        assert_eq!((e.line, e.column), (1, column), "{text}: {e}");
        assert!(e.message.starts_with("expected "), "{e}");
    }
    let e = error("sphere\nlight 1 2");
    assert_eq!((e.line, e.column), (2, 1));
    assert!(e.message.contains("but the file ends"), "{e}");
}

#[test]
fn unknown_keywords_suggest_the_nearest() {
    let e = error("sphere\n  specularExponnent 50");
    assert_eq!((e.line, e.column), (2, 3));
    assert_eq!(
        e.message,
        "unknown keyword `specularExponnent`, did you mean `specularExponent`?"
    );
    let e = error("shpere");
    assert!(e.message.ends_with("did you mean `sphere`?"), "{e}");
    let e = error("frobnicate");
    assert_eq!(e.message, "unknown keyword `frobnicate`");
    let e = error("sphere }");
    assert_eq!((e.line, e.column), (1, 8));
    assert!(e.message.contains("unexpected `}`"), "{e}");
}

#[test]
fn def_errors() {
    let e = error("def red diffuse 1 0 0");
    assert_eq!((e.line, e.column), (1, 9));
    assert!(e.message.contains("expected `{` after `def red`"), "{e}");
    let e = error("def 2x { }");
    assert_eq!((e.line, e.column), (1, 5));
    let e = error("def a { }\ndef a { }");
    assert_eq!((e.line, e.column), (2, 5));
    assert!(
        e.message.contains("already defined (at line 1, column 5)"),
        "{e}"
    );
    let e = error("def a { sphere");
    assert!(e.message.contains("no closing `}`"), "{e}");
    let e = error("def green { }\nuse gren");
    assert_eq!((e.line, e.column), (2, 5));
    assert!(e.message.contains("`gren` is not defined"), "{e}");
    assert!(e.message.ends_with("did you mean `green`?"), "{e}");
}

#[test]
fn an_error_inside_a_use_names_its_def() {
    let e = error("def leg {\n  scale 1 x 1 cube }\ndef table { use leg }\n\nuse table");
    assert_eq!(
        (e.line, e.column),
        (2, 11),
        "at the bad word in the def: {e}"
    );
    assert_eq!(
        e.message,
        "expected a factor along x, y and z after `scale`, found `x` \
         (in def `leg`, used at line 3, column 17, in def `table`, used at line 5, column 5)"
    );
}

#[test]
fn a_def_that_uses_itself_is_an_error_not_a_hang() {
    let e = error("def a { sphere use a }\nuse a");
    assert_eq!((e.line, e.column), (1, 20));
    assert!(e.message.starts_with("`a` uses itself (a → a)"), "{e}");
    let e = error("def a { use b }\ndef b { use a }\nuse a");
    assert!(e.message.starts_with("`a` uses itself (a → b → a)"), "{e}");
}

#[test]
fn expansion_is_bounded() {
    let mut text = String::from("def d0 { sphere }\n");
    for i in 1..30 {
        text += &format!("def d{i} {{ use d{j} use d{j} }}\n", j = i - 1);
    }
    text += "use d29";
    let e = error(&text);
    assert!(
        e.message
            .contains(&format!("more than {MAX_EXPANDED_TOKENS} tokens")),
        "{e}"
    );
}

#[test]
fn meshes_from_files_and_missing_ones() {
    let s = scene("translate 0 0 2 mesh square.3vn mesh gone.3vn mesh gone.3vn");
    assert_eq!(s.geometry.meshes.len(), 1);
    let mesh = &s.geometry.meshes[0];
    assert_eq!(mesh.faces.len(), 2);
    assert!(
        mesh.positions.iter().all(|p| p.z == 2.0),
        "placed by the transform"
    );
    assert_eq!(
        s.warnings.len(),
        1,
        "one warning per missing file: {:?}",
        s.warnings
    );
    assert!(
        s.warnings[0].starts_with("t.dat:1: cannot read mesh file gone.3vn"),
        "{:?}",
        s.warnings
    );
    let e = error("mesh\n");
    assert!(e.message.contains("`mesh` needs a .3vn file name"), "{e}");
}

#[test]
fn the_torus_rings_the_z_axis_as_the_books_glut_torus_does() {
    // Ring radius 1 around z in the plane z = 0, tube radius 0.2; then moved up by 1.
    let s = scene("translate 0 0 1 torus");
    assert!(matches!(s.geometry.objects[0].shape, Shape::Torus(_)));
    let bvh = Bvh::build(&s.geometry);
    let tracer = Tracer::new(&s, &bvh);
    let down = |x: f32, y: f32| Ray::new(Vec3::new(x, y, 5.0), -Vec3::Z);
    // Straight down onto the top of the tube, at z = 1 + 0.2, wherever around the ring.
    for (x, y) in [(1.0, 0.0), (0.0, -1.0), (0.6, 0.8)] {
        let hit = tracer
            .closest_hit(&down(x, y), 0.0)
            .expect("the tube is below");
        assert!((hit.t - 3.8).abs() < 1e-4, "({x}, {y}): t = {}", hit.t);
    }
    // Down the hole, and outside the ring: nothing.
    assert!(tracer.closest_hit(&down(0.0, 0.0), 0.0).is_none());
    assert!(tracer.closest_hit(&down(1.3, 0.0), 0.0).is_none());
}

#[test]
fn booleans_cut_their_two_operands() {
    // The cube −1…1 and, scaled after it (the book's transforms are not scoped), a sphere of
    // radius 1.3 around it: down the z axis the union shows the sphere's top, the
    // intersection the cube's, and the difference nothing (the sphere holds that whole line).
    let first_hit = |operation: &str, origin: Vec3, dir: Vec3| {
        let s = scene(&format!(
            "diffuse 1 0 0 {operation} cube diffuse 0 0 1 scale 1.3 1.3 1.3 sphere"
        ));
        assert_eq!(s.geometry.objects.len(), 1, "{operation}: one object");
        let bvh = Bvh::build(&s.geometry);
        let hit = Tracer::new(&s, &bvh).closest_hit(&Ray::new(origin, dir), 0.0);
        hit.map(|hit| (hit.t, s.materials[s.geometry.material(&hit) as usize].color))
    };
    let (red, blue) = (Vec3::X, Vec3::Z);
    let down = (Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
    let (t, color) = first_hit("union", down.0, down.1).unwrap();
    assert!(
        (t - 3.7).abs() < 1e-5 && color == blue,
        "union: {t} {color}"
    );
    let (t, color) = first_hit("intersection", down.0, down.1).unwrap();
    assert!(
        (t - 4.0).abs() < 1e-5 && color == red,
        "intersection: {t} {color}"
    );
    assert_eq!(first_hit("difference", down.0, down.1), None);
    // Towards a corner of the cube, which sticks out of the sphere: the difference keeps it.
    let corner = (Vec3::new(5.0, 4.9, 4.8), Vec3::new(-1.0, -1.0, -1.0));
    let (t, color) = first_hit("difference", corner.0, corner.1).unwrap();
    assert!(
        (t - 4.0).abs() < 1e-5 && color == red,
        "difference: {t} {color}"
    );
}

#[test]
fn boolean_errors_are_at_their_operand() {
    // The operands are read first: an error in one is reported where it is.
    let e = error("intersection sphere shpere");
    assert_eq!((e.line, e.column), (1, 21));
    let e = error("difference sphere");
    assert!(e.message.contains("ends before its second"), "{e}");
    // Meshes cannot be cut, and open surfaces have no inside.
    let e = error("light 0 0 0 1 1 1\nunion sphere translate 1 0 0 teapot");
    assert_eq!((e.line, e.column), (2, 30));
    assert!(e.message.contains("`teapot` is a mesh"), "{e}");
    let e = error("union sphere square");
    assert_eq!((e.line, e.column), (1, 1));
    assert!(e.message.contains("open"), "{e}");
    // A nested boolean is one operand.
    let s = scene("union sphere translate 3 0 0 difference cube sphere");
    assert_eq!(s.geometry.objects.len(), 1);
}

#[test]
fn bad_values_are_errors_at_their_statement() {
    for (text, wanted) in [
        ("speedOfLight 0", "`speedOfLight` must be positive"),
        ("maxRecursionDepth 0", "max_depth must be between"),
        (
            "minReflectivity 2",
            "`minReflectivity` must be between 0 and 1",
        ),
        (
            "scale 0 1 1 sphere",
            "scale factors must be finite and non-zero",
        ),
        ("rotate 30 0 0 0", "rotation axis must not be zero"),
        ("scale 1e16 1 1 sphere", "the sphere"),
        (
            "scale 1e30 1e30 1e30 sphere",
            "cannot be undone in single precision",
        ),
        ("taperedCylinder -1", "radii must not be negative"),
        ("light 1e20 0 0 1 1 1", "the position"),
        ("parameters 11", "`parameters` takes 0 to 10 numbers"),
    ] {
        let e = error(text);
        assert!(e.message.contains(wanted), "{text}: {e}");
        assert_eq!(e.line, 1);
    }
}

/// A BMP image `width` pixels wide and `height` high, its left half red and its right half
/// green.
fn red_green_bmp(width: u32, height: u32) -> Vec<u8> {
    let image = image::RgbImage::from_fn(width, height, |x, _| {
        if x < width / 2 {
            image::Rgb([255, 0, 0])
        } else {
            image::Rgb([0, 255, 0])
        }
    });
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Bmp,
        )
        .unwrap();
    bytes
}

/// [`read`], with the images `wide.bmp` (8 × 1) and `backdrop.bmp` (4 × 2) beside the scene,
/// each red on its left half and green on its right.
fn with_images(text: &str) -> Result<Scene, SceneError> {
    let (wide, backdrop) = (red_green_bmp(8, 1), red_green_bmp(4, 2));
    let files = [("wide.bmp", &wide[..]), ("backdrop.bmp", &backdrop[..])];
    parse_sdl(text, Path::new("t.dat"), SceneFiles::Builtin(&files))
}

/// The colour of the surface `ray` hits first, before lighting: its texture's or its own.
fn surface_color(s: &Scene, origin: Vec3, dir: Vec3) -> Vec3 {
    let bvh = Bvh::build(&s.geometry);
    let tracer = Tracer::new(s, &bvh);
    let ray = Ray::new(origin, dir);
    let hit = tracer.closest_hit(&ray, 0.0).expect("the ray hits");
    let surface = s.geometry.surface(&ray, &hit);
    tracer.base_color(&s.materials[surface.material as usize], &surface)
}

#[test]
fn the_checkerboard_shades_the_diffuse_colour_in_half_unit_cubes_of_object_space() {
    // A cube scaled by 2: its top face is object y = 1, world y = 2. Object cells (0, 2, 0) and
    // (1, 2, 0) lie under world x = 0.5 and x = 1.5.
    let s = scene("diffuse 1 .5 0 texture -1 scale 2 2 2 cube");
    let down = |x: f32| surface_color(&s, Vec3::new(x, 5.0, 0.5), -Vec3::Y);
    assert!(close(down(0.5), Vec3::new(0.2, 0.1, 0.0)), "{}", down(0.5));
    assert!(close(down(1.5), Vec3::new(0.8, 0.4, 0.0)), "{}", down(1.5));
}

#[test]
fn wood_rings_the_z_axis_in_the_books_two_colours() {
    // On the square (z = 0) along the x axis the rings do not wobble: the first ring is
    // light, the second dark, whatever the diffuse colour.
    let s = scene("diffuse 0 0 1 texture -2 square");
    let down = |x: f32| surface_color(&s, Vec3::new(x, 0.0, 5.0), -Vec3::Z);
    assert!(
        close(down(0.06), Vec3::new(0.6, 0.5, 0.2)),
        "{}",
        down(0.06)
    );
    assert!(
        close(down(0.18), Vec3::new(1.0, 0.62, 0.26)),
        "{}",
        down(0.18)
    );
}

#[test]
fn marble_shades_the_diffuse_colour_between_vein_and_stone() {
    let s = scene("diffuse 1 .5 .25 texture -3 square");
    let mut shades = Vec::new();
    for k in 0..40 {
        let (x, y) = (-0.95 + k as f32 * 0.047, 0.3);
        let c = surface_color(&s, Vec3::new(x, y, 5.0), -Vec3::Z);
        assert!(close(c, Vec3::new(1.0, 0.5, 0.25) * c.x), "{c}");
        assert!((0.149..=0.951).contains(&c.x), "{c}");
        shades.push(c.x);
    }
    let spread =
        shades.iter().cloned().fold(0.0, f32::max) - shades.iter().cloned().fold(1.0, f32::min);
    assert!(spread > 0.2, "the marble barely varies: {shades:?}");
}

#[test]
fn a_pixmap_lies_on_a_square_as_its_parameters_say() {
    // The image spans x from −1 to 3 (p0, p3) and y from −1 to 1 (p1, p2): the square (x up
    // to 1) shows only its red left half. Without parameters it shows the whole image.
    let at = |text: &str, x: f32| {
        let s = with_images(text).unwrap();
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
        surface_color(&s, Vec3::new(x, 0.0, 5.0), -Vec3::Z)
    };
    let mapped = "makePixmap 1 wide.bmp texture 1 parameters 4 -1 -1 1 3 square";
    assert_eq!(at(mapped, 0.6), Vec3::X);
    assert_eq!(at(mapped, -0.6), Vec3::X);
    let whole = "makePixmap 1 wide.bmp texture 1 square";
    assert_eq!(at(whole, 0.6), Vec3::Y);
    assert_eq!(at(whole, -0.6), Vec3::X);
    // The other version of the book's code writes a third number, the OpenGL texture's name.
    let three = "makePixmap 1 wide.bmp 7 texture 1 square";
    assert_eq!(at(three, 0.6), Vec3::Y);
}

#[test]
fn texture_problems_are_errors_or_warnings_at_their_line() {
    let e = with_images("sphere\nmakePixmap 16 wide.bmp").err().unwrap();
    assert_eq!((e.line, e.column), (2, 1));
    assert!(e.message.contains("numbered 0 to 15"), "{e}");
    let e = with_images("makePixmap 1").err().unwrap();
    assert!(e.message.contains("needs an image file name"), "{e}");
    let e = with_images("makePixmap 1 wide.bmp texture 1 parameters 4 2 0 1 2 square").err();
    let e = e.unwrap();
    assert!(e.message.contains("empty range 2 to 2"), "{e}");
    // What real files get away with: a missing image, a pixmap never made, an unknown texture.
    let s = with_images(
        "makePixmap 2 gone.bmp\nmakePixmap 3 gone.bmp texture 2 sphere\ntexture 5 cube\n\
         texture -9 cube backgroundImage gone.bmp",
    )
    .unwrap();
    assert_eq!(s.geometry.objects.len(), 3);
    let warnings = s.warnings.join("\n");
    assert_eq!(s.warnings.len(), 3, "{warnings}");
    assert!(
        warnings.contains("t.dat:1: cannot read pixmap file gone.bmp"),
        "{warnings}"
    );
    assert!(
        warnings.contains("t.dat:2: a shape's texture names a pixmap"),
        "{warnings}"
    );
    assert!(
        warnings.contains("t.dat:4: a texture number other than"),
        "{warnings}"
    );
    assert!(s.textures.is_empty());
}

#[test]
fn rays_that_miss_see_the_background_image_standing_on_the_image_plane() {
    // The 4 × 2 image stands on the image plane, as tall as the view and twice as wide as
    // high: a direction a quarter of the way across it sees its red half, three quarters
    // across its green half, and beyond its edge the background colour.
    let s = with_images("background .1 .2 .3 backgroundImage backdrop.bmp").unwrap();
    let bvh = Bvh::build(&s.geometry);
    let tracer = Tracer::new(&s, &bvh);
    let c = &s.camera;
    let across = |x: f32, y: f32| {
        let dir = -c.near * c.n + x * 2.0 * c.half_height * c.u + y * c.half_height * c.v;
        let mut counts = Default::default();
        tracer.trace_eye(&Ray::new(c.eye, dir), &mut counts)
    };
    assert_eq!(across(-0.5, 0.5), Vec3::X);
    assert_eq!(across(0.5, -0.5), Vec3::Y);
    assert_eq!(across(1.2, 0.0), Vec3::new(0.1, 0.2, 0.3));
    assert_eq!(across(0.0, -1.1), Vec3::new(0.1, 0.2, 0.3));
}

#[test]
fn a_tapered_tube_is_a_wall_around_a_hole() {
    // Radius 1 at z = 0 to 1.2 at z = 1, the wall 0.25 thick: a hole of radius 0.75 to 0.95.
    let s = scene("taperedTube 1.2 .25");
    assert_eq!(s.geometry.objects.len(), 1);
    let bvh = Bvh::build(&s.geometry);
    let tracer = Tracer::new(&s, &bvh);
    let first = |origin: Vec3, dir: Vec3| {
        let ray = Ray::new(origin, dir);
        let hit = tracer.closest_hit(&ray, 0.0)?;
        Some((hit.t, s.geometry.surface(&ray, &hit).normal))
    };
    // Up the axis, through the hole.
    assert_eq!(first(Vec3::new(0.0, 0.0, -5.0), Vec3::Z), None);
    // Up into the base's ring, from below.
    let (t, normal) = first(Vec3::new(0.875, 0.0, -5.0), Vec3::Z).unwrap();
    assert!(
        (t - 5.0).abs() < 1e-4 && close(normal, -Vec3::Z),
        "{t} {normal}"
    );
    // Down onto the top's ring, between radius 0.95 and 1.2.
    let (t, normal) = first(Vec3::new(0.0, 1.1, 5.0), -Vec3::Z).unwrap();
    assert!(
        (t - 4.0).abs() < 1e-4 && close(normal, Vec3::Z),
        "{t} {normal}"
    );
    // From inside the hole at half height, out through the inner wall (radius 0.85 there),
    // whose normal faces the hole.
    let (t, normal) = first(Vec3::new(0.0, 0.0, 0.5), Vec3::X).unwrap();
    assert!((t - 0.85).abs() < 1e-4 && normal.x < -0.9, "{t} {normal}");
    let e = error("light 0 0 0 1 1 1\ntaperedTube .5 1");
    assert_eq!((e.line, e.column), (2, 1));
    assert!(e.message.contains("wall must be thicker than 0"), "{e}");
}

#[test]
fn load_any_reads_dat_and_sdl_files_and_their_meshes() {
    let folder = tempfile::tempdir().unwrap();
    std::fs::write(folder.path().join("square.3vn"), SQUARE_3VN).unwrap();
    for name in ["scene.dat", "scene.SDL"] {
        let path = folder.path().join(name);
        std::fs::write(&path, "light 0 5 5 1 1 1 sphere mesh square.3vn").unwrap();
        let s = load_any(path.to_str().unwrap()).unwrap();
        assert_eq!(
            (s.geometry.objects.len(), s.geometry.meshes.len()),
            (1, 1),
            "{name}"
        );
    }
    let path = folder.path().join("bad.dat");
    std::fs::write(&path, "\n\nexponentt 3").unwrap();
    let message = load_any(path.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        message.contains("bad.dat:3:1: unknown keyword `exponentt`"),
        "{message}"
    );
}

#[test]
fn a_few_uses_cannot_ask_for_billions_of_triangles() {
    // 2^12 teapots of about 4000 triangles each: more than the limit, refused there.
    let mut text = String::from("def t0 { teapot }\n");
    for i in 1..=12 {
        text += &format!("def t{i} {{ use t{j} use t{j} }}\n", j = i - 1);
    }
    text += "use t12";
    let e = error(&text);
    assert!(
        e.message
            .contains(&format!("more than {MAX_TRIANGLES} triangles")),
        "{e}"
    );
    assert!(e.message.contains("in def `t0`"), "{e}");
}

#[test]
fn format_sdl_reads_a_file_whatever_its_name() {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("scene.txt");
    std::fs::write(&path, "light 0 5 5 1 1 1 sphere mesh gone.3vn").unwrap();
    let name = path.to_str().unwrap();
    let s = load_any_as(name, NffLighting::default(), Some(SceneFormat::Sdl)).unwrap();
    assert_eq!(s.geometry.objects.len(), 1);
    assert!(load_any(name).is_err(), "read as TOML by its name");

    let out = folder.path().join("out.png");
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args(args)
            .output()
            .unwrap()
    };
    let rendered = run(&[
        "render",
        name,
        "--format",
        "sdl",
        "--size",
        "8",
        "-o",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&rendered.stderr);
    assert!(rendered.status.success(), "{stderr}");
    assert!(out.exists());
    assert!(
        stderr.contains("warning: ") && stderr.contains(":1: cannot read mesh file"),
        "{stderr}"
    );
    let inspected = run(&[
        "inspect", name, "--format", "sdl", "--pixel", "4,4", "--size", "8",
    ]);
    assert!(
        inspected.status.success(),
        "{}",
        String::from_utf8_lossy(&inspected.stderr)
    );
    let refused = run(&["render", name, "--format", "stl"]);
    assert!(!refused.status.success());
    assert!(
        String::from_utf8_lossy(&refused.stderr)
            .contains("expected toml, nff, sdl, obj, ply or gltf")
    );
}

#[test]
fn load_any_frames_an_sdl_scene_which_has_no_camera() {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("far.sdl");
    std::fs::write(&path, "translate 100 0 0 sphere").unwrap();
    let placeholder = read("translate 100 0 0 sphere").unwrap().camera.spec;
    assert_eq!(placeholder, raylab::camera::CameraSpec::default());
    let framed = load_any(path.to_str().unwrap()).unwrap().camera.spec;
    assert_eq!(
        framed.look_at.round(),
        Vec3::new(100.0, 0.0, 0.0),
        "{framed:?}"
    );
    assert!(framed.eye.distance(framed.look_at) > 1.0);
}

#[test]
fn the_books_exponent_is_read_as_specular_exponent_with_one_warning() {
    // As the book's own bookScene.dat writes it.
    let s = scene("specular .5 .5 .5 exponent 50 sphere exponent 20 cube");
    assert_eq!(s.materials[0].shininess, 50.0);
    assert_eq!(s.materials[1].shininess, 20.0);
    assert_eq!(s.warnings.len(), 1, "{:?}", s.warnings);
    assert!(
        s.warnings[0].starts_with("t.dat:1: `exponent` is read as `specularExponent`"),
        "{:?}",
        s.warnings
    );
}
