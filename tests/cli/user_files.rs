//! The files a user brings, as they come: a model given as the wrong kind of mesh, an OBJ file
//! opened on its own, a scene without a camera, a binary file, special files. Each either
//! renders what a person expects or stops at once with a message that names the file and what
//! it is, printed as text a terminal shows.

use std::path::Path;
use std::time::Duration;

use raylab::srgb_image::SrgbImage;

use crate::common::run::{Measured, raylab, raylab_measured, stderr};

/// A tetrahedron 0.15 units across, far from the origin: a model that the default camera would
/// show as a speck, or not at all.
const SMALL_TETRAHEDRON: &str = "\
v 10.0 5.0 -3.0
v 10.15 5.0 -3.0
v 10.075 5.0 -2.85
v 10.075 5.13 -2.925
f 1 2 3
f 1 2 4
f 2 3 4
f 3 1 4
";

/// The share of `image`'s pixels that are not its corner's colour (the background's).
fn covered_share(image: &SrgbImage) -> f64 {
    let background = image.at(0, 0);
    let covered = image.pixels.iter().filter(|&&p| p != background).count();
    covered as f64 / image.pixels.len() as f64
}

/// Whether `text` holds a control character other than a line break or a tab: bytes a terminal
/// would act on.
fn has_control_characters(text: &str) -> bool {
    text.chars()
        .any(|c| c.is_control() && c != '\n' && c != '\t')
}

#[test]
fn a_mesh_of_another_kind_is_named_for_what_it_is() {
    let dir = tempfile::tempdir().unwrap();
    let files: [(&str, &[u8], &str); 5] = [
        (
            "bunny.ply",
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n",
            "bunny.ply is a PLY file, not OBJ",
        ),
        (
            "duck.gltf",
            b"{\n  \"asset\": { \"version\": \"2.0\" },\n  \"scenes\": []\n}\n",
            "duck.gltf is a glTF file, not OBJ",
        ),
        (
            "duck.glb",
            b"glTF\x02\0\0\0\x10\0\0\0",
            "duck.glb is a binary glTF file, not OBJ",
        ),
        ("empty.obj", b"", "no faces"),
        ("points.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n", "3 vertices"),
    ];
    for (name, bytes, expected) in files {
        std::fs::write(dir.path().join(name), bytes).unwrap();
        let scene = format!("[[objects]]\ntype = \"obj\"\nfile = \"{name}\"\n");
        std::fs::write(dir.path().join("scene.toml"), scene).unwrap();
        let out = raylab(
            &["render", "scene.toml", "-o", "x.png", "--size", "8"],
            dir.path(),
        );
        assert_eq!(out.status.code(), Some(1), "{name}: {}", stderr(&out));
        assert!(
            stderr(&out).contains("scene.toml:3:8: "),
            "{name}: {}",
            stderr(&out)
        );
        assert!(stderr(&out).contains(expected), "{name}: {}", stderr(&out));
        assert!(
            !dir.path().join("x.png").exists(),
            "{name}: no image for a broken scene"
        );
    }
}

