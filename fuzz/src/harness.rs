//! What the fuzz targets do with an input, as plain functions of its bytes: read it with one of
//! raylab's readers and, when it reads as a scene, render a tiny image of the scene and trace
//! the ray tree of one pixel. A reader's error is a fine outcome (returned as its message); a panic, a hang
//! or a runaway allocation is a bug. The fuzz targets (`fuzz/fuzz_targets/`) call these, and so
//! does the replay of the kept corpus (`tests/library/fuzz_corpus.rs`), so this file uses raylab and
//! std alone.

use std::path::{Path, PathBuf};
use std::sync::LazyLock;

use raylab::bvh::Bvh;
use raylab::camera::CameraSpec;
use raylab::compare::difference::{DEFAULT_TOLERANCE, HeatMap, difference};
use raylab::formats::nff::{NffDocument, NffLighting, parse_nff_document};
use raylab::formats::part::read_part_bytes;
use raylab::formats::sdl::parse_sdl;
use raylab::formats::toml::{
    ModelFormat, build_model_scene, parse_scene_with, parse_views, views_text,
};
use raylab::formats::{SceneError, SceneFiles, ascii_text, utf8_text};
use raylab::grade::assignment::parse_assignment;
use raylab::inspect::trace_ray_tree;
use raylab::progressive::render_image;
use raylab::scene::Scene;
use raylab::srgb_image::SrgbImage;
use raylab::views::{path, turntable};
use raylab::whitted::Tracer;

const TETRA_OBJ: &[u8] = include_bytes!("../../assets/models/tetra.obj");
const TETRA_MTL: &[u8] = include_bytes!("../../assets/models/tetra.mtl");
const GRID_PNG: &[u8] = include_bytes!("../../assets/textures/grid.png");
const PAWN_GLB: &[u8] = include_bytes!("../../assets/models/pawn.glb");
const LEAF_PNG: &[u8] = include_bytes!("../../assets/textures/leaf.png");

/// The files a fuzzed TOML scene may name: the shipped scenes' models and textures, by the
/// names the shipped scenes use. The large ones (the torus, the bricks, the sky) are played by
/// the small ones, so that every shipped scene loads, and renders fast.
const SCENE_FILES: &[(&str, &[u8])] = &[
    ("../models/tetra.obj", TETRA_OBJ),
    ("../models/tetra.mtl", TETRA_MTL),
    ("../models/torus.obj", TETRA_OBJ),
    ("../models/pawn.glb", PAWN_GLB),
    ("../textures/grid.png", GRID_PNG),
    ("../textures/bricks.png", GRID_PNG),
    ("../textures/sky.bmp", GRID_PNG),
    ("../textures/leaf.png", LEAF_PNG),
];

/// The scene the `obj` and `ply` targets load their input in, as a scene file's object of
/// type `kind` (`obj`, `ply`) whose file is `model.KIND`.
fn model_scene(kind: &str) -> String {
    format!(
        "[camera]\neye = [0, 1.5, 4]\nlook_at = [0, 0, 0]\n\n[[lights]]\ntype = \"point\"\n\
         position = [2, 5, 4]\n\n[[objects]]\ntype = \"{kind}\"\nfile = \"model.{kind}\"\n"
    )
}

/// Reads `data` as a TOML scene file, which may name [`SCENE_FILES`], and renders it.
pub fn toml_scene(data: &[u8]) -> Result<(), String> {
    let origin = Path::new("fuzz.toml");
    let text = utf8_text(data, origin).map_err(|e| e.to_string())?;
    let files = SceneFiles::Builtin(SCENE_FILES);
    let scene = parse_scene_with(text, origin, files).map_err(|e| e.to_string())?;
    render_tiny(scene);
    Ok(())
}

/// Reads `data` as an OBJ file (its MTL file `tetra.mtl` beside it) the way a scene file's
/// `type = "obj"` object loads one, and renders it.
pub fn obj(data: &[u8]) -> Result<(), String> {
    render_obj_model(&[("model.obj", data), ("tetra.mtl", TETRA_MTL)])
}

/// Loads `model.obj` of `files` (with the MTL files and images it names) the way a scene file's
/// `type = "obj"` object loads one, and renders it.
fn render_obj_model(files: &[(&str, &[u8])]) -> Result<(), String> {
    let origin = Path::new("fuzz-obj.toml");
    let scene = parse_scene_with(&model_scene("obj"), origin, SceneFiles::Builtin(files))
        .map_err(|e| e.to_string())?;
    render_tiny(scene);
    Ok(())
}

/// A square with texture coordinates, in the materials `a` and `b` of its MTL file
/// `model.mtl`: the model the `mtl` target's input is the materials of.
const TEXTURED_SQUARE_OBJ: &str = "mtllib model.mtl\nusemtl a\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\n\
     v -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 4/4\n";

