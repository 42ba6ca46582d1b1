//! glTF 2.0 models as raylab reads them. Every file is written by the test's own [`Writer`]
//! (JSON with serde_json, the binary buffer by hand), not by the reader under test: the same
//! model as `.gltf` with a `.bin`, with a `data:` URI and as `.glb`; node hierarchies with TRS
//! and matrices against the same triangles written as a scene file's mesh; every index type,
//! strips, fans and sparse accessors; vertex colours; the material rule against materials
//! written in TOML; lights and cameras; and the errors of broken and refused files.

use std::path::Path;

use base64::Engine;
use glam::{Quat, Vec3};
use raylab::formats::load_any;
use raylab::light::Light;
use serde_json::{Value, json};

use super::models::{load_written, rendered};

/// glTF's component types.
const U8: u32 = 5121;
const U16: u32 = 5123;
const U32: u32 = 5125;
const F32: u32 = 5126;
/// glTF's primitive modes.
const POINTS: u32 = 0;
const TRIANGLES: u32 = 4;
const STRIP: u32 = 5;
const FAN: u32 = 6;

/// A glTF file being written: its JSON and its one binary buffer.
struct Writer {
    json: Value,
    bin: Vec<u8>,
}

impl Writer {
    fn new() -> Writer {
        Writer {
            json: json!({
                "asset": {"version": "2.0", "generator": "raylab's tests"},
                "accessors": [], "bufferViews": [], "meshes": [], "nodes": [],
                "scenes": [{"nodes": []}], "scene": 0
            }),
            bin: Vec::new(),
        }
    }

    fn push(&mut self, list: &str, item: Value) -> usize {
        let array = self.json[list].as_array_mut().unwrap();
        array.push(item);
        array.len() - 1
    }

    /// A buffer view of `bytes`, 4-byte aligned in the buffer.
    fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut view =
            json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(stride) = stride {
            view["byteStride"] = json!(stride);
        }
        self.bin.extend_from_slice(bytes);
        self.push("bufferViews", view)
    }

    /// A VEC3 float accessor of `points` (with the min and max glTF asks of positions).
    fn vec3s(&mut self, points: &[Vec3]) -> usize {
        let bytes: Vec<u8> = points
            .iter()
            .flat_map(|p| p.to_array())
            .flat_map(f32::to_le_bytes)
            .collect();
        let view = self.view(&bytes, None);
        let min = points.iter().fold(Vec3::INFINITY, |a, &b| a.min(b));
        let max = points.iter().fold(Vec3::NEG_INFINITY, |a, &b| a.max(b));
        self.push(
            "accessors",
            json!({"bufferView": view, "componentType": F32, "count": points.len(),
                   "type": "VEC3", "min": min.to_array(), "max": max.to_array()}),
        )
    }

    /// A SCALAR accessor of `indices` stored as `component` (U8, U16 or U32).
    fn indices(&mut self, indices: &[u32], component: u32) -> usize {
        let bytes: Vec<u8> = indices
            .iter()
            .flat_map(|&i| match component {
                U8 => vec![i as u8],
                U16 => (i as u16).to_le_bytes().to_vec(),
                _ => i.to_le_bytes().to_vec(),
            })
            .collect();
        let view = self.view(&bytes, None);
        self.push(
            "accessors",
            json!({"bufferView": view, "componentType": component, "count": indices.len(),
                   "type": "SCALAR"}),
        )
    }

    /// A mesh of one primitive of `mode`; `attributes` names accessors.
    fn mesh(
        &mut self,
        attributes: Value,
        indices: Option<usize>,
        mode: u32,
        material: Option<usize>,
    ) -> usize {
        let mut primitive = json!({"attributes": attributes, "mode": mode});
        if let Some(indices) = indices {
            primitive["indices"] = json!(indices);
        }
        if let Some(material) = material {
            primitive["material"] = json!(material);
        }
        self.push("meshes", json!({"primitives": [primitive]}))
    }

    /// A node; a root of the scene when `root`.
    fn node(&mut self, node: Value, root: bool) -> usize {
        let index = self.push("nodes", node);
        if root {
            self.json["scenes"][0]["nodes"]
                .as_array_mut()
                .unwrap()
                .push(json!(index));
        }
        index
    }

    /// The JSON with the buffer at `uri`.
    fn text_with(&self, uri: &str) -> Vec<u8> {
        let mut json = self.json.clone();
        json["buffers"] = json!([{"uri": uri, "byteLength": self.bin.len()}]);
        serde_json::to_vec_pretty(&json).unwrap()
    }

    /// A `.gltf` naming `bin` beside it, and the bytes of `bin`.
    fn gltf(&self, bin: &str) -> (Vec<u8>, Vec<u8>) {
        (self.text_with(bin), self.bin.clone())
    }

    /// A `.gltf` holding its buffer as a `data:` URI.
    fn embedded(&self) -> Vec<u8> {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        self.text_with(&format!("data:application/octet-stream;base64,{data}"))
    }

    /// The `.glb`: header, JSON chunk (padded with spaces), BIN chunk (padded with zeros).
    fn glb(&self) -> Vec<u8> {
        let mut json = self.json.clone();
        json["buffers"] = json!([{"byteLength": self.bin.len()}]);
        let mut text = serde_json::to_vec(&json).unwrap();
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let length = 12 + 8 + text.len() + 8 + bin.len();
        let mut out = b"glTF".to_vec();
        out.extend(2u32.to_le_bytes());
        out.extend((length as u32).to_le_bytes());
        out.extend((text.len() as u32).to_le_bytes());
        out.extend(b"JSON");
        out.extend(text);
        out.extend((bin.len() as u32).to_le_bytes());
        out.extend(b"BIN\0");
        out.extend(bin);
        out
    }
}

/// A unit cube's corners and its 12 triangles, counter-clockwise seen from outside.
fn cube() -> (Vec<Vec3>, Vec<u32>) {
    let corners = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32) - 0.5)
        .collect();
    let faces = vec![
        0, 2, 1, 1, 2, 3, // z = −½
        4, 5, 6, 5, 7, 6, // z = +½
        0, 1, 4, 1, 5, 4, // y = −½
        2, 6, 3, 3, 6, 7, // y = +½
        0, 4, 2, 2, 4, 6, // x = −½
        1, 3, 5, 3, 7, 5, // x = +½
    ];
    (corners, faces)
}

