//! The models people own, as raylab reads them: PLY in ASCII, binary little endian and binary
//! big endian, against the same mesh written as OBJ and as a scene file's own `type = "mesh"`;
//! quads and n-gons; vertex colours. Every file is written by the test itself, not by a reader
//! under test.

use std::path::Path;

use glam::{Vec2, Vec3};
use raylab::camera::PIXEL_CENTRE;
use raylab::color::{Color, srgb_to_linear, to_srgb8};
use raylab::formats::load_any;
use raylab::material::Material;
use raylab::progressive::render_image;
use raylab::render::assemble;
use raylab::scene::Scene;

/// A mesh as the test writes it: polygons of any number of corners, one colour per vertex.
struct Model {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    colors: Vec<[u8; 3]>,
    polygons: Vec<Vec<u32>>,
}

/// A 16-sided prism of quads, its caps 16-gons with their own vertices, and a pentagon beside
/// it; each vertex with a normal, texture coordinates and a colour.
fn lantern() -> Model {
    const SIDES: u32 = 16;
    let mut model = Model {
        positions: Vec::new(),
        normals: Vec::new(),
        uvs: Vec::new(),
        colors: Vec::new(),
        polygons: Vec::new(),
    };
    let vertex = |model: &mut Model, p: Vec3, n: Vec3, k: u32| {
        model.positions.push(p);
        model.normals.push(n);
        model.uvs.push(Vec2::new(k as f32 / SIDES as f32, p.y));
        model
            .colors
            .push([(k * 15) as u8, 200 - (k * 9) as u8, 40 + (k * 13) as u8]);
        model.positions.len() as u32 - 1
    };
    // The side, then each cap: rings of SIDES vertices.
    for (y, radius) in [(0.0, 1.0), (1.5, 0.6)] {
        for k in 0..SIDES {
            let angle = std::f32::consts::TAU * k as f32 / SIDES as f32;
            let out = Vec3::new(angle.cos(), 0.25, angle.sin()).normalize();
            let p = Vec3::new(radius * angle.cos(), y, radius * angle.sin());
            vertex(&mut model, p, out, k);
        }
    }
    for k in 0..SIDES {
        let next = (k + 1) % SIDES;
        model.polygons.push(vec![k, SIDES + k, SIDES + next, next]);
    }
    for (y, radius, normal) in [(0.0, 1.0, -Vec3::Y), (1.5, 0.6, Vec3::Y)] {
        let cap: Vec<u32> = (0..SIDES)
            .map(|k| {
                let angle = std::f32::consts::TAU * k as f32 / SIDES as f32;
                let p = Vec3::new(radius * angle.cos(), y, radius * angle.sin());
                vertex(&mut model, p, normal, k)
            })
            .collect();
        // Counter-clockwise seen from outside.
        model.polygons.push(if normal.y > 0.0 {
            cap.into_iter().rev().collect()
        } else {
            cap
        });
    }
    let pentagon: Vec<u32> = (0..5)
        .map(|k| {
            let angle = std::f32::consts::TAU * k as f32 / 5.0;
            let p = Vec3::new(2.2 + 0.6 * angle.cos(), 0.8 + 0.6 * angle.sin(), 0.3);
            vertex(&mut model, p, Vec3::Z, k)
        })
        .collect();
    model.polygons.push(pentagon);
    model
}

/// The PLY encodings.
#[derive(Clone, Copy, Debug)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

