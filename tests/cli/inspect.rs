//! `raylab inspect`: a pixel's ray tree as text and as JSON, and the mistakes in naming the pixel.

use std::path::Path;

use crate::common::run::{raylab, stderr};

#[test]
fn inspect_prints_the_ray_tree_of_a_pixel_as_text_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/glass.toml");
    let args = |json: bool| {
        let mut args = vec![
            "inspect",
            scene.to_str().unwrap(),
            "--pixel",
            "80,60",
            "--width",
            "160",
            "--height",
            "120",
        ];
        if json {
            args.push("--json");
        }
        raylab(&args, dir.path())
    };
    let text = args(false);
    assert!(text.status.success(), "{}", stderr(&text));
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.starts_with("pixel (80, 60): colour"), "{text}");
    assert!(text.contains("eye ray, depth 1"), "{text}");

    let json = args(true);
    assert!(json.status.success(), "{}", stderr(&json));
    let tree: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    assert_eq!(tree["pixel"], serde_json::json!([80, 60]));
    let nodes = tree["nodes"].as_array().unwrap();
    assert_eq!(nodes[0]["kind"], "eye");
    assert_eq!(nodes[0]["depth"], 1);
    // Every node but the eye ray names its parent, which lists it as a child.
    for (i, node) in nodes.iter().enumerate().skip(1) {
        let parent = node["parent"].as_u64().unwrap() as usize;
        let children = nodes[parent]["children"].as_array().unwrap();
        assert!(children.contains(&serde_json::json!(i)), "node {i}");
    }
}

#[test]
fn inspect_mistakes_are_errors_not_panics() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &str); 4] = [
        (
            &[
                "inspect", "--pixel", "64,0", "--width", "64", "--height", "48",
            ],
            "outside the 64×48 image",
        ),
        (&["inspect", "--pixel", "3"], "expected X,Y"),
        (&["inspect", "--pixel=-1,2"], "expected X,Y"),
        (&["inspect", "--pixel", "a,b"], "expected X,Y"),
    ];
    for (args, message) in cases {
        let out = raylab(args, dir.path());
        assert!(!out.status.success(), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn inspect_materials_lists_a_gltf_models_values_beside_raylabs_and_render_prints_the_report() {
    let dir = tempfile::tempdir().unwrap();
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/gltf/seed_cubes.glb");
    let model = model.to_str().unwrap();
    let out = raylab(&["inspect", model, "--materials"], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0], "glTF: 3 materials → 1 mirror, 1 glass, 1 Phong",
        "{text}"
    );
    assert_eq!(lines[1], "material 0 `mirror` → mirror", "{text}");
    assert!(
        lines[2].starts_with("  glTF:   base colour 1 1 1 1, metallic 1, roughness 0,"),
        "{text}"
    );
    assert!(
        lines[3].contains("diffuse 0,") && lines[3].contains("reflectivity 1 in 1 1 1,"),
        "{text}"
    );
    assert!(text.contains("material 1 `glass` → glass\n"), "{text}");
    assert!(text.contains("transmission 1, ior 1.4"), "{text}");
    assert!(
        text.contains("transparency 1, ior 1.4, fresnel true"),
        "{text}"
    );

    // A scene of another format lists raylab's materials alone.
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/glass.toml");
    let out = raylab(
        &["inspect", scene.to_str().unwrap(), "--materials"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.starts_with("material 0 `default`\n  raylab: color 0.8 0.8 0.8,"),
        "{text}"
    );

    // Rendering the model prints the report as a note.
    let out = raylab(
        &[
            "render",
            model,
            "-o",
            "cubes.png",
            "--width",
            "64",
            "--height",
            "48",
        ],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("seed_cubes.glb: glTF: 3 materials → 1 mirror, 1 glass, 1 Phong"),
        "{}",
        stderr(&out)
    );
}