/// The cube placed twice: by a root node's TRS, and by a parent's matrix times its child's
/// TRS. Returns the writer and the two placements as scene-file transform steps.
fn two_cubes() -> (Writer, [String; 2]) {
    let mut w = Writer::new();
    let (corners, faces) = cube();
    let positions = w.vec3s(&corners);
    let indices = w.indices(&faces, U16);
    let mesh = w.mesh(
        json!({"POSITION": positions}),
        Some(indices),
        TRIANGLES,
        None,
    );
    let turn = Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.0).normalize(), 0.6);
    w.node(
        json!({"mesh": mesh, "translation": [-0.8, 0.5, 0.0], "rotation": turn.to_array(),
               "scale": [0.8, 1.2, 0.9]}),
        true,
    );
    let child = w.node(
        json!({"mesh": mesh, "translation": [0.0, 0.0, 0.5], "scale": [0.5, 0.5, 0.5]}),
        false,
    );
    let parent =
        glam::Mat4::from_translation(Vec3::new(1.0, 0.3, 0.0)) * glam::Mat4::from_rotation_y(0.4);
    w.node(
        json!({"matrix": parent.to_cols_array(), "children": [child]}),
        true,
    );
    let first = "[{ scale = [0.8, 1.2, 0.9] }, { rotate = { axis = [0.70710677, 0.70710677, 0], \
                 degrees = 34.37747 } }, { translate = [-0.8, 0.5, 0] }]"
        .to_string();
    let second = format!(
        "[{{ scale = [0.5, 0.5, 0.5] }}, {{ translate = [0, 0, 0.5] }}, {{ rotate = {{ axis = \
         [0, 1, 0], degrees = {} }} }}, {{ translate = [1, 0.3, 0] }}]",
        0.4f32.to_degrees()
    );
    (w, [first, second])
}

/// A scene file around `objects`: a camera, a point and a directional light, two materials.
fn scene_with(objects: &str) -> String {
    format!(
        "[camera]\neye = [1.5, 2.5, 4]\nlook_at = [0, 0.3, 0]\nview_angle = 45\n\
         [[lights]]\ntype = \"point\"\nposition = [3, 5, 4]\n\
         [[lights]]\ntype = \"directional\"\ndirection = [-1, 1, 2]\ncolor = [0.4, 0.4, 0.4]\n\
         [materials.red]\ncolor = [0.9, 0.2, 0.1]\nspecular = 0.5\n\
         {objects}"
    )
}

/// A scene file placing the glTF file `file` in `material`.
fn placing(file: &str, material: &str) -> String {
    scene_with(&format!(
        "[[objects]]\ntype = \"gltf\"\nfile = \"{file}\"\nmaterial = \"{material}\"\n"
    ))
}

/// Writes `files` into `dir` and the error of loading `name` among them.
fn error_of(dir: &Path, files: &[(&str, &[u8])], name: &str) -> String {
    for (file, bytes) in files {
        std::fs::write(dir.join(file), bytes).unwrap();
    }
    match load_any(dir.join(name).to_str().unwrap()) {
        Ok(_) => panic!("{name} loaded"),
        Err(e) => e.to_string(),
    }
}

/// How many of the pixels of `a` and `b` differ by more than 2 levels in some channel.
fn pixels_apart(a: &[u8], b: &[u8]) -> usize {
    a.chunks(3)
        .zip(b.chunks(3))
        .filter(|(p, q)| p.iter().zip(q.iter()).any(|(x, y)| x.abs_diff(*y) > 2))
        .count()
}

