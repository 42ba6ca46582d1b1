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
