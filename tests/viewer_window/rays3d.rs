//! The ray-tree figure in the viewer (`rays3d`, the key R): a picked pixel's rays drawn in the
//! scene as an observer sees it, each line in its kind's colour where no surface hides it, and
//! the scene camera's image again once the figure is left.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use raylab::camera::{Camera, CameraSpec, PIXEL_CENTRE};
use raylab::figure::{RayFigure, SegmentKind, line_width, view_depth};
use raylab::formats::toml::default_scene;
use raylab::inspect::trace_ray_tree;
use raylab::render::assemble;
use raylab::whitted::EYE_RAY_T_MIN;

use crate::harness::{Run, cpu_render, image_rect, mismatches, printed_camera, run_to_screenshot};

/// The image's side, and the pixel picked.
const SIZE: u32 = 200;
const PIXEL: (u32, u32) = (100, 92);

/// The table `[name]` the viewer printed, as a camera spec.
fn printed_table(stdout: &str, name: &str) -> CameraSpec {
    let start = stdout
        .find(&format!("[{name}]"))
        .unwrap_or_else(|| panic!("no [{name}] in {stdout}"));
    printed_camera(&stdout[start..].replacen(name, "camera", 1))
}

/// Whether `q` lies inside the quadrilateral `corners` (in order round it).
fn inside(q: Vec2, corners: &[Vec2; 4]) -> bool {
    let side = |a: Vec2, b: Vec2| (b - a).perp_dot(q - a);
    let sides: Vec<f32> = (0..4)
        .map(|i| side(corners[i], corners[(i + 1) % 4]))
        .collect();
    sides.iter().all(|&s| s >= 0.0) || sides.iter().all(|&s| s <= 0.0)
}

fn segment_distance(p: Vec2, (a, b): (Vec2, Vec2)) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

/// The viewer at the default window, `PIXEL` picked and its figure shown, the observer orbited,
/// then the script's `rest`: the run and its screenshot.
fn orbited(dir: &Path, rest: &str) -> (Run, PathBuf) {
    let (x, y) = PIXEL;
    let script =
        format!("wait; pick {x} {y}; wait; rays3d on; wait; rays3d orbit 20 5; wait; {rest}");
    let size = SIZE.to_string();
    run_to_screenshot(
        dir,
        &["--size", &size, "--samples", "1", "--script", &script],
    )
}

#[test]
fn the_figure_shows_each_ray_where_the_observer_sees_it() {
    let dir = tempfile::tempdir().unwrap();
    let (run, shot) = orbited(dir.path(), "print-camera");
    let (x, y) = PIXEL;
    let observer = Camera::new(printed_table(&run.stdout, "observer")).unwrap();
    let mut scene = default_scene().unwrap();
    (scene.settings.width, scene.settings.height) = (SIZE, SIZE);
    scene.camera = Camera::new(printed_camera(&run.stdout)).unwrap();
    assert_eq!(
        scene.camera.spec,
        default_scene().unwrap().camera.spec,
        "the scene camera stays"
    );
    let assembled = assemble(scene).unwrap();
    let tracer = assembled.tracer();
    let tree = trace_ray_tree(&tracer, x, y);
    let camera = assembled.scene.camera;
    let figure = RayFigure::new(&tree, (&assembled.scene, &camera), (SIZE, SIZE), u32::MAX);

    let size = (SIZE, SIZE);
    let projected: Vec<_> = figure
        .segments
        .iter()
        .map(|s| observer.project_segment(s.from, s.to, SIZE, SIZE))
        .collect();
    let plane = figure.image_plane.map(|c| observer.project(c, SIZE, SIZE));
    let plane: Option<[Vec2; 4]> = plane
        .iter()
        .copied()
        .collect::<Option<Vec<_>>>()
        .map(|v| [v[0], v[1], v[2], v[3]]);
    let markers: Vec<Vec2> = figure
        .lights
        .iter()
        .chain([&figure.eye])
        .filter_map(|&p| observer.project(p, SIZE, SIZE))
        .collect();
    let keep_off = 2.0 * line_width(SIZE) as f32 + 2.0;
    let depth_at = |px: u32, py: u32| {
        let ray = observer.eye_ray((px, py), PIXEL_CENTRE, size);
        tracer
            .closest_hit(&ray, EYE_RAY_T_MIN)
            .map_or(f32::INFINITY, |h| view_depth(&observer, ray.at(h.t)))
    };
    let shot = image::open(&shot).unwrap().to_rgb8();
    let (x0, y0, w, _) = image_rect(&run.stdout);
    let scale = w / SIZE as f32;
    let mut seen: Vec<SegmentKind> = Vec::new();
    for (i, segment) in figure.segments.iter().enumerate() {
        for k in 1..40 {
            let p: Vec3 = segment.from.lerp(segment.to, k as f32 / 40.0);
            let depth = view_depth(&observer, p);
            let Some(q) = observer
                .project(p, SIZE, SIZE)
                .filter(|_| depth > observer.near * 1.01)
            else {
                continue;
            };
            let (px, py) = (q.x.floor(), q.y.floor());
            if px < 2.0 || py < 2.0 || px > (SIZE - 3) as f32 || py > (SIZE - 3) as f32 {
                continue;
            }
            // Near a line of another kind, either may be drawn on top.
            let near_other = projected.iter().enumerate().any(|(j, o)| {
                let other_kind = figure.segments[j].kind != segment.kind;
                other_kind && o.is_some_and(|o| segment_distance(q, o) < keep_off)
            });
            let near_end =
                projected[i].is_some_and(|(a, b)| a.distance(q).min(b.distance(q)) < keep_off);
            let near_marker = markers.iter().any(|m| m.distance(q) < 2.0 * keep_off);
            let on_plane = plane.is_some_and(|corners| inside(q, &corners));
            if near_other || near_end || near_marker || on_plane {
                continue;
            }
            let (px, py) = (px as u32, py as u32);
            let around = (py - 2..=py + 2).flat_map(|v| (px - 2..=px + 2).map(move |u| (u, v)));
            let nearest = around
                .map(|(u, v)| depth_at(u, v))
                .fold(f32::INFINITY, f32::min);
            if depth >= nearest * 0.98 {
                continue;
            }
            // The centre of that image pixel in the window.
            let sx = (x0 + (px as f32 + 0.5) * scale) as u32;
            let sy = (y0 + (py as f32 + 0.5) * scale) as u32;
            let shown = shot.get_pixel(sx, sy).0;
            let expected = segment.kind.color();
            assert!(
                (0..3).all(|c| shown[c].abs_diff(expected[c]) <= 2),
                "{:?} at image pixel ({px}, {py}), window ({sx}, {sy}): {shown:?}, not {expected:?}",
                segment.kind
            );
            seen.push(segment.kind);
        }
    }
    for kind in [
        SegmentKind::Eye,
        SegmentKind::Shadow,
        SegmentKind::Reflected,
    ] {
        assert!(
            seen.iter().filter(|&&k| k == kind).count() >= 2,
            "{kind:?} seen: {seen:?}"
        );
    }
}

#[test]
fn leaving_the_figure_shows_the_scene_cameras_image_again() {
    let dir = tempfile::tempdir().unwrap();
    let (run, shot) = orbited(dir.path(), "rays3d off; wait; close-inspector; wait");
    let scene = default_scene().unwrap();
    let expected = cpu_render(&scene, SIZE, scene.camera.spec);
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), SIZE, &expected),
        0
    );
}