#[test]
fn an_obj_file_opens_as_a_scene_framed_and_lit() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tiny.obj"), SMALL_TETRAHEDRON).unwrap();
    let out = raylab(
        &["render", "tiny.obj", "-o", "tiny.png", "--size", "64"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("point light at the eye"),
        "{}",
        stderr(&out)
    );
    let image = SrgbImage::read(&dir.path().join("tiny.png")).unwrap();
    let covered = covered_share(&image);
    assert!(
        covered > 0.1,
        "the model fills {:.1} % of the image",
        100.0 * covered
    );
    let lit = image.pixels.iter().any(|p| p.iter().any(|&l| l > 100));
    assert!(lit, "the model is lit");
    // `inspect` opens it the same way.
    let out = raylab(
        &["inspect", "tiny.obj", "--pixel", "32,32", "--size", "64"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

#[test]
fn a_scene_without_a_camera_frames_its_objects() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "\
[[lights]]
type = \"point\"
position = [10, 10, 10]

[[objects]]
type = \"sphere\"
center = [3, 2, 1]
radius = 0.075
";
    std::fs::write(dir.path().join("speck.toml"), scene).unwrap();
    let out = raylab(
        &["render", "speck.toml", "-o", "speck.png", "--size", "64"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let image = SrgbImage::read(&dir.path().join("speck.png")).unwrap();
    let covered = covered_share(&image);
    assert!(
        covered > 0.1,
        "the sphere fills {:.1} % of the image",
        100.0 * covered
    );
}

#[test]
fn a_binary_file_is_named_and_its_bytes_are_never_printed() {
    let dir = tempfile::tempdir().unwrap();
    let mut ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 2\nend_header\n".to_vec();
    ply.extend([
        0x1b, b'[', b'2', b'J', 0, 7, 0x9b, 0xff, 0x1b, b']', b'0', b';',
    ]);
    std::fs::write(dir.path().join("igea.ply"), &ply).unwrap();
    let out = raylab(&["render", "igea.ply", "-o", "x.png"], dir.path());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("igea.ply: byte 64: vertex 0: the vertex element needs x, y and z"),
        "{}",
        stderr(&out)
    );
    // A TOML file with terminal escapes in it: the error shows them escaped.
    std::fs::write(
        dir.path().join("odd.toml"),
        b"[camera]\neye = \x1b[31m\x07\n",
    )
    .unwrap();
    let out = raylab(&["render", "odd.toml", "-o", "x.png"], dir.path());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("odd.toml:2:"), "{}", stderr(&out));
    assert!(stderr(&out).contains("\\u{1b}"), "{}", stderr(&out));
    for out in [
        &out,
        &raylab(&["render", "igea.ply", "-o", "x.png"], dir.path()),
    ] {
        let text = stderr(out);
        assert!(
            !has_control_characters(&text),
            "raw control bytes printed: {text:?}"
        );
    }
}

#[test]
fn special_files_are_refused_before_they_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "[[objects]]\ntype = \"obj\"\nfile = \"/dev/zero\"\n";
    std::fs::write(dir.path().join("zero_mesh.toml"), obj).unwrap();
    let texture = "\
[textures.noise]
type = \"image\"
file = \"/dev/urandom\"

[materials.m]
texture = \"noise\"

[[objects]]
type = \"sphere\"
material = \"m\"
";
    std::fs::write(dir.path().join("noise_texture.toml"), texture).unwrap();
    for scene in ["/dev/zero", "zero_mesh.toml", "noise_texture.toml", "."] {
        let args = ["render", scene, "-o", "x.png", "--size", "8"];
        let Measured { output, .. } =
            raylab_measured(&args, dir.path(), &[], Duration::from_secs(60));
        assert_eq!(
            output.status.code(),
            Some(1),
            "{scene}: {}",
            stderr(&output)
        );
        let text = stderr(&output);
        assert!(text.contains("not a regular file"), "{scene}: {text}");
    }
}

#[test]
fn a_file_larger_than_memory_allows_is_refused_before_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.obj");
    let line = "v 0 0 0\n".repeat(1 << 17);
    std::fs::write(&path, line.as_bytes()).unwrap();
    let scene = "[[objects]]\ntype = \"obj\"\nfile = \"big.obj\"\n";
    std::fs::write(dir.path().join("big.toml"), scene).unwrap();
    let args = ["render", "big.toml", "-o", "x.png", "--size", "8"];
    let env = [("RAYLAB_MAX_MEMORY", "100K")];
    let Measured { output, .. } = raylab_measured(&args, dir.path(), &env, Duration::from_secs(60));
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("reading this 1.0 MB file"),
        "{}",
        stderr(&output)
    );
    assert!(Path::new(&path).exists());
}