#[test]
fn gltf_with_a_bin_file_with_a_data_uri_and_as_glb_render_the_triangles_a_scene_file_places() {
    let dir = tempfile::tempdir().unwrap();
    let (w, [first, second]) = two_cubes();
    let (text, bin) = w.gltf("cubes%20data.bin");
    let (embedded, glb) = (w.embedded(), w.glb());
    let files: &[(&str, &[u8])] = &[
        ("cubes.gltf", &text),
        ("cubes data.bin", &bin),
        ("embedded.gltf", &embedded),
        ("cubes.glb", &glb),
    ];
    let images: Vec<Vec<u8>> = ["cubes.gltf", "embedded.gltf", "cubes.glb"]
        .iter()
        .map(|file| {
            let scene_file = format!("{file}.toml");
            let scene = placing(file, "red");
            let mut all = files.to_vec();
            all.push((&scene_file, scene.as_bytes()));
            rendered(load_written(dir.path(), &all, &scene_file))
        })
        .collect();
    // The mesh two nodes place is stored once, as a model placed by two instances.
    let cubes = load_written(dir.path(), &[], "cubes.glb.toml");
    assert_eq!(cubes.geometry.models().len(), 1);
    assert_eq!(cubes.geometry.instances().len(), 2);
    assert!(cubes.geometry.meshes.is_empty());
    assert!(images[0] == images[1], "the data: URI changes the image");
    assert!(images[0] == images[2], "the GLB changes the image");

    // The same triangles, written as the scene file's own meshes with the nodes' transforms.
    let (corners, faces) = cube();
    let mesh = format!(
        "type = \"mesh\"\nmaterial = \"red\"\npositions = [{}]\nfaces = [{}]\n",
        corners
            .iter()
            .map(|p| format!("[{}, {}, {}]", p.x, p.y, p.z))
            .collect::<Vec<_>>()
            .join(", "),
        faces
            .chunks(3)
            .map(|f| format!("[{}, {}, {}]", f[0], f[1], f[2]))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let reference = scene_with(&format!(
        "[[objects]]\n{mesh}transform = {first}\n[[objects]]\n{mesh}transform = {second}\n"
    ));
    let reference = rendered(load_written(
        dir.path(),
        &[("reference.toml", reference.as_bytes())],
        "reference.toml",
    ));
    let differing = pixels_apart(&images[0], &reference);
    // The transforms are composed in another order of roundings: an edge pixel may turn.
    assert!(
        differing <= 20,
        "{differing} of {} pixels differ from the scene file's own meshes",
        96 * 72
    );
    assert!(
        images[0].chunks(3).any(|p| p[0] > 100 && p[1] < 80),
        "the red cubes show"
    );
}

/// One quad strip's worth of corners: a bent ribbon of `n` vertices along x.
fn ribbon(n: usize) -> Vec<Vec3> {
    (0..n)
        .map(|i| {
            let x = (i / 2) as f32 * 0.5 - 1.0;
            Vec3::new(x, (i % 2) as f32, 0.3 * (x * 2.0).sin())
        })
        .collect()
}

/// The triangles of a strip of `n` vertices, cut by the test as the specification says: odd
/// ones swap their last two corners.
fn strip_triangles(n: u32) -> Vec<u32> {
    (0..n - 2)
        .flat_map(|i| {
            if i % 2 == 0 {
                [i, i + 1, i + 2]
            } else {
                [i, i + 2, i + 1]
            }
        })
        .collect()
}

/// The image of one primitive of `mode` through `indices` (stored as `component`, or none)
/// over `corners`, placed in a scene file.
fn primitive_image(
    dir: &Path,
    corners: &[Vec3],
    indices: Option<(&[u32], u32)>,
    mode: u32,
) -> Vec<u8> {
    let mut w = Writer::new();
    let positions = w.vec3s(corners);
    let indices = indices.map(|(i, component)| w.indices(i, component));
    let mesh = w.mesh(json!({"POSITION": positions}), indices, mode, None);
    w.node(json!({"mesh": mesh}), true);
    let scene = placing("p.glb", "red");
    rendered(load_written(
        dir,
        &[("p.glb", &w.glb()), ("p.toml", scene.as_bytes())],
        "p.toml",
    ))
}

#[test]
fn every_index_type_strips_and_fans_draw_the_triangles_the_specification_cuts() {
    let dir = tempfile::tempdir().unwrap();
    let corners = ribbon(10);
    let strip = strip_triangles(10);
    let listed = primitive_image(dir.path(), &corners, Some((&strip, U32)), TRIANGLES);
    assert!(listed.chunks(3).any(|p| p[0] > 100), "the ribbon shows");
    for component in [U8, U16] {
        let image = primitive_image(dir.path(), &corners, Some((&strip, component)), TRIANGLES);
        assert!(
            image == listed,
            "indices stored as {component} change the image"
        );
    }
    let unindexed: Vec<Vec3> = strip.iter().map(|&i| corners[i as usize]).collect();
    assert!(
        primitive_image(dir.path(), &unindexed, None, TRIANGLES) == listed,
        "a primitive without indices draws other triangles"
    );
    let all: Vec<u32> = (0..10).collect();
    assert!(
        primitive_image(dir.path(), &corners, Some((&all, U8)), STRIP) == listed,
        "a strip draws other triangles"
    );
    assert!(
        primitive_image(dir.path(), &corners, None, STRIP) == listed,
        "a strip without indices draws other triangles"
    );
    // A fan round a hub: triangles (i+1, i+2, 0).
    let hub: Vec<Vec3> = std::iter::once(Vec3::new(0.0, 0.5, 0.6))
        .chain((0..7).map(|k| {
            let a = k as f32 * 0.8;
            Vec3::new(a.cos(), 0.5 + a.sin() * 0.8, 0.0)
        }))
        .collect();
    let fan_list: Vec<u32> = (0..6u32).flat_map(|i| [i + 1, i + 2, 0]).collect();
    let fan_listed = primitive_image(dir.path(), &hub, Some((&fan_list, U16)), TRIANGLES);
    assert!(
        primitive_image(dir.path(), &hub, None, FAN) == fan_listed,
        "a fan draws other triangles"
    );
}

#[test]
fn a_sparse_accessor_replaces_the_elements_it_names() {
    let dir = tempfile::tempdir().unwrap();
    let corners = ribbon(8);
    let strip = strip_triangles(8);
    let dense = primitive_image(dir.path(), &corners, Some((&strip, U16)), TRIANGLES);

    // The same positions with two of them wrong in the base view, put right by the sparse part.
    let mut w = Writer::new();
    let mut wrong = corners.clone();
    wrong[3] = Vec3::splat(40.0);
    wrong[6] = Vec3::splat(-40.0);
    let positions = w.vec3s(&wrong);
    let sparse_indices = w.view(&[3u8, 6], None);
    let values: Vec<u8> = [corners[3], corners[6]]
        .iter()
        .flat_map(|p| p.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    let sparse_values = w.view(&values, None);
    w.json["accessors"][positions]["sparse"] = json!({
        "count": 2,
        "indices": {"bufferView": sparse_indices, "componentType": U8},
        "values": {"bufferView": sparse_values}
    });
    let min = corners.iter().fold(Vec3::INFINITY, |a, &b| a.min(b));
    let max = corners.iter().fold(Vec3::NEG_INFINITY, |a, &b| a.max(b));
    w.json["accessors"][positions]["min"] = json!(min.to_array());
    w.json["accessors"][positions]["max"] = json!(max.to_array());
    let indices = w.indices(&strip, U16);
    let mesh = w.mesh(
        json!({"POSITION": positions}),
        Some(indices),
        TRIANGLES,
        None,
    );
    w.node(json!({"mesh": mesh}), true);
    let scene = placing("s.gltf", "red");
    let (text, bin) = w.gltf("s.bin");
    let sparse = rendered(load_written(
        dir.path(),
        &[
            ("s.gltf", &text),
            ("s.bin", &bin),
            ("s.toml", scene.as_bytes()),
        ],
        "s.toml",
    ));
    assert!(
        sparse == dense,
        "the sparse substitutes are not where they belong"
    );
}

#[test]
fn vertex_colours_multiply_the_material_colour() {
    let dir = tempfile::tempdir().unwrap();
    let corners = ribbon(8);
    let strip = strip_triangles(8);
    let tint = [0.25f32, 0.5, 1.0];
    let mut w = Writer::new();
    let positions = w.vec3s(&corners);
    // COLOR_0 as normalized u8 RGBA, stored with a stride of 8 bytes.
    let colours: Vec<u8> = (0..corners.len())
        .flat_map(|_| [64u8, 128, 255, 255, 9, 9, 9, 9])
        .collect();
    let colour_view = w.view(&colours, Some(8));
    let colour_accessor = w.push(
        "accessors",
        json!({"bufferView": colour_view, "componentType": U8, "normalized": true,
               "count": corners.len(), "type": "VEC4"}),
    );
    let indices = w.indices(&strip, U16);
    let mesh = w.mesh(
        json!({"POSITION": positions, "COLOR_0": colour_accessor}),
        Some(indices),
        TRIANGLES,
        None,
    );
    w.node(json!({"mesh": mesh}), true);
    let scene = placing("c.glb", "red");
    let coloured = rendered(load_written(
        dir.path(),
        &[("c.glb", &w.glb()), ("c.toml", scene.as_bytes())],
        "c.toml",
    ));
    // The same ribbon without colours, its material's colour multiplied by the test.
    let mut plain = Writer::new();
    let positions = plain.vec3s(&corners);
    let indices = plain.indices(&strip, U16);
    let mesh = plain.mesh(
        json!({"POSITION": positions}),
        Some(indices),
        TRIANGLES,
        None,
    );
    plain.node(json!({"mesh": mesh}), true);
    let byte = |b: u8| f32::from(b) / 255.0;
    let tinted = [0.9 * byte(64), 0.2 * byte(128), 0.1 * byte(255)];
    let scene = scene_with(&format!(
        "[materials.tinted]\ncolor = [{}, {}, {}]\nspecular = 0.5\n\
         [[objects]]\ntype = \"gltf\"\nfile = \"plain.glb\"\nmaterial = \"tinted\"\n",
        tinted[0], tinted[1], tinted[2]
    ));
    let reference = rendered(load_written(
        dir.path(),
        &[
            ("plain.glb", &plain.glb()),
            ("plain.toml", scene.as_bytes()),
        ],
        "plain.toml",
    ));
    assert!(tint[2] == byte(255));
    let differing = pixels_apart(&coloured, &reference);
    assert_eq!(differing, 0, "vertex colours do not multiply the colour");
}

/// A closed UV sphere of radius 1 at the origin, as corners and triangles.
fn sphere() -> (Vec<Vec3>, Vec<u32>) {
    let (rings, segments) = (12u32, 24u32);
    let mut corners = Vec::new();
    for r in 0..=rings {
        let theta = std::f32::consts::PI * r as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            corners.push(Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ));
        }
    }
    let mut faces = Vec::new();
    for r in 0..rings {
        for s in 0..segments {
            let a = r * segments + s;
            let b = r * segments + (s + 1) % segments;
            let (c, d) = (a + segments, b + segments);
            faces.extend([a, b, c, b, d, c]);
        }
    }
    (corners, faces)
}

