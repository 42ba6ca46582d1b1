//! `raylab inspect --draw` and `--obj`: the ray-tree figure and its lines as OBJ, from the
//! command line. (`tests/library/figure.rs` checks what the figure shows.)

use std::collections::BTreeMap;
use std::path::Path;

use raylab::srgb_image::SrgbImage;

use crate::common::run::{raylab, stderr};

/// A floor lit by two lights, a ball between the centre pixel's floor point and the second,
/// and a glass ball beside it.
const SCENE: &str = r#"
[render]
width = 33
height = 25

[camera]
eye = [0, 3, 6]
look_at = [0, 0, 0]
view_angle = 40

[materials.glass]
transparency = 0.9
reflectivity = 0.1
ior = 1.5

[[lights]]
type = "point"
position = [-3, 5, 0]

[[lights]]
type = "point"
position = [3, 5, 0]

[[objects]]
type = "plane"
normal = [0, 1, 0]

[[objects]]
type = "sphere"
center = [1.5, 2.5, 0]
radius = 0.5

[[objects]]
type = "sphere"
center = [-1, 0.5, 1]
radius = 0.5
material = "glass"
"#;

fn scene_in(dir: &Path) -> &'static str {
    std::fs::write(dir.join("scene.toml"), SCENE).unwrap();
    "scene.toml"
}

/// The OBJ file's vertices, group by group, as `[x, y, z]` read back as `f32`.
fn obj_groups(text: &str) -> BTreeMap<String, Vec<[f32; 3]>> {
    let mut groups: BTreeMap<String, Vec<[f32; 3]>> = BTreeMap::new();
    let mut group = String::new();
    let mut lines = 0;
    let mut vertices = 0;
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["g", name] => group = name.to_string(),
            ["v", x, y, z] => {
                let v = [x, y, z].map(|s| s.parse::<f32>().unwrap());
                groups.entry(group.clone()).or_default().push(v);
                vertices += 1;
            }
            ["l", a, b] => {
                assert_eq!(a.parse::<usize>().unwrap() + 1, b.parse::<usize>().unwrap());
                assert_eq!(
                    b.parse::<usize>().unwrap(),
                    vertices,
                    "a line joins its own two vertices"
                );
                lines += 1;
            }
            [] => {}
            [first, ..] if first.starts_with('#') => {}
            other => panic!("unexpected OBJ line {other:?}"),
        }
    }
    assert_eq!(2 * lines, vertices);
    groups
}

fn vector(value: &serde_json::Value) -> [f32; 3] {
    [0, 1, 2].map(|i| value[i].as_f64().unwrap() as f32)
}