/// `model` as a PLY file in `encoding`, its colours written when `colors`.
fn ply(model: &Model, encoding: Encoding, colors: bool) -> Vec<u8> {
    let format = match encoding {
        Encoding::Ascii => "ascii",
        Encoding::Little => "binary_little_endian",
        Encoding::Big => "binary_big_endian",
    };
    let mut header = format!(
        "ply\nformat {format} 1.0\ncomment written by raylab's tests\nelement vertex {}\n",
        model.positions.len()
    );
    for name in ["x", "y", "z", "nx", "ny", "nz", "s", "t"] {
        header += &format!("property float {name}\n");
    }
    if colors {
        header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    }
    header += &format!(
        "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        model.polygons.len()
    );
    let mut bytes = header.into_bytes();
    let floats = |v: usize| -> Vec<f32> {
        let (p, n, uv) = (model.positions[v], model.normals[v], model.uvs[v]);
        vec![p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y]
    };
    let number = |bytes: &mut Vec<u8>, f: f32| match encoding {
        Encoding::Ascii => bytes.extend(format!("{f} ").into_bytes()),
        Encoding::Little => bytes.extend(f.to_le_bytes()),
        Encoding::Big => bytes.extend(f.to_be_bytes()),
    };
    let integer = |bytes: &mut Vec<u8>, i: i32| match encoding {
        Encoding::Ascii => bytes.extend(format!("{i} ").into_bytes()),
        Encoding::Little => bytes.extend(i.to_le_bytes()),
        Encoding::Big => bytes.extend(i.to_be_bytes()),
    };
    let byte = |bytes: &mut Vec<u8>, b: u8| match encoding {
        Encoding::Ascii => bytes.extend(format!("{b} ").into_bytes()),
        _ => bytes.push(b),
    };
    let end_line = |bytes: &mut Vec<u8>| {
        if let Encoding::Ascii = encoding {
            bytes.push(b'\n');
        }
    };
    for v in 0..model.positions.len() {
        floats(v).into_iter().for_each(|f| number(&mut bytes, f));
        if colors {
            model.colors[v]
                .into_iter()
                .for_each(|b| byte(&mut bytes, b));
        }
        end_line(&mut bytes);
    }
    for polygon in &model.polygons {
        byte(&mut bytes, polygon.len() as u8);
        polygon.iter().for_each(|&v| integer(&mut bytes, v as i32));
        end_line(&mut bytes);
    }
    bytes
}

/// `model` as an OBJ file: positions, normals and texture coordinates, one index for all three.
fn obj(model: &Model) -> String {
    let mut text = String::from("# written by raylab's tests\n");
    for v in 0..model.positions.len() {
        let (p, n, uv) = (model.positions[v], model.normals[v], model.uvs[v]);
        text += &format!(
            "v {} {} {}\nvn {} {} {}\nvt {} {}\n",
            p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y
        );
    }
    for polygon in &model.polygons {
        let corners: Vec<String> = polygon
            .iter()
            .map(|v| format!("{0}/{0}/{0}", v + 1))
            .collect();
        text += &format!("f {}\n", corners.join(" "));
    }
    text
}

/// `model` as a scene file's `type = "mesh"` object, each polygon cut by the test into a fan of
/// triangles from its first corner.
fn toml_mesh(model: &Model) -> String {
    let list = |items: Vec<String>| format!("[{}]", items.join(", "));
    let vector = |v: Vec3| format!("[{}, {}, {}]", v.x, v.y, v.z);
    let faces = model.polygons.iter().flat_map(|polygon| {
        (1..polygon.len() - 1)
            .map(|k| format!("[{}, {}, {}]", polygon[0], polygon[k], polygon[k + 1]))
    });
    format!(
        "type = \"mesh\"\npositions = {}\nnormals = {}\nuvs = {}\nfaces = {}\n",
        list(model.positions.iter().map(|&p| vector(p)).collect()),
        list(model.normals.iter().map(|&n| vector(n)).collect()),
        list(
            model
                .uvs
                .iter()
                .map(|uv| format!("[{}, {}]", uv.x, uv.y))
                .collect()
        ),
        list(faces.collect()),
    )
}

/// A scene file around `object` (the keys of one `[[objects]]` table): a camera, two lights
/// and a checkered texture on the object, so that normals and texture coordinates show.
fn scene_around(object: &str) -> String {
    format!(
        "[camera]\neye = [1, 3, 5]\nlook_at = [0.6, 0.6, 0]\nview_angle = 45\n\
         [[lights]]\ntype = \"point\"\nposition = [3, 5, 4]\n\
         [[lights]]\ntype = \"directional\"\ndirection = [-1, 1, 2]\ncolor = [0.4, 0.4, 0.4]\n\
         [textures.checks]\ntype = \"checker_uv\"\n\
         [materials.model]\ntexture = \"checks\"\nspecular = 0.5\nshininess = 40\n\
         [[objects]]\nmaterial = \"model\"\ntransform = [{{ rotate = {{ axis = [0, 1, 0], degrees = 20 }} }}]\n{object}"
    )
}

/// The 8-bit image of `scene` at 96 × 72.
pub fn rendered(mut scene: Scene) -> Vec<u8> {
    scene.settings.width = 96;
    scene.settings.height = 72;
    let assembled = assemble(scene).unwrap();
    to_srgb8(&render_image(&assembled.tracer()).0)
}