#[test]
fn a_mirror_glass_and_a_rough_ball_render_as_balls_with_the_rules_values_written_in_toml() {
    let dir = tempfile::tempdir().unwrap();
    let (corners, faces) = sphere();
    let mut w = Writer::new();
    let positions = w.vec3s(&corners);
    let indices = w.indices(&faces, U16);
    w.json["materials"] = json!([
        {"name": "mirror", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.8, 0.4, 1],
            "metallicFactor": 1, "roughnessFactor": 0}},
        {"name": "glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                           "KHR_materials_ior": {"ior": 1.5}}},
        {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1],
            "metallicFactor": 0, "roughnessFactor": 1},
            "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1}}}
    ]);
    w.json["extensionsUsed"] = json!([
        "KHR_materials_transmission",
        "KHR_materials_ior",
        "KHR_materials_clearcoat"
    ]);
    for (material, x) in [(0, -2.2), (1, 0.0), (2, 2.2)] {
        let mesh = w.mesh(
            json!({"POSITION": positions}),
            Some(indices),
            TRIANGLES,
            Some(material),
        );
        w.node(json!({"mesh": mesh, "translation": [x, 1.0, 0.0]}), true);
    }
    let floor = "[textures.checks]\ntype = \"checker3d\"\n[materials.floor]\ntexture = \"checks\"\n\
                 [[objects]]\ntype = \"plane\"\nnormal = [0, 1, 0]\npoint = [0, 0, 0]\nmaterial = \"floor\"\n";
    let camera = "[camera]\neye = [0, 2.5, 7]\nlook_at = [0, 1, 0]\nview_angle = 50\n\
                  [[lights]]\ntype = \"point\"\nposition = [3, 6, 5]\n";
    let from_gltf = format!("{camera}{floor}[[objects]]\ntype = \"gltf\"\nfile = \"balls.glb\"\n");
    let scene = load_written(
        dir.path(),
        &[
            ("balls.glb", &w.glb()),
            ("from_gltf.toml", from_gltf.as_bytes()),
        ],
        "from_gltf.toml",
    );
    let report = scene.notes.join("\n");
    assert!(
        report.ends_with(
            "balls.glb: glTF: 3 materials → 1 mirror, 1 glass, 1 Phong; not used: \
             KHR_materials_clearcoat (1)"
        ),
        "{report}"
    );
    assert!(
        scene
            .material_names
            .contains(&"balls.glb › glass".to_string()),
        "{:?}",
        scene.material_names
    );
    let from_gltf = rendered(scene);

    // The rule's values, written by hand: a gold mirror reflects all, tinted gold, and scatters
    // nothing, glass
    // lets all through with Fresnel at index 1.5 and reflects 4 %, a rough dielectric is
    // diffuse with no highlight.
    let materials = "[materials.mirror]\ncolor = [1, 0.8, 0.4]\nambient = 0\ndiffuse = 0\nspecular = 1\n\
                     specular_color = [1, 0.8, 0.4]\nshininess = 10000\nreflectivity = 1\n\
                     reflection_color = [1, 0.8, 0.4]\n\
                     [materials.glass]\ncolor = [1, 1, 1]\nambient = 0\ndiffuse = 0\nspecular = 1\n\
                     shininess = 10000\nreflectivity = 0.04\ntransparency = 1\nior = 1.5\nfresnel = true\n\
                     [materials.clay]\ncolor = [0.8, 0.5, 0.3]\nambient = 0.1\ndiffuse = 1\nspecular = 0\n\
                     shininess = 1\n";
    let mut balls = String::new();
    for (name, x) in [("mirror", -2.2), ("glass", 0.0), ("clay", 2.2)] {
        balls += &format!(
            "[[objects]]\ntype = \"gltf\"\nfile = \"ball.glb\"\nmaterial = \"{name}\"\n\
             transform = [{{ translate = [{x}, 1, 0] }}]\n"
        );
    }
    let mut one = Writer::new();
    let positions = one.vec3s(&corners);
    let indices = one.indices(&faces, U16);
    let mesh = one.mesh(
        json!({"POSITION": positions}),
        Some(indices),
        TRIANGLES,
        None,
    );
    one.node(json!({"mesh": mesh}), true);
    let by_hand = format!("{camera}{floor}{materials}{balls}");
    let by_hand = rendered(load_written(
        dir.path(),
        &[
            ("ball.glb", &one.glb()),
            ("by_hand.toml", by_hand.as_bytes()),
        ],
        "by_hand.toml",
    ));
    let differing = pixels_apart(&from_gltf, &by_hand);
    // The balls placed by a node and by a scene file's transform land on the same floats.
    assert_eq!(
        differing, 0,
        "the rule's materials differ from the same values in TOML"
    );
}