/// Reads `data` as the MTL file of an OBJ model (a textured square, whose `map_Kd` lines may
/// name `grid.png`) the way a scene file's `type = "obj"` object loads one, and renders it.
pub fn mtl(data: &[u8]) -> Result<(), String> {
    render_obj_model(&[
        ("model.obj", TEXTURED_SQUARE_OBJ.as_bytes()),
        ("model.mtl", data),
        ("grid.png", GRID_PNG),
    ])
}

/// Reads `data` as a PLY file: a mesh read must have its faces' vertices and one of each
/// attribute per vertex (or none); then loads it the way a scene file's `type = "ply"` object
/// does, and renders it.
pub fn ply(data: &[u8]) -> Result<(), String> {
    let mesh = raylab::formats::ply::parse_ply(data).map_err(|e| e.to_string())?;
    let vertices = mesh.positions.len();
    let per_vertex = |n: usize| n == 0 || n == vertices;
    assert!(per_vertex(mesh.normals.len()) && per_vertex(mesh.uvs.len()));
    assert!(per_vertex(mesh.colors.len()));
    assert!(
        mesh.faces
            .iter()
            .flatten()
            .all(|&v| (v as usize) < vertices)
    );
    let files = [("model.ply", data)];
    let scene = parse_scene_with(
        &model_scene("ply"),
        Path::new("fuzz-ply.toml"),
        SceneFiles::Builtin(&files),
    )
    .map_err(|e| e.to_string())?;
    render_tiny(scene);
    Ok(())
}

/// Reads `data` as a glTF or GLB file opened on its own (its lights and first camera used),
/// with the buffer `model.bin` beside it for a `.gltf` that names one, and renders it.
pub fn gltf(data: &[u8]) -> Result<(), String> {
    let files = [("model.gltf", data), ("model.bin", &data[data.len() / 2..])];
    let scene = build_model_scene(
        Path::new("model.gltf"),
        SceneFiles::Builtin(&files),
        ModelFormat::Gltf,
    )
    .map_err(|e| e.to_string())?;
    render_tiny(scene);
    Ok(())
}

/// Reads `data` as an NFF file, checks that the document written back as NFF reads back the
/// same, builds the scene and renders it.
pub fn nff(data: &[u8]) -> Result<(), String> {
    let text = ascii_text(data);
    let document = read_nff(&text).map_err(|e| e.to_string())?;
    assert_reads_back(&document);
    let scene = document
        .to_scene(NffLighting::default())
        .map_err(|e| e.to_string())?;
    render_tiny(scene);
    Ok(())
}

/// The one mesh file a fuzzed SDL file may name (`mesh square.3vn`): a square of one face.
const SQUARE_3VN: &[u8] = b"4 1 1\n-1 -1 0  1 -1 0  1 1 0  -1 1 0\n0 0 1\n4\n0 1 2 3\n0 0 0 0\n";
/// A 2 × 2 image (binary PPM: red, blue / blue, red), for `makePixmap` and `backgroundImage`.
const TWO_BY_TWO_PPM: &[u8] = b"P6 2 2 255\n\xff\0\0\0\0\xff\0\0\xff\xff\0\0";

/// Reads `data` as an SDL file, which may name `square.3vn` and `tex.ppm`, and renders it (through the
/// placeholder camera SDL scenes get).
pub fn sdl(data: &[u8]) -> Result<(), String> {
    let files = [("square.3vn", SQUARE_3VN), ("tex.ppm", TWO_BY_TWO_PPM)];
    let scene = parse_sdl(
        &ascii_text(data),
        Path::new("fuzz.dat"),
        SceneFiles::Builtin(&files),
    )
    .map_err(|e| e.to_string())?;
    render_tiny(scene);
    Ok(())
}

/// Reads `data` as a views file (`NAME.views.toml`), checks that the views written back read
/// back the same, and builds the cameras of a short path through them and of a turntable
/// around the first.
pub fn views(data: &[u8]) -> Result<(), String> {
    let origin = Path::new("fuzz.views.toml");
    let text = utf8_text(data, origin).map_err(|e| e.to_string())?;
    let base = CameraSpec::default();
    let views = parse_views(text, origin, base).map_err(|e| e.to_string())?;
    let written = views_text(&views);
    let reread = parse_views(&written, origin, base)
        .unwrap_or_else(|e| panic!("the views raylab wrote do not read back: {e}\n{written}"));
    assert_eq!(reread, views, "{written}");
    let cameras = views.cameras();
    if let Some(first) = cameras.first() {
        assert_eq!(turntable(first, 5)?.len(), 5);
    }
    assert_eq!(path(&cameras, 7)?.len(), 7);
    Ok(())
}