/// Writes `files` into `dir` and loads the scene file `name` among them.
pub fn load_written(dir: &Path, files: &[(&str, &[u8])], name: &str) -> Scene {
    for (file, bytes) in files {
        std::fs::write(dir.join(file), bytes).unwrap();
    }
    let path = dir.join(name);
    load_any(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_ply_in_ascii_and_in_either_binary_renders_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let model = lantern();
    let scene = scene_around("type = \"ply\"\nfile = \"lantern.ply\"\n");
    let images: Vec<Vec<u8>> = [Encoding::Ascii, Encoding::Little, Encoding::Big]
        .into_iter()
        .map(|encoding| {
            let ply = ply(&model, encoding, true);
            let files = [("lantern.ply", &ply[..]), ("scene.toml", scene.as_bytes())];
            rendered(load_written(dir.path(), &files, "scene.toml"))
        })
        .collect();
    let background = images[0][..3].to_vec();
    let covered = images[0].chunks(3).filter(|p| *p != background).count();
    assert!(covered > 96 * 72 / 10, "the model covers {covered} pixels");
    assert!(
        images[1] == images[0],
        "binary little endian differs from ASCII"
    );
    assert!(
        images[2] == images[0],
        "binary big endian differs from ASCII"
    );
}

#[test]
fn quads_and_n_gons_from_ply_and_obj_render_as_the_triangles_the_test_cuts_them_into() {
    let dir = tempfile::tempdir().unwrap();
    let model = lantern();
    let ply = ply(&model, Encoding::Little, false);
    let obj = obj(&model);
    let ply_scene = scene_around("type = \"ply\"\nfile = \"lantern.ply\"\n");
    let obj_scene = scene_around("type = \"obj\"\nfile = \"lantern.obj\"\n");
    let mesh_scene = scene_around(&toml_mesh(&model));
    let files = [
        ("lantern.ply", &ply[..]),
        ("lantern.obj", obj.as_bytes()),
        ("ply.toml", ply_scene.as_bytes()),
        ("obj.toml", obj_scene.as_bytes()),
        ("mesh.toml", mesh_scene.as_bytes()),
    ];
    let from_ply = rendered(load_written(dir.path(), &files, "ply.toml"));
    let from_obj = rendered(load_written(dir.path(), &files, "obj.toml"));
    let from_toml = rendered(load_written(dir.path(), &files, "mesh.toml"));
    let background = from_toml[..3].to_vec();
    let covered = from_toml.chunks(3).filter(|p| *p != background).count();
    assert!(covered > 96 * 72 / 10, "the model covers {covered} pixels");
    assert!(
        from_ply == from_toml,
        "the PLY's triangles differ from the fans"
    );
    assert!(
        from_obj == from_toml,
        "the OBJ's triangles differ from the fans"
    );
}

#[test]
fn a_ply_opened_on_its_own_is_framed_and_lit_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let ply = ply(&lantern(), Encoding::Ascii, true);
    let scene = load_written(dir.path(), &[("lantern.PLY", &ply)], "lantern.PLY");
    assert_eq!(scene.geometry.meshes.len(), 1);
    assert_eq!(scene.lights.len(), 1);
    assert!(
        scene
            .warnings
            .iter()
            .any(|w| w.contains("a PLY file has no lights or camera")),
        "{:?}",
        scene.warnings
    );
    let image = rendered(scene);
    let background = image[..3].to_vec();
    let covered = image.chunks(3).filter(|p| *p != background).count();
    assert!(covered > 96 * 72 / 10, "the model covers {covered} pixels");
}

/// A square in the plane z = 0 from −1 to 1, its left corners `left` and its right corners
/// `right` (8-bit sRGB), as an ASCII PLY file.
fn square(left: [u8; 3], right: [u8; 3]) -> Vec<u8> {
    let corners = [(-1, -1, left), (1, -1, right), (1, 1, right), (-1, 1, left)];
    let mut text = String::from(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n",
    );
    for (x, y, [r, g, b]) in corners {
        text += &format!("{x} {y} 0 {r} {g} {b}\n");
    }
    text += "4 0 1 2 3\n";
    text.into_bytes()
}