/// A model with the cube, a camera and the given lights, at nodes the test places.
fn lit_cube(lights: Value, light_nodes: &[Value], camera: bool) -> Writer {
    let mut w = Writer::new();
    let (corners, faces) = cube();
    let positions = w.vec3s(&corners);
    let indices = w.indices(&faces, U8);
    let mesh = w.mesh(
        json!({"POSITION": positions}),
        Some(indices),
        TRIANGLES,
        None,
    );
    w.node(json!({"mesh": mesh, "translation": [0.0, 0.0, 0.0]}), true);
    if !lights.is_null() {
        w.json["extensionsUsed"] = json!(["KHR_lights_punctual"]);
        w.json["extensions"] = json!({"KHR_lights_punctual": {"lights": lights}});
    }
    for node in light_nodes {
        w.node(node.clone(), true);
    }
    if camera {
        w.json["cameras"] = json!([{"type": "perspective",
            "perspective": {"yfov": 0.7, "znear": 0.1, "aspectRatio": 2.0}}]);
        // A camera at (0, 0, 6) turned 90° about y, so that it looks down −x from (6, 0, 0)…
        let turn = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
        w.node(
            json!({"camera": 0, "rotation": turn.to_array(), "translation": [6.0, 0.0, 0.0]}),
            true,
        );
        // …and the same camera again at (0, 1, 5), looking down −z.
        w.node(json!({"camera": 0, "translation": [0.0, 1.0, 5.0]}), true);
    }
    w
}

#[test]
fn lights_and_the_camera_come_from_their_nodes_with_the_written_conversion() {
    let dir = tempfile::tempdir().unwrap();
    let lights = json!([
        {"type": "point", "intensity": 20.0, "color": [1.0, 0.5, 0.5]},
        {"type": "directional", "intensity": 2.0},
        {"type": "spot", "intensity": 5.0, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}}
    ]);
    let down = Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2);
    let nodes = [
        json!({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.0, 3.0, 4.0]}),
        json!({"extensions": {"KHR_lights_punctual": {"light": 1}}, "rotation": down.to_array()}),
        json!({"extensions": {"KHR_lights_punctual": {"light": 2}}, "translation": [0.0, 5.0, 0.0], "rotation": down.to_array()}),
    ];
    let w = lit_cube(lights, &nodes, true);
    let scene = load_written(dir.path(), &[("lit.glb", &w.glb())], "lit.glb");
    let pi = std::f32::consts::PI;
    let [point, directional, spot] = scene.lights.as_slice() else {
        panic!("{:?}", scene.lights)
    };
    let Light::Point { position, color } = point else {
        panic!("{point:?}")
    };
    assert!(position.abs_diff_eq(Vec3::new(0.0, 3.0, 4.0), 1e-5));
    // Its brightness at the cube's centre, 5 away.
    assert!((color.x - 20.0 / (pi * 25.0)).abs() < 1e-5, "{color:?}");
    assert!((color.y - 10.0 / (pi * 25.0)).abs() < 1e-5, "{color:?}");
    let Light::Directional { direction, color } = directional else {
        panic!("{directional:?}")
    };
    assert!(direction.abs_diff_eq(Vec3::Y, 1e-5), "{direction}");
    assert!((color.x - 2.0 / pi).abs() < 1e-5);
    let Light::Spot(spot) = spot else {
        panic!("{spot:?}")
    };
    assert!(spot.position.abs_diff_eq(Vec3::new(0.0, 5.0, 0.0), 1e-5));
    assert!(spot.direction.abs_diff_eq(Vec3::NEG_Y, 1e-5));
    assert!((spot.cos_angle - 0.4f32.cos()).abs() < 1e-5);
    assert!((spot.color.x - 5.0 / pi).abs() < 1e-5);
    // The camera: at its node, looking down its −z (here −x), +y up, the file's field of view
    // and aspect ratio.
    assert!(scene.camera.eye.abs_diff_eq(Vec3::new(6.0, 0.0, 0.0), 1e-5));
    assert!(
        scene.camera.n.abs_diff_eq(Vec3::X, 1e-5),
        "n = {}",
        scene.camera.n
    );
    assert!(scene.camera.v.abs_diff_eq(Vec3::Y, 1e-5));
    assert!((scene.camera.spec.view_angle - 0.7f32.to_degrees()).abs() < 1e-4);
    assert_eq!(scene.settings.width, 2 * scene.settings.height);
    // Every camera is a bookmarked view, in the file's order.
    let views: Vec<(u8, Vec3)> = scene.views.iter().map(|(k, v)| (k, v.eye)).collect();
    assert_eq!(views.len(), 2, "{views:?}");
    assert_eq!(views[0].0, 1);
    assert!(views[0].1.abs_diff_eq(Vec3::new(6.0, 0.0, 0.0), 1e-5));
    assert_eq!(views[1].0, 2);
    assert!(views[1].1.abs_diff_eq(Vec3::new(0.0, 1.0, 5.0), 1e-5));
    let second = scene.views.get(2).unwrap();
    assert!(
        (second.look_at - second.eye)
            .normalize()
            .abs_diff_eq(Vec3::NEG_Z, 1e-5)
    );
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let image = rendered(scene);
    assert!(image.iter().any(|&b| b > 60), "the lit cube shows");
}

