//! Input that could hang, exhaust or silently fool raylab: arrays of the wrong length, numbers
//! that overflow single precision, ray trees that grow without bound. Each is refused with a
//! message that says why, or bounded, and what lies within the limits still works.

use std::path::Path;
use std::process::{Command, Output};

use raylab::bvh::Bvh;
use raylab::formats::SceneError;
use raylab::formats::toml::parse_scene;
use raylab::inspect::trace_ray_tree;
use raylab::light::Light;
use raylab::progressive::render_image;
use raylab::scene::Scene;
use raylab::whitted::{RAY_BUDGET, StopReason, Tracer};

fn parse(text: &str) -> Result<Scene, SceneError> {
    parse_scene(text, Path::new("test.toml"), Path::new("."))
}

/// Parses `text`, which must fail at `line:column` with a message containing `part`.
fn assert_error(text: &str, line: usize, column: usize, part: &str) {
    let error = match parse(text) {
        Ok(_) => panic!("expected an error for:\n{text}"),
        Err(error) => error,
    };
    assert_eq!((error.line, error.column), (line, column), "{error}");
    assert!(
        error.message.contains(part),
        "expected {part:?} in:\n{error}"
    );
}

// ---- arrays: too long is the same error as too short ------------------------------------------

#[test]
fn arrays_that_are_too_long_are_errors_not_truncated() {
    let sphere = "[[objects]]\ntype = \"sphere\"\n";
    assert_error(
        &format!("{sphere}center = [0, 0, 0, 99]\n"),
        3,
        10,
        "expected 3 values, got 4",
    );
    assert_error(
        "[render]\nbackground = [1, 0, 0, 5]\n",
        2,
        14,
        "expected 3 values, got 4",
    );
    assert_error(
        "[[objects]]\ntype = \"mesh\"\npositions = [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]\n\
         faces = [[0, 1, 2, 3]]\n",
        4,
        10,
        "expected 3 values, got 4",
    );
    assert_error(
        "[[objects]]\ntype = \"triangle\"\n\
         vertices = [[0,0,0], [1,0,0], [0,1,0], [1,1,0]]\n",
        3,
        12,
        "expected 3 values, got 4",
    );
    assert_error(
        "[[objects]]\ntype = \"triangle\"\nvertices = [[0,0,0], [1,0,0], [0,1,0]]\n\
         uvs = [[0, 0, 0], [1, 0], [0, 1]]\n",
        4,
        8,
        "expected 2 values, got 3",
    );
    assert_error(
        "[textures.t]\ntype = \"image\"\nfile = \"x.png\"\nscale = [1, 2, 3]\n",
        4,
        9,
        "expected 2 values, got 3",
    );
}

#[test]
fn arrays_that_are_too_short_say_the_same() {
    assert_error(
        "[render]\nbackground = [1, 0]\n",
        2,
        14,
        "expected 3 values, got 2",
    );
    assert_error(
        "[[objects]]\ntype = \"mesh\"\npositions = [[0,0,0],[1,0,0],[1,1,0]]\nfaces = [[0, 1]]\n",
        4,
        10,
        "expected 3 values, got 2",
    );
}

// ---- numbers that overflow single precision -----------------------------------------------------

#[test]
fn coordinates_past_single_precision_are_errors_that_say_so() {
    assert_error(
        "[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -6e19]\nradius = 2e19\n",
        3,
        10,
        "single precision",
    );
    assert_error(
        "[[objects]]\ntype = \"sphere\"\nradius = 3e38\n",
        3,
        10,
        "the sphere reaches",
    );
    assert_error(
        "[[objects]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n\
         transform = [{ translate = [3e38, 0, 0] }, { translate = [3e38, 0, 0] }]\n",
        5,
        28,
        "single precision",
    );
    assert_error(
        "[[objects]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n\
         transform = [{ scale = [1e30, 1, 1] }, { scale = [1e30, 1, 1] }]\n",
        5,
        13,
        "largest single-precision number",
    );
    assert_error(
        "[[objects]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n\
         transform = [{ translate = [9e14, 0, 0] }, { translate = [9e14, 0, 0] }]\n",
        1,
        1,
        "the cuboid reaches",
    );
    assert_error(
        "[[objects]]\ntype = \"mesh\"\npositions = [[0,0,0],[1,0,0],[0,1,0]]\nfaces = [[0,1,2]]\n\
         transform = [{ scale = [1e16, 1e16, 1e16] }]\n",
        1,
        1,
        "a vertex reaches",
    );
}

#[test]
fn camera_numbers_past_single_precision_are_errors_that_say_so() {
    assert_error(
        "[camera]\neye = [3e38, 0, 0]\nlook_at = [-3e38, 0, 0]\n",
        2,
        7,
        "single precision",
    );
    assert_error(
        "[camera]\nnear = 1e-38\n",
        2,
        8,
        "near distance must be from",
    );
    assert_error(
        "[camera]\nnear = 1e30\n",
        2,
        8,
        "near distance must be from",
    );
}