#[test]
fn the_obj_export_holds_the_points_of_the_json_tree_one_group_per_kind() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_in(dir.path());
    for pixel in ["16,12", "10,16"] {
        let args = [
            "inspect", scene, "--pixel", pixel, "--json", "--obj", "tree.obj",
        ];
        let out = raylab(&args, dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
        let tree: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let groups = obj_groups(&std::fs::read_to_string(dir.path().join("tree.obj")).unwrap());
        let (mut rays, mut shadows, mut blocked) = (Vec::new(), Vec::new(), Vec::new());
        for node in tree["nodes"].as_array().unwrap() {
            let kind = node["kind"].as_str().unwrap().to_string();
            let origin = vector(&node["origin"]);
            let hit = &node["hit"];
            assert!(!hit.is_null(), "every ray of this scene hits something");
            rays.push((kind.clone(), origin, vector(&hit["point"])));
            for shadow in node["shadows"].as_array().unwrap() {
                let (o, d) = (vector(&shadow["origin"]), vector(&shadow["dir"]));
                let blockers = shadow["blockers"].as_array().unwrap();
                let at = |t: f32| [0, 1, 2].map(|i| o[i] + d[i] * t);
                if shadow["blocked"].as_bool().unwrap() {
                    let t = blockers.last().unwrap()["t"].as_f64().unwrap() as f32;
                    blocked.push((o, at(t)));
                } else {
                    shadows.push((o, at(shadow["distance"].as_f64().unwrap() as f32)));
                }
            }
        }
        // Eye, reflected and transmitted rays: from their origin to their hit, exactly.
        for kind in ["eye", "reflected", "transmitted"] {
            let expected: Vec<[f32; 3]> = rays
                .iter()
                .filter(|r| r.0 == kind)
                .flat_map(|r| [r.1, r.2])
                .collect();
            assert_eq!(
                groups.get(kind).cloned().unwrap_or_default(),
                expected,
                "{kind}"
            );
        }
        for (group, expected) in [("shadow", &shadows), ("shadow-blocked", &blocked)] {
            let written = groups.get(group).cloned().unwrap_or_default();
            assert_eq!(written.len(), 2 * expected.len(), "{group}");
            for (pair, (from, to)) in written.chunks(2).zip(expected.iter()) {
                assert_eq!(pair[0], *from, "{group}: the shadow ray's origin");
                let off = (0..3)
                    .map(|i| (pair[1][i] - to[i]).abs())
                    .fold(0.0, f32::max);
                assert!(off < 1e-5, "{group}: {:?} vs {to:?}", pair[1]);
            }
        }
        assert_eq!(
            groups["image-plane"].len(),
            16,
            "the frame and the cell: 8 lines"
        );
        assert_eq!(
            groups["normal"].len(),
            2 * rays.len(),
            "a normal at each hit"
        );
    }
    // The centre pixel's floor point has one clear and one blocked shadow ray.
    let out = raylab(
        &["inspect", scene, "--pixel", "16,12", "--obj", "tree.obj"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let groups = obj_groups(&std::fs::read_to_string(dir.path().join("tree.obj")).unwrap());
    assert_eq!(groups["shadow"].len(), 2);
    assert_eq!(groups["shadow-blocked"].len(), 2);
}

#[test]
fn draw_writes_the_figure_at_its_size_and_keeps_the_scene_camera() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_in(dir.path());
    let json_of = |extra: &[&str]| {
        let args = [&["inspect", scene, "--pixel", "16,12", "--json"][..], extra].concat();
        let out = raylab(&args, dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
        let tree: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        (tree["nodes"][0]["dir"].clone(), stderr(&out))
    };
    let (plain, _) = json_of(&[]);
    // With --draw, --look-at is the observer's: the eye ray stays the scene camera's.
    let (drawn, said) = json_of(&["--draw", "fig.png", "--look-at", "0,1,0", "--from", "6,4,6"]);
    assert_eq!(plain, drawn);
    assert!(said.contains("figure: fig.png (1024×768, observer at (6.000, 4.000, 6.000) looking at (0.000, 1.000, 0.000)"), "{said}");
    let image = SrgbImage::read(&dir.path().join("fig.png")).unwrap();
    assert_eq!((image.width, image.height), (1024, 768));
    let (_, said) = json_of(&[
        "--draw",
        "small.png",
        "--draw-size",
        "200x100",
        "--generations",
        "1",
        "--xray",
    ]);
    assert!(said.contains("figure: small.png (200×100"), "{said}");
    let small = SrgbImage::read(&dir.path().join("small.png")).unwrap();
    assert_eq!((small.width, small.height), (200, 100));
}

#[test]
fn a_wrong_figure_request_is_refused_with_what_to_do() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_in(dir.path());
    let inspect = ["inspect", scene, "--pixel", "16,12"];
    for (extra, code, message) in [
        (
            &["--draw", "f.png", "--generations", "0"][..],
            1,
            "--generations must be at least 1",
        ),
        (
            &["--draw", "f.txt"],
            1,
            "--draw: f.txt: unknown image format",
        ),
        (&["--from", "1,2,3"], 2, "--draw"),
        (
            &["--draw", "f.png", "--draw-size", "0x10"],
            2,
            "is not a size",
        ),
        (
            &["--draw", "f.png", "--draw-size", "100000x10"],
            1,
            "--draw-size",
        ),
        (
            &["--draw", "f.png", "--from", "1,1,1", "--look-at", "1,1,1"],
            1,
            "the observer (--from, --look-at, --observer-angle): the eye and the look-at point coincide",
        ),
        (
            &["--draw", "f.png", "--observer-angle", "180"],
            1,
            "view angle must be between 0 and 180",
        ),
    ] {
        let out = raylab(&[&inspect[..], extra].concat(), dir.path());
        assert_eq!(out.status.code(), Some(code), "{extra:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains(message),
            "{extra:?}: {}",
            stderr(&out)
        );
        assert!(!dir.path().join("f.png").exists(), "{extra:?}");
    }
}

#[test]
fn a_figure_too_large_for_the_memory_limit_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let scene = scene_in(dir.path());
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(["inspect", scene, "--pixel", "16,12", "--draw", "f.png"])
        .args(["--draw-size", "16384x16384"])
        .env("RAYLAB_MAX_MEMORY", "256M")
        .current_dir(dir.path())
        .output()
        .unwrap();
    let text = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("--draw-size: a 16384×16384 figure would take about")
            && text.contains("RAYLAB_MAX_MEMORY"),
        "{text}"
    );
    assert!(!dir.path().join("f.png").exists());
}