#[test]
fn a_model_without_lights_or_camera_is_framed_and_lit_from_the_eye_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let w = lit_cube(Value::Null, &[], false);
    let (text, bin) = w.gltf("cube.bin");
    let scene = load_written(
        dir.path(),
        &[("cube.gltf", &text), ("cube.bin", &bin)],
        "cube.gltf",
    );
    let [Light::Point { position, .. }] = scene.lights.as_slice() else {
        panic!("{:?}", scene.lights)
    };
    assert_eq!(*position, scene.camera.eye);
    assert!(
        scene.warnings.iter().any(|w| w.ends_with(
            "cube.gltf: a glTF file has no lights or camera: raylab framed the model and lit it \
             with a white point light at the eye"
        )),
        "{:?}",
        scene.warnings
    );
    assert!(
        scene
            .notes
            .iter()
            .any(|n| n.ends_with("cube.gltf: glTF: 0 materials")),
        "{:?}",
        scene.notes
    );
    let image = rendered(scene);
    let lit = image.chunks(3).filter(|p| p[0] > 40).count();
    assert!(
        lit > 96 * 72 / 20,
        "the framed cube fills part of the view: {lit} pixels"
    );
}

#[test]
fn broken_and_refused_files_get_errors_that_say_where_and_what() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    // Bad JSON: at its line and column.
    let bad = b"{\n  \"asset\": {\"version\": \"2.0\"},\n  \"nodes\": [ , ]\n}\n";
    let error = error_of(dir, &[("bad.gltf", bad)], "bad.gltf");
    assert!(
        error.contains("bad.gltf:3:14: not valid glTF JSON"),
        "{error}"
    );

    // A required extension raylab cannot honour, by name.
    let (mut w, _) = two_cubes();
    w.json["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    w.json["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    let error = error_of(dir, &[("draco.glb", &w.glb())], "draco.glb");
    assert!(
        error.contains(
            "the file requires the extension KHR_draco_mesh_compression, which raylab cannot honour"
        ),
        "{error}"
    );

    // Points: refused, naming the mesh and the primitive.
    let mut w = Writer::new();
    let positions = w.vec3s(&ribbon(4));
    let mesh = w.mesh(json!({"POSITION": positions}), None, POINTS, None);
    w.node(json!({"mesh": mesh}), true);
    let error = error_of(dir, &[("points.glb", &w.glb())], "points.glb");
    assert!(
        error.contains("mesh 0 primitive 0 draws points; raylab draws only triangles"),
        "{error}"
    );

    // An accessor reaching past its view, named.
    let (mut w, _) = two_cubes();
    w.json["accessors"][1]["count"] = json!(400);
    let error = error_of(dir, &[("long.glb", &w.glb())], "long.glb");
    assert!(error.contains("accessor 1 (indices)"), "{error}");
    assert!(error.contains("do not fit in buffer view"), "{error}");

    // A node that is its own ancestor.
    let (mut w, _) = two_cubes();
    w.json["nodes"][1]["children"] = json!([2]);
    let error = error_of(dir, &[("loop.glb", &w.glb())], "loop.glb");
    assert!(error.contains("nested more than 64 deep"), "{error}");

    // A GLB cut short: at the byte its header is wrong.
    let (w, _) = two_cubes();
    let mut cut = w.glb();
    cut.truncate(cut.len() - 10);
    let error = error_of(dir, &[("cut.glb", &cut)], "cut.glb");
    assert!(
        error.contains("cut.glb: byte 8: the header gives the file's length"),
        "{error}"
    );

    // A file of another format, named for what it is.
    let ply = b"ply\nformat ascii 1.0\nelement vertex 0\nend_header\n";
    let error = error_of(dir, &[("scan.glb", ply)], "scan.glb");
    assert!(
        error.contains("scan.glb is a PLY file, not glTF"),
        "{error}"
    );

    // A missing buffer file, and a missing model named by a scene file (at its `file` key).
    let (w, _) = two_cubes();
    let (text, _) = w.gltf("gone.bin");
    let error = error_of(dir, &[("nobin.gltf", &text)], "nobin.gltf");
    assert!(error.contains("buffer 0: cannot read"), "{error}");
    let scene = "[[objects]]\ntype = \"gltf\"\nfile = \"gone.glb\"\n";
    let error = error_of(dir, &[("missing.toml", scene.as_bytes())], "missing.toml");
    assert!(
        error.contains("missing.toml:3:8: cannot load glTF file"),
        "{error}"
    );
}

/// A 5 × 4 PNG of distinct colours, so that every wrap and turn of it shows.
fn texture_png() -> Vec<u8> {
    png_of(image::RgbImage::from_fn(5, 4, |x, y| {
        image::Rgb([
            (x * 60) as u8,
            (y * 80) as u8,
            255 - (x * 20 + y * 30) as u8,
        ])
    }))
}

/// The test's PNG with an alpha channel: a ring of clear texels around an opaque middle, and
/// alpha falling off along x.
fn texture_png_with_alpha() -> Vec<u8> {
    png_of(image::RgbaImage::from_fn(5, 4, |x, y| {
        let alpha = if (1..4).contains(&x) && (1..3).contains(&y) {
            255 - x * 50
        } else {
            0
        };
        image::Rgba([(x * 60) as u8, (y * 80) as u8, 200, alpha as u8])
    }))
}