/// A sphere at the edge of the range still draws: the limits refuse only what would overflow.
#[test]
fn a_huge_far_sphere_within_the_limits_is_seen() {
    let scene = parse(
        "[render]\nwidth = 9\nheight = 9\nbackground = [0, 0, 0]\n\
         [camera]\neye = [0, 0, 0]\nlook_at = [0, 0, -1]\n\
         [[lights]]\nposition = [0, 0, 0]\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -9e14]\nradius = 1e14\n",
    )
    .unwrap();
    let bvh = Bvh::build(&scene.geometry);
    let (pixels, stats) = render_image(&Tracer::new(&scene, &bvh));
    let hits = stats.rays.primary_hits;
    assert!((1..81).contains(&hits), "{hits} of 81 pixels see it");
    let (center, corner) = (pixels[4 * 9 + 4], pixels[0]);
    assert!(center.is_finite() && center.max_element() > 0.1, "{center}");
    assert_eq!(corner.max_element(), 0.0, "{corner}");
}

// ---- what the README promises is optional --------------------------------------------------------

#[test]
fn a_light_without_a_type_is_a_point_light() {
    let scene = parse("[[lights]]\nposition = [1, 2, 3]\n").unwrap();
    assert!(matches!(
        scene.lights[..],
        [Light::Point { position, .. }] if position.to_array() == [1.0, 2.0, 3.0]
    ));
}

// ---- ray trees that grow without bound ----------------------------------------------------------

/// Two nested glass balls that reflect and transmit half each, with adaptive depth control off
/// and the deepest tree allowed: the tree doubles at every level, about 3·10¹³ rays a pixel.
const EXPLODING_TREE: &str = r#"
[render]
width = 3
height = 3
max_depth = 64
min_weight = 0
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
[[lights]]
position = [3, 3, 5]
[materials.half]
reflectivity = 0.5
transparency = 0.5
ior = 1.5
[[objects]]
type = "sphere"
radius = 2
material = "half"
[[objects]]
type = "sphere"
radius = 1
material = "half"
"#;

#[test]
fn an_exploding_ray_tree_stops_at_the_ray_budget() {
    let scene = parse(EXPLODING_TREE).unwrap();
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let (pixels, stats) = render_image(&tracer);
    let rays = stats.rays;
    assert!(pixels.iter().all(|c| c.is_finite()));
    assert!(rays.over_budget > 0, "{rays:?}");
    assert!(
        rays.reflected + rays.transmitted <= RAY_BUDGET * rays.primary,
        "{rays:?}"
    );

    // The inspector records the same bounded tree, and says where the budget cut it.
    let tree = trace_ray_tree(&tracer, 1, 1);
    assert!(
        tree.nodes.len() as u64 <= RAY_BUDGET + 1,
        "{}",
        tree.nodes.len()
    );
    assert!(
        tree.nodes.len() as u64 > RAY_BUDGET / 2,
        "{}",
        tree.nodes.len()
    );
    let budget_cuts = tree
        .nodes
        .iter()
        .flat_map(|node| &node.cuts)
        .filter(|cut| cut.reason == StopReason::RayBudget)
        .count();
    assert!(budget_cuts > 0);
    assert_eq!(tree.color, pixels[4]);
}

#[test]
fn ordinary_trees_never_reach_the_budget() {
    let scene = raylab::formats::toml::default_scene().unwrap();
    let bvh = Bvh::build(&scene.geometry);
    let mut scene = scene.clone();
    scene.settings.width = 64;
    scene.settings.height = 48;
    let (_, stats) = render_image(&Tracer::new(&scene, &bvh));
    assert_eq!(stats.rays.over_budget, 0);
    assert!(stats.rays.reflected + stats.rays.transmitted > 0);
}

/// Runs `raylab args` in `dir`, with `RAYLAB_MAX_MEMORY` set to `memory` if given.
fn raylab(dir: &Path, args: &[&str], memory: Option<&str>) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_raylab"));
    command.args(args).current_dir(dir);
    if let Some(memory) = memory {
        command.env("RAYLAB_MAX_MEMORY", memory);
    }
    command.output().unwrap()
}

/// The command must fail, saying `part`.
fn assert_refused(out: &Output, part: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains(part), "expected {part:?} in:\n{stderr}");
}

/// The command line says when the budget cut trees, and `inspect` prints a bounded tree.
#[test]
fn the_command_line_warns_of_the_budget_and_inspect_stays_small() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tree.toml"), EXPLODING_TREE).unwrap();
    let raylab = |args: &[&str]| raylab(dir.path(), args, None);
    let render = raylab(&["render", "tree.toml", "-o", "tree.png"]);
    let stderr = String::from_utf8_lossy(&render.stderr);
    assert!(render.status.success(), "{stderr}");
    assert!(
        stderr.contains(&format!("budget of {RAY_BUDGET} rays per eye ray")),
        "{stderr}"
    );
    for json in [false, true] {
        let mut args = vec!["inspect", "tree.toml", "--pixel", "1,1"];
        if json {
            args.push("--json");
        }
        let inspect = raylab(&args);
        assert!(inspect.status.success());
        let text = String::from_utf8_lossy(&inspect.stdout);
        assert!(text.len() < 4 << 20, "{} bytes", text.len());
        assert!(text.contains(if json { "ray_budget" } else { "budget" }));
    }
}