/// The square of [`square`] opened on its own, seen head on from z = 3 and lit from there.
fn square_scene(dir: &Path, left: [u8; 3], right: [u8; 3]) -> Scene {
    let mut scene = load_written(dir, &[("square.ply", &square(left, right))], "square.ply");
    scene.camera = raylab::camera::Camera::new(raylab::camera::CameraSpec {
        eye: Vec3::new(0.0, 0.0, 3.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        view_angle: 45.0,
        near: 1.0,
    })
    .unwrap();
    scene.lights = vec![raylab::light::Light::Point {
        position: scene.camera.eye,
        color: Color::ONE,
    }];
    scene.settings.width = 64;
    scene.settings.height = 48;
    scene
}

#[test]
fn vertex_colours_multiply_the_surface_colour_as_they_are_interpolated() {
    let dir = tempfile::tempdir().unwrap();
    // One colour at every vertex is the material's colour times it.
    let orange = [230, 120, 40];
    let coloured = square_scene(dir.path(), orange, orange);
    let mut plain = square_scene(dir.path(), [255; 3], [255; 3]);
    plain.geometry.meshes[0].colors.clear();
    let linear = Color::from(orange.map(|c| srgb_to_linear(c as f32 / 255.0)));
    plain.materials[0].color = Material::default().color * linear;
    let shaded = |scene: Scene| {
        let assembled = assemble(scene).unwrap();
        render_image(&assembled.tracer()).0
    };
    // Equal but for rounding: the colour is interpolated from three equal corners.
    let (coloured, plain) = (shaded(coloured), shaded(plain));
    let worst = coloured
        .iter()
        .zip(&plain)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .fold(0.0, f32::max);
    assert!(worst < 1e-5, "the images differ by up to {worst}");
    assert!(coloured[24 * 64 + 32].x > 0.2, "the middle is lit");

    // Colours that differ from left to right: each pixel is the white square's times the
    // colour interpolated at the point its eye ray hits.
    let (left, right) = ([255, 0, 0], [0, 128, 255]);
    let varied = square_scene(dir.path(), left, right);
    let white = square_scene(dir.path(), [255; 3], [255; 3]);
    let camera = varied.camera;
    let (width, height) = (varied.settings.width, varied.settings.height);
    let (varied, white) = (shaded(varied), shaded(white));
    let linear = |c: [u8; 3]| Color::from(c.map(|c| srgb_to_linear(c as f32 / 255.0)));
    let (left, right) = (linear(left), linear(right));
    let mut checked = 0;
    for y in 0..height {
        for x in 0..width {
            let ray = camera.eye_ray((x, y), PIXEL_CENTRE, (width, height));
            let hit = ray.origin + ray.dir * (-ray.origin.z / ray.dir.z);
            if hit.x.abs() > 0.95 || hit.y.abs() > 0.95 {
                continue;
            }
            let share = (hit.x + 1.0) / 2.0;
            let expected = left * (1.0 - share) + right * share;
            let i = (y * width + x) as usize;
            let got = varied[i] / white[i].max(Color::splat(1e-6));
            assert!(
                (got - expected).abs().max_element() < 1e-3,
                "pixel ({x}, {y}) at x = {}: {got} for {expected}",
                hit.x
            );
            checked += 1;
        }
    }
    assert!(checked > 600, "{checked} pixels checked");
}

#[test]
fn a_broken_ply_is_refused_at_its_line_column_or_byte() {
    let dir = tempfile::tempdir().unwrap();
    let text = String::from_utf8(square([1; 3], [2; 3])).unwrap();
    let bad_text = text.replace("1 -1 0 2 2 2", "1 -1 zero 2 2 2");
    std::fs::write(dir.path().join("bad.ply"), &bad_text).unwrap();
    let error = load_any(dir.path().join("bad.ply").to_str().unwrap()).unwrap_err();
    let line = 1 + bad_text.lines().position(|l| l.contains("zero")).unwrap();
    assert!(
        error
            .to_string()
            .contains(&format!("bad.ply:{line}:6: `zero` is not a finite number")),
        "{error}"
    );
    let mut binary = ply(&lantern(), Encoding::Big, true);
    let header = binary
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    binary.truncate(binary.len() - 7);
    std::fs::write(dir.path().join("cut.ply"), &binary).unwrap();
    let scene = "[[objects]]\ntype = \"ply\"\nfile = \"cut.ply\"\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let error = load_any(dir.path().join("scene.toml").to_str().unwrap()).unwrap_err();
    let message = error.to_string();
    assert!(message.contains("cut.ply: byte "), "{message}");
    let byte: usize = message
        .split("byte ")
        .nth(1)
        .unwrap()
        .split(':')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!(byte > header && byte <= binary.len(), "{message}");
    assert!(
        message.contains(&format!("face {}", lantern().polygons.len() - 1)),
        "{message}"
    );
    // A missing file is an error at the scene file's `file` key.
    let scene = "[[objects]]\ntype = \"ply\"\nfile = \"gone.ply\"\n";
    std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
    let error = load_any(dir.path().join("scene.toml").to_str().unwrap()).unwrap_err();
    assert!(
        error
            .to_string()
            .contains("scene.toml:3:8: cannot load PLY file"),
        "{error}"
    );
}