fn png_of(image: impl Into<image::DynamicImage>) -> Vec<u8> {
    let mut png = std::io::Cursor::new(Vec::new());
    image
        .into()
        .write_to(&mut png, image::ImageFormat::Png)
        .unwrap();
    png.into_inner()
}

/// A quad facing +z, corners `(±1, ±1, 0)`, with texture coordinates in set 1 running from −1
/// to 2 (so that the image wraps), in a material whose base colour texture is the PNG with
/// `wrap` (glTF's codes) and, when given, `transform`; its base colour factor `factor`; with
/// COLOR_0 `colour` when given.
fn textured_quad(
    wrap: [u32; 2],
    transform: Option<Value>,
    factor: [f32; 3],
    colour: Option<[f32; 3]>,
) -> Writer {
    let mut w = Writer::new();
    let corners = [
        Vec3::new(-1.0, -1.0, 0.0),
        Vec3::new(1.0, -1.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(-1.0, 1.0, 0.0),
    ];
    let positions = w.vec3s(&corners);
    let uvs: Vec<u8> = QUAD_UVS
        .iter()
        .flatten()
        .flat_map(|c: &f32| c.to_le_bytes())
        .collect();
    let uv_view = w.view(&uvs, None);
    let uv_accessor = w.push(
        "accessors",
        json!({"bufferView": uv_view, "componentType": F32, "count": 4, "type": "VEC2"}),
    );
    let png = w.view(&texture_png(), None);
    w.json["images"] = json!([{"bufferView": png, "mimeType": "image/png"}]);
    w.json["samplers"] = json!([{"wrapS": wrap[0], "wrapT": wrap[1]}]);
    w.json["textures"] = json!([{"source": 0, "sampler": 0}]);
    let mut info = json!({"index": 0, "texCoord": 0});
    if let Some(transform) = transform {
        info["extensions"] = json!({"KHR_texture_transform": transform});
        w.json["extensionsUsed"] = json!(["KHR_texture_transform"]);
    }
    w.json["materials"] = json!([{"pbrMetallicRoughness": {
        "baseColorTexture": info, "baseColorFactor": [factor[0], factor[1], factor[2], 1.0],
        "metallicFactor": 0, "roughnessFactor": 1}}]);
    let mut attributes = json!({"POSITION": positions, "TEXCOORD_1": uv_accessor});
    if let Some(c) = colour {
        let bytes: Vec<u8> = (0..4).flat_map(|_| c).flat_map(f32::to_le_bytes).collect();
        let view = w.view(&bytes, None);
        let accessor = w.push(
            "accessors",
            json!({"bufferView": view, "componentType": F32, "count": 4, "type": "VEC3"}),
        );
        attributes["COLOR_0"] = json!(accessor);
    }
    let indices = w.indices(&[0, 1, 2, 0, 2, 3], U8);
    let mesh = w.mesh(attributes, Some(indices), TRIANGLES, Some(0));
    w.node(json!({"mesh": mesh}), true);
    w
}

/// The quad's texture coordinates, in glTF's texture space.
const QUAD_UVS: [[f32; 2]; 4] = [[-1.0, 2.0], [2.0, 2.0], [2.0, -1.0], [-1.0, -1.0]];

/// A scene file facing the quad of the glTF file `file` (in its own materials), lit from the
/// front.
fn facing(file: &str) -> String {
    format!(
        "[render]\nambient = [0, 0, 0]\n[camera]\neye = [0, 0, 3.2]\nlook_at = [0, 0, 0]\n\
         view_angle = 40\n[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 1]\n\
         [[objects]]\ntype = \"gltf\"\nfile = \"{file}\"\n"
    )
}

/// The image of the quad written in a scene file facing it as [`facing`] does, with texture
/// coordinates `uvs`, in a material of the keys `material` that may name the texture `image`
/// (the PNG `png`, wrapping as `wrap` says).
fn quad_by_hand(dir: &Path, png: &[u8], wrap: &str, material: &str, uvs: &[String]) -> Vec<u8> {
    std::fs::write(dir.join("texture.png"), png).unwrap();
    let text = format!(
        "[render]\nambient = [0, 0, 0]\n[camera]\neye = [0, 0, 3.2]\nlook_at = [0, 0, 0]\n\
         view_angle = 40\n[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 1]\n\
         [textures.image]\ntype = \"image\"\nfile = \"texture.png\"\nwrap = \"{wrap}\"\n\
         [materials.quad]\n{material}\
         [[objects]]\ntype = \"mesh\"\nmaterial = \"quad\"\n\
         positions = [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]\nfaces = [[0, 1, 2], [0, 2, 3]]\n\
         uvs = [{}]\n",
        uvs.join(", ")
    );
    rendered(load_written(
        dir,
        &[("by_hand.toml", text.as_bytes())],
        "by_hand.toml",
    ))
}

#[test]
fn a_base_colour_texture_wraps_turns_and_is_tinted_as_gltf_says() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    const MIRRORED_REPEAT: u32 = 33648;
    const REPEAT: u32 = 10497;
    const CLAMP_TO_EDGE: u32 = 33071;
    let transform =
        json!({"offset": [0.2, -0.1], "rotation": 0.5, "scale": [1.5, 0.75], "texCoord": 1});
    let w = textured_quad([MIRRORED_REPEAT; 2], Some(transform), [1.0; 3], None);
    let scene = facing("quad.glb");
    let from_gltf = rendered(load_written(
        dir,
        &[("quad.glb", &w.glb()), ("quad.toml", scene.as_bytes())],
        "quad.toml",
    ));

    // The same quad in a scene file: the texture transform applied and the texture space
    // turned upright by the test, the image mirrored along both axes.
    let (c, s) = (0.5f32.cos(), 0.5f32.sin());
    let uvs: Vec<String> = QUAD_UVS
        .iter()
        .map(|&[u, v]| {
            let (u, v) = (1.5 * u, 0.75 * v);
            let (u, v) = (0.2 + c * u - s * v, -0.1 + s * u + c * v);
            format!("[{u}, {}]", 1.0 - v)
        })
        .collect();
    let material = "texture = \"image\"\nambient = 0.1\ndiffuse = 1\nspecular = 0\nshininess = 1\n";
    let by_hand = quad_by_hand(dir, &texture_png(), "mirror", material, &uvs);
    let differing = pixels_apart(&from_gltf, &by_hand);
    // The test turns the coordinates with its own roundings: a texel edge may move a pixel.
    assert!(
        differing <= 30,
        "{differing} pixels differ from the scene file's texture"
    );
    let distinct: std::collections::HashSet<&[u8]> = from_gltf.chunks(3).collect();
    assert!(
        distinct.len() > 30,
        "the texture shows: {} colours",
        distinct.len()
    );

    // Each axis wraps as its sampler says.
    let w = textured_quad([REPEAT, CLAMP_TO_EDGE], None, [1.0; 3], None);
    let scene = load_written(
        dir,
        &[
            ("axes.glb", &w.glb()),
            ("axes.toml", facing("axes.glb").as_bytes()),
        ],
        "axes.toml",
    );
    let [raylab::texture::Texture::Image { wrap, .. }] = scene.textures.as_slice() else {
        panic!("one image texture")
    };
    assert_eq!(
        *wrap,
        [raylab::texture::Wrap::Repeat, raylab::texture::Wrap::Clamp]
    );

    // The base colour factor multiplies the texture as COLOR_0 does.
    let tint = [0.5, 1.0, 0.25];
    let images: Vec<Vec<u8>> = [
        textured_quad([REPEAT; 2], None, tint, None),
        textured_quad([REPEAT; 2], None, [1.0; 3], Some(tint)),
        textured_quad([REPEAT; 2], None, [1.0; 3], None),
    ]
    .iter()
    .enumerate()
    .map(|(k, w)| {
        let (file, scene) = (format!("tint{k}.glb"), format!("tint{k}.toml"));
        rendered(load_written(
            dir,
            &[(&file, &w.glb()), (&scene, facing(&file).as_bytes())],
            &scene,
        ))
    })
    .collect();
    assert!(
        images[0] == images[1],
        "the factor does not multiply as a vertex colour"
    );
    assert!(
        pixels_apart(&images[0], &images[2]) > 96 * 72 / 4,
        "the factor is not applied"
    );
}