// ---- memory in proportion to the input ----------------------------------------------------------

/// A scene using a 4000×4000 texture (a PNG of a few kilobytes: one grey level compresses well).
fn big_texture_scene(dir: &Path, used: bool) {
    image::GrayImage::new(4000, 4000)
        .save(dir.join("big.png"))
        .unwrap();
    let material = if used {
        "[materials.m]\ntexture = \"big\"\n"
    } else {
        ""
    };
    let scene = format!("[textures.big]\ntype = \"image\"\nfile = \"big.png\"\n{material}");
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
}

/// Renders `scene.toml` as a small image.
const RENDER_SCENE: [&str; 8] = [
    "render",
    "scene.toml",
    "-o",
    "out.png",
    "--width",
    "8",
    "--height",
    "8",
];

#[test]
fn a_texture_larger_than_the_memory_is_refused_before_it_is_decoded() {
    let dir = tempfile::tempdir().unwrap();
    big_texture_scene(dir.path(), true);
    let out = raylab(dir.path(), &RENDER_SCENE, Some("32M"));
    assert_refused(&out, "the 4000×4000 image would take about 64.0 MB");
    assert_refused(&out, "more than the 33.6 MB of memory available");
    // Three bytes a texel: 48 MB for the texels and 16 MB while decoding fit in 80 MB.
    let out = raylab(dir.path(), &RENDER_SCENE, Some("80M"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_texture_no_material_uses_is_not_loaded() {
    let dir = tempfile::tempdir().unwrap();
    big_texture_scene(dir.path(), false);
    let out = raylab(dir.path(), &RENDER_SCENE, Some("32M"));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: scene.toml: texture `big` is not used by any material"),
        "{stderr}"
    );
}

#[test]
fn an_image_larger_than_the_memory_is_refused_before_the_render() {
    let dir = tempfile::tempdir().unwrap();
    // Adaptive anti-aliasing keeps a copy of the film as shown, 3 bytes a pixel.
    let adaptive = ["--samples", "16", "--aa-threshold", "0.03"];
    for (ext, sampling, needed) in [
        ("png", &[][..], "4.3 GB"),
        ("exr", &[], "4.3 GB"),
        ("png", &adaptive, "5.1 GB"),
    ] {
        let output = format!("big.{ext}");
        let size = ["--width", "16384", "--height", "16384"];
        let args = [&["render", "-o", output.as_str()][..], &size, sampling].concat();
        let out = raylab(dir.path(), &args, Some("1G"));
        assert_refused(
            &out,
            &format!("rendering a 16384×16384 image would take about {needed}"),
        );
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn a_scene_file_too_large_to_read_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let light = "[[lights]]\nposition = [1, 2, 3]\n";
    std::fs::write(dir.path().join("lights.toml"), light.repeat(40_000)).unwrap();
    let out = raylab(
        dir.path(),
        &["render", "lights.toml", "-o", "x.png"],
        Some("16M"),
    );
    assert_refused(
        &out,
        "lights.toml:1:1: reading this 1.3 MB file would take about 61.4 MB",
    );
}

#[test]
fn sizes_are_checked_against_their_stated_maximum() {
    let dir = tempfile::tempdir().unwrap();
    let out = raylab(dir.path(), &["bench", "--scenes", "bumpy:4294967295"], None);
    assert_refused(&out, "from 1 to 20000000 triangles, got 4294967295");
    let out = raylab(dir.path(), &["render", "-o", "x.png"], Some("lots"));
    assert_refused(&out, "RAYLAB_MAX_MEMORY=lots: expected bytes");
}

// ---- the same limits in NFF --------------------------------------------------------------------

const NFF_VIEW: &str = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n";

fn parse_nff(text: &str) -> Result<Scene, SceneError> {
    raylab::formats::nff::parse_nff(text, Path::new("test.nff"), Default::default())
}

#[test]
fn nff_shapes_past_single_precision_are_errors_at_their_keyword() {
    let error = parse_nff(&format!("{NFF_VIEW}s 0 0 -6e19 2e19\n")).unwrap_err();
    assert_eq!((error.line, error.column), (8, 1), "{error}");
    assert!(
        error.message.contains("the centre reaches [0, 0, -6e19]"),
        "{error}"
    );
    let error = parse_nff(&format!("{NFF_VIEW}s 0 0 0 3e38\n")).unwrap_err();
    assert!(error.message.contains("the sphere reaches"), "{error}");
}

#[test]
fn an_nff_hither_below_the_near_range_clips_as_little_as_raylab_can() {
    let text = NFF_VIEW.replace("hither 1", "hither 1e-12");
    let scene = parse_nff(&text).unwrap();
    assert_eq!(scene.camera.near, 1e-6);
}
