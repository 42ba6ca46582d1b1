//! OBJ files and relative paths: normals, texture coordinates and materials read from OBJ and
//! MTL files (with the images their `map_Kd` lines name), their odd encodings, their warnings and
//! errors at a line, and every path resolved against the scene file's folder.

use std::path::Path;

use raylab::bvh::Bvh;
use raylab::color::Color;
use raylab::formats::SceneError;
use raylab::formats::toml::{DEFAULT_MATERIAL, load_scene, parse_scene};
use raylab::progressive::render_image;
use raylab::scene::Scene;
use raylab::whitted::Tracer;

use crate::harness::{assets, parse, scenes_dir};

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

/// A 64 × 64 image of four colours: red top left, green top right, blue bottom left, white
/// bottom right.
fn quadrants_png() -> Vec<u8> {
    let image = image::RgbImage::from_fn(64, 64, |x, y| {
        image::Rgb(match (x < 32, y < 32) {
            (true, true) => [255, 0, 0],
            (false, true) => [0, 255, 0],
            (true, false) => [0, 0, 255],
            (false, false) => [255, 255, 255],
        })
    });
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    png
}

#[test]
fn an_mtl_map_kd_image_colours_the_obj_where_its_texture_coordinates_say() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("maps")).unwrap();
    std::fs::write(dir.path().join("maps/quadrants.png"), quadrants_png()).unwrap();
    // Texture coordinates as OBJ has them (v up), an option before the file name, and the
    // folder written with Windows' backslash, as exporters on Windows write it.
    let obj = "mtllib quad.mtl\nusemtl paint\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
    let mtl = "newmtl paint\nKd 0.2 0.2 0.2\nmap_Kd -s 1 1 1 maps\\quadrants.png\n";
    std::fs::write(dir.path().join("quad.obj"), obj).unwrap();
    std::fs::write(dir.path().join("quad.mtl"), mtl).unwrap();
    let scene = "[render]\nwidth = 64\nheight = 64\nambient = [0.2, 0.2, 0.2]\n\n\
                 [camera]\neye = [0.5, 0.5, 2]\nlook_at = [0.5, 0.5, 0]\nup = [0, 1, 0]\n\
                 view_angle = 20\n\n[[lights]]\ntype = \"point\"\nposition = [0.5, 0.5, 2]\n\
                 color = [1, 1, 1]\n\n[[objects]]\ntype = \"obj\"\nfile = \"quad.obj\"\n";
    let scene = parse_scene(scene, Path::new("test.toml"), dir.path()).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let material = &scene.materials[scene.geometry.meshes[0].material as usize];
    assert!(material.texture.is_some(), "{material:?}");
    let bvh = Bvh::build(&scene.geometry);
    let image = render_image(&Tracer::new(&scene, &bvh)).0;
    let at = |x: usize, y: usize| image[y * 64 + x].to_array();
    let dominant = |[r, g, b]: [f32; 3], channel: usize| {
        let c = [r, g, b];
        (0..3).all(|other| other == channel || c[channel] > 4.0 * c[other])
    };
    assert!(dominant(at(16, 16), 0), "top left {:?}", at(16, 16));
    assert!(dominant(at(48, 16), 1), "top right {:?}", at(48, 16));
    assert!(dominant(at(16, 48), 2), "bottom left {:?}", at(16, 48));
    let [r, g, b] = at(48, 48);
    assert!(
        r > 0.3 && (r - g).abs() < 0.01 && (r - b).abs() < 0.01,
        "bottom right {r} {g} {b}"
    );

    // An image that is not there is a warning; the material keeps its `Kd`.
    std::fs::write(
        dir.path().join("quad.mtl"),
        "newmtl paint\nKd 0.2 0.2 0.2\nmap_Kd gone.png\n",
    )
    .unwrap();
    let scene = "[[objects]]\ntype = \"obj\"\nfile = \"quad.obj\"\n";
    let scene = parse_scene(scene, Path::new("test.toml"), dir.path()).unwrap();
    let said = warning(&scene, "map_Kd gone.png");
    assert!(
        said.contains("material `paint`") && said.contains("keeps its `Kd` colour"),
        "{said}"
    );
    let material = &scene.materials[scene.geometry.meshes[0].material as usize];
    assert_eq!(
        (material.texture, material.color),
        (None, Color::new(0.2, 0.2, 0.2))
    );
}