#[test]
fn an_emissive_texture_glows_in_its_colours_as_a_scene_files_emission_texture_does() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    const CLAMP_TO_EDGE: u32 = 33071;
    let mut w = textured_quad([CLAMP_TO_EDGE; 2], None, [1.0; 3], None);
    // A black surface whose emissive texture is the PNG, in texture coordinate set 1.
    w.json["materials"] = json!([{
        "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0,
                                 "roughnessFactor": 1},
        "emissiveTexture": {"index": 0, "texCoord": 1}, "emissiveFactor": [1, 0.5, 1]}]);
    let from_gltf = rendered(load_written(
        dir,
        &[
            ("glow.glb", &w.glb()),
            ("glow.toml", facing("glow.glb").as_bytes()),
        ],
        "glow.toml",
    ));

    // The same quad in a scene file, its emission textured by the same image.
    let uvs: Vec<String> = QUAD_UVS
        .iter()
        .map(|&[u, v]| format!("[{u}, {}]", 1.0 - v))
        .collect();
    let material = "color = [0, 0, 0]\nemission = [1, 0.5, 1]\nemission_texture = \"image\"\n\
                    ambient = 0.1\ndiffuse = 1\nspecular = 0\nshininess = 1\n";
    let by_hand = quad_by_hand(dir, &texture_png(), "clamp", material, &uvs);
    assert!(
        from_gltf == by_hand,
        "the glTF glow differs from the scene file's"
    );
    let distinct: std::collections::HashSet<&[u8]> = from_gltf.chunks(3).collect();
    assert!(
        distinct.len() >= 15,
        "the texture glows: {} colours",
        distinct.len()
    );
}

#[test]
fn alpha_mode_mask_cuts_the_quad_where_a_scene_files_alpha_cutoff_does() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    const CLAMP_TO_EDGE: u32 = 33071;
    let glb = |mode: &str| {
        let mut w = textured_quad([CLAMP_TO_EDGE; 2], None, [1.0; 3], None);
        let png = w.view(&texture_png_with_alpha(), None);
        w.json["images"][0]["bufferView"] = json!(png);
        // The base colour's alpha is the factor's 0.8 times the texture's, cut at 0.4: where
        // the texture's alpha is below 0.5.
        w.json["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = json!([1, 1, 1, 0.8]);
        w.json["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = json!(1);
        w.json["materials"][0]["alphaMode"] = json!(mode);
        w.json["materials"][0]["alphaCutoff"] = json!(0.4);
        w.glb()
    };
    let image = |mode: &str| {
        let name = format!("{mode}.glb");
        let scene = facing(&name);
        let files = [
            (name.as_str(), &glb(mode)[..]),
            ("quad.toml", scene.as_bytes()),
        ];
        rendered(load_written(dir, &files, "quad.toml"))
    };
    let (masked, opaque) = (image("MASK"), image("OPAQUE"));

    let uvs: Vec<String> = QUAD_UVS
        .iter()
        .map(|&[u, v]| format!("[{u}, {}]", 1.0 - v))
        .collect();
    let material = "texture = \"image\"\nalpha_cutoff = 0.5\nambient = 0.1\ndiffuse = 1\n\
                    specular = 0\nshininess = 1\n";
    let by_hand = quad_by_hand(dir, &texture_png_with_alpha(), "clamp", material, &uvs);
    assert!(
        masked == by_hand,
        "the glTF cut-out differs from the scene file's"
    );
    let cut = pixels_apart(&masked, &opaque);
    assert!(
        cut > 96 * 72 / 10,
        "only {cut} pixels are cut away from the opaque quad"
    );

    // BLEND is drawn as MASK at 0.5, and the report says so.
    let blend = load_written(dir, &[("blend.glb", &glb("BLEND"))], "blend.glb");
    let report = blend.notes.join("\n");
    assert!(
        report.contains("alphaMode BLEND (1) drawn as MASK at 0.5"),
        "{report}"
    );
    assert_eq!(blend.materials.last().unwrap().alpha_cutoff, Some(0.625));
}