/// The scene file an assignment may name, `scene.toml`: a ball and a light.
const ASSIGNED_SCENE: &str = "[camera]\neye = [0, 1, 4]\nlook_at = [0, 0, 0]\n[[lights]]\n\
    type = \"point\"\nposition = [2, 4, 3]\n[[objects]]\ntype = \"sphere\"\n\
    center = [0, 0, 0]\nradius = 1\n";

/// Reads `data` as a `raylab grade` assignment, in a folder of this process's own beside the
/// scene file `scene.toml` ([`ASSIGNED_SCENE`]), and checks that it has scenes.
pub fn assignment(data: &[u8]) -> Result<(), String> {
    static FOLDER: LazyLock<PathBuf> = LazyLock::new(|| {
        let folder = std::env::temp_dir().join(format!("raylab-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&folder).expect("a folder for the assignment");
        std::fs::write(folder.join("scene.toml"), ASSIGNED_SCENE).expect("the scene file");
        folder
    });
    let path = FOLDER.join("assignment.toml");
    let assignment = parse_assignment(data, &path).map_err(|e| e.to_string())?;
    assert!(!assignment.scenes.is_empty());
    Ok(())
}

/// Reads `data` as a part of an image (an OpenEXR file from `raylab render --tile`), header
/// first, and checks that its pixels fill its rectangle.
pub fn part(data: &[u8]) -> Result<(), String> {
    let part = read_part_bytes(data, Path::new("fuzz.exr")).map_err(|e| e.to_string())?;
    assert_eq!(part.pixels.len() as u64, part.info.rect.pixels());
    Ok(())
}

/// Reads NFF text into a document, named `fuzz.nff` in its errors.
fn read_nff(text: &str) -> Result<NffDocument, SceneError> {
    parse_nff_document(text, Path::new("fuzz.nff"))
}

/// Writes `document` as NFF and reads it back. The writer rounds numbers to six significant
/// digits, as C's `%g` does, so the first reading back equals `document` only up to that
/// rounding: the two written texts hold the same words, and their numbers differ by at most
/// the rounding. Numbers once rounded stay as they are, so the second reading back equals the
/// first exactly.
fn assert_reads_back(document: &NffDocument) {
    let written = document.to_nff_string();
    let reread = read_nff(&written)
        .unwrap_or_else(|e| panic!("the NFF raylab wrote does not read back: {e}\n{written}"));
    let rewritten = reread.to_nff_string();
    let words = |text: &str| text.split_whitespace().map(str::to_owned).collect();
    let (first, second): (Vec<String>, Vec<String>) = (words(&written), words(&rewritten));
    assert_eq!(
        first.len(),
        second.len(),
        "{written}\nreads back as\n{rewritten}"
    );
    for (a, b) in first.iter().zip(&second) {
        assert!(
            a == b || same_but_rounding(a, b),
            "`{a}` reads back as `{b}`:\n{written}\nreads back as\n{rewritten}"
        );
    }
    let third = read_nff(&rewritten)
        .unwrap_or_else(|e| panic!("the NFF raylab wrote does not read back: {e}\n{rewritten}"));
    assert_eq!(third, reread, "{rewritten}");
}

/// Whether the numbers `a` and `b` differ by no more than `%g`'s rounding (half a unit in the
/// sixth significant digit; double precision is coarser than that near zero).
fn same_but_rounding(a: &str, b: &str) -> bool {
    match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(a), Ok(b)) => (a - b).abs() <= 5e-6 * a.abs().max(b.abs()) + f64::MIN_POSITIVE,
        _ => false,
    }
}

/// Renders `scene` as a 4 × 3 image at one sample per pixel, through the BVH and the
/// progressive renderer, and traces the ray tree of one pixel with the inspector: little work,
/// but all of it the renderer's own.
fn render_tiny(mut scene: Scene) {
    let settings = &mut scene.settings;
    (settings.width, settings.height) = (4, 3);
    (settings.samples, settings.block_size) = (1, 2);
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let (pixels, _) = render_image(&tracer);
    assert_eq!(pixels.len(), 4 * 3);
    let tree = trace_ray_tree(&tracer, 2, 1);
    assert!(
        !tree.nodes.is_empty(),
        "a ray tree holds at least the eye ray"
    );
}

/// Reads `data` as an image file that `raylab diff` compares (any format), compares it with
/// itself and draws the heat map.
pub fn image(data: &[u8]) -> Result<(), String> {
    let image = SrgbImage::decode(data)?;
    let figures = difference(&image, &image, DEFAULT_TOLERANCE)?;
    assert!(figures.within_tolerance() && figures.largest == 0);
    let map = HeatMap::new(&image, &image, &figures);
    let dark = map.color(0, 0);
    let last = (image.width - 1, image.height - 1);
    assert_eq!(
        map.color(last.0, last.1),
        dark,
        "equal pixels are all one colour"
    );
    Ok(())
}
