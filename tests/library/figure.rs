//! The lecture's ray-tree figure (`raylab::figure`) on scenes made for it: a mirror ball, a glass
//! ball and a blocker between a hit and one of two lights. Each line is checked where the
//! observer sees it: on a pixel of its kind's colour where no surface lies in front of it (the
//! observer's depth, found here from the observer's own eye rays, and the image plane's), and
//! not drawn where one does, or dashed there in x-ray.

use glam::{Vec2, Vec3};
use raylab::backend::Backend;
use raylab::camera::{Camera, CameraSpec, PIXEL_CENTRE};
use raylab::figure::{
    FigureStyle, RayFigure, SegmentKind, draw, line_width, observed, observer_depths, side_view,
    view_depth,
};
use raylab::formats::toml::parse_scene;
use raylab::inspect::trace_ray_tree;
use raylab::render::{Assembled, assemble};
use raylab::srgb_image::SrgbImage;
use raylab::whitted::EYE_RAY_T_MIN;

/// The scene camera's image: odd sides, so that the centre pixel looks at the look-at point.
const TRACED: (u32, u32) = (33, 25);
const CENTRE: (u32, u32) = (16, 12);
/// A pixel above the centre: it sees the upper half of the mirror ball, which reflects upwards.
const ABOVE_CENTRE: (u32, u32) = (16, 7);
/// The figure's size.
const FIGURE: (u32, u32) = (320, 240);

const CAMERA_AND_FLOOR: &str = r#"
[render]
width = 33
height = 25
max_depth = 5
background = [0.2, 0.3, 0.5]

[camera]
eye = [0, 3, 6]
look_at = [0, 0, 0]
view_angle = 40

[materials.floor]
color = [0.6, 0.6, 0.5]

[[objects]]
type = "plane"
normal = [0, 1, 0]
material = "floor"
"#;

/// A mirror ball: the eye ray reflects back up and out.
fn mirror_ball() -> String {
    format!(
        "{CAMERA_AND_FLOOR}
[[lights]]
type = \"point\"
position = [4, 6, 4]

[materials.mirror]
color = [0.1, 0.1, 0.1]
reflectivity = 0.9

[[objects]]
type = \"sphere\"
center = [0, 0.8, 0]
radius = 0.8
material = \"mirror\"
"
    )
}

/// A glass ball where the centre pixel looks: the transmitted rays run inside it, hidden from
/// an observer outside by its surface.
fn glass_ball() -> String {
    format!(
        "{CAMERA_AND_FLOOR}
[[lights]]
type = \"point\"
position = [4, 6, 4]

[materials.glass]
color = [1, 1, 1]
diffuse = 0.05
transparency = 0.9
ior = 1.5

[[objects]]
type = \"sphere\"
center = [0, 1, 0]
radius = 1
material = \"glass\"
"
    )
}

/// The floor point the centre pixel sees, lit by two lights, a ball between it and the second.
fn blocked_light() -> String {
    format!(
        "{CAMERA_AND_FLOOR}
[[lights]]
type = \"point\"
position = [-3, 5, 0]

[[lights]]
type = \"point\"
position = [3, 5, 0]

[[objects]]
type = \"sphere\"
center = [1.5, 2.5, 0]
radius = 0.5
"
    )
}

/// A figure drawn, with what the test needs to check it.
struct Drawn {
    figure: RayFigure,
    observer: Camera,
    traced: SrgbImage,
    /// The figure without its lines and lights: the scene and the image plane.
    base: SrgbImage,
    image: SrgbImage,
    /// The depth of the nearest surface or image plane at each pixel, found by the test.
    surface: Vec<f32>,
}

fn shade(backend: &mut Backend, assembled: &Assembled) -> SrgbImage {
    let (film, _) = backend.render_image(assembled).expect("the CPU renders");
    SrgbImage::from_linear(film.width(), film.height(), &film.pixels())
}

/// The figure of `pixel` of the scene `toml`, up to `generations`, seen by `observer` (the side
/// view when `None`).
fn drawn(
    toml: &str,
    pixel: (u32, u32),
    generations: u32,
    xray: bool,
    observer: Option<CameraSpec>,
) -> Drawn {
    let scene = parse_scene(toml, "figure.toml".as_ref(), ".".as_ref()).unwrap();
    let assembled = assemble(scene).unwrap();
    let tree = trace_ray_tree(&assembled.tracer(), pixel.0, pixel.1);
    let figure = RayFigure::new(
        &tree,
        (&assembled.scene, &assembled.scene.camera),
        TRACED,
        generations,
    );
    let aspect = FIGURE.0 as f32 / FIGURE.1 as f32;
    let spec =
        observer.unwrap_or_else(|| side_view(&figure, &assembled.scene.camera, 45.0, aspect));
    let observer = Camera::new(spec).unwrap();
    let mut backend = Backend::on_all_cores().unwrap();
    let traced = shade(&mut backend, &assembled);
    let seen = shade(&mut backend, &observed(&assembled, observer, FIGURE));
    let depths = observer_depths(&assembled.tracer(), &observer, FIGURE);
    let style = FigureStyle {
        xray,
        ..FigureStyle::default()
    };
    let image = draw(&figure, &observer, &seen, &depths, &traced, &style);
    let bare = RayFigure {
        segments: Vec::new(),
        lights: Vec::new(),
        ..figure.clone()
    };
    let base = draw(&bare, &observer, &seen, &depths, &traced, &style);
    let surface = surface_depths(&assembled, &observer, figure.image_plane);
    Drawn {
        figure,
        observer,
        traced,
        base,
        image,
        surface,
    }
}

/// The depth of what the observer sees at each pixel's centre: the nearest of the scene's
/// closest hit and the image plane (corners top left, top right, bottom right, bottom left).
fn surface_depths(assembled: &Assembled, observer: &Camera, plane: [Vec3; 4]) -> Vec<f32> {
    let tracer = assembled.tracer();
    let (across, down) = (plane[1] - plane[0], plane[3] - plane[0]);
    let normal = across.cross(down);
    let mut depths = Vec::new();
    for y in 0..FIGURE.1 {
        for x in 0..FIGURE.0 {
            let ray = observer.eye_ray((x, y), PIXEL_CENTRE, FIGURE);
            let scene = tracer
                .closest_hit(&ray, EYE_RAY_T_MIN)
                .map_or(f32::INFINITY, |hit| view_depth(observer, ray.at(hit.t)));
            let t = (plane[0] - ray.origin).dot(normal) / ray.dir.dot(normal);
            let on = ray.at(t) - plane[0];
            let (a, b) = (
                on.dot(across) / across.length_squared(),
                on.dot(down) / down.length_squared(),
            );
            let inside = t >= EYE_RAY_T_MIN && (0.0..1.0).contains(&a) && (0.0..1.0).contains(&b);
            let plane_depth = if inside {
                view_depth(observer, ray.at(t))
            } else {
                f32::INFINITY
            };
            depths.push(scene.min(plane_depth));
        }
    }
    depths
}

fn segment_distance(p: Vec2, (a, b): (Vec2, Vec2)) -> f32 {
    let ab = b - a;
    let s = ((p - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
    p.distance(a + ab * s)
}

/// What the samples along the lines found.
#[derive(Debug, Default)]
struct Samples {
    /// (kind, pixel colour) of samples in front of every surface around them.
    visible: Vec<(SegmentKind, [u8; 3])>,
    /// (kind, pixel colour, the colour without the lines) of samples behind every surface
    /// around them.
    hidden: Vec<(SegmentKind, [u8; 3], [u8; 3])>,
}

/// Samples each line of the figure where it is clearly in front of or clearly behind what the
/// observer sees around it, away from other lines and the markers.
fn samples(d: &Drawn) -> Samples {
    let (w, h) = FIGURE;
    let project = |p| d.observer.project(p, w, h);
    let projected: Vec<Option<(Vec2, Vec2)>> = d
        .figure
        .segments
        .iter()
        .map(|s| d.observer.project_segment(s.from, s.to, w, h))
        .collect();
    let markers: Vec<Vec2> = d
        .figure
        .lights
        .iter()
        .chain([&d.figure.eye])
        .filter_map(|&p| project(p))
        .collect();
    let keep_off = 2.0 * line_width(h) as f32 + 3.0;
    let mut found = Samples::default();
    for (i, segment) in d.figure.segments.iter().enumerate() {
        for k in 1..60 {
            let p = segment.from.lerp(segment.to, k as f32 / 60.0);
            let depth = view_depth(&d.observer, p);
            let Some(q) = project(p).filter(|_| depth > d.observer.near * 1.01) else {
                continue;
            };
            let (px, py) = (q.x.floor() as i64, q.y.floor() as i64);
            if px < 3 || py < 3 || px >= w as i64 - 3 || py >= h as i64 - 3 {
                continue;
            }
            let near_other = projected.iter().enumerate().any(|(j, other)| {
                j != i && other.is_some_and(|o| segment_distance(q, o) < keep_off)
            });
            let near_marker = markers.iter().any(|m| m.distance(q) < 2.0 * keep_off);
            let near_own_end =
                projected[i].is_some_and(|(a, b)| a.distance(q).min(b.distance(q)) < keep_off);
            if near_other || near_marker || near_own_end {
                continue;
            }
            let around = (-2..=2).flat_map(|dy| (-2..=2).map(move |dx| (dx, dy)));
            let depths: Vec<f32> = around
                .map(|(dx, dy)| d.surface[((py + dy) as u32 * w + (px + dx) as u32) as usize])
                .collect();
            let nearest = depths.iter().copied().fold(f32::INFINITY, f32::min);
            let farthest = depths.iter().copied().fold(0.0, f32::max);
            let (x, y) = (px as u32, py as u32);
            if depth < nearest * 0.98 {
                found.visible.push((segment.kind, d.image.at(x, y)));
            } else if depth > farthest * 1.02 {
                found
                    .hidden
                    .push((segment.kind, d.image.at(x, y), d.base.at(x, y)));
            }
        }
    }
    found
}

/// Every visible sample shows its kind's colour, every hidden one the scene; returns the
/// samples for the test's own counts.
fn assert_drawn_where_seen(d: &Drawn) -> Samples {
    let found = samples(d);
    for &(kind, color) in &found.visible {
        assert_eq!(color, kind.color(), "a visible {kind:?} sample");
    }
    for &(kind, color, base) in &found.hidden {
        assert_eq!(color, base, "a hidden {kind:?} sample is drawn");
    }
    found
}

fn count(samples: &[(SegmentKind, [u8; 3])], kind: SegmentKind) -> usize {
    samples.iter().filter(|s| s.0 == kind).count()
}

fn pixels_of(image: &SrgbImage, kind: SegmentKind) -> usize {
    image.pixels.iter().filter(|&&p| p == kind.color()).count()
}

#[test]
fn a_mirror_balls_rays_show_where_the_observer_sees_them_and_generation_1_has_no_reflection() {
    let all = drawn(&mirror_ball(), ABOVE_CENTRE, u32::MAX, false, None);
    let found = assert_drawn_where_seen(&all);
    for kind in [
        SegmentKind::Eye,
        SegmentKind::Reflected,
        SegmentKind::Shadow,
    ] {
        assert!(count(&found.visible, kind) >= 3, "{kind:?}: {found:?}");
    }
    assert!(pixels_of(&all.image, SegmentKind::Reflected) > 50);
    // The normals are too short to sample away from their ends.
    assert!(pixels_of(&all.image, SegmentKind::Normal) > 10);
    let first = drawn(&mirror_ball(), ABOVE_CENTRE, 1, false, None);
    assert_drawn_where_seen(&first);
    assert_eq!(pixels_of(&first.base, SegmentKind::Reflected), 0);
    for kind in [SegmentKind::Reflected, SegmentKind::Transmitted] {
        assert_eq!(pixels_of(&first.image, kind), 0, "{kind:?} at generation 1");
    }
    assert!(pixels_of(&first.image, SegmentKind::Eye) > 50);
}

#[test]
fn a_glass_balls_inner_rays_are_hidden_and_in_xray_dashed() {
    let plain = drawn(&glass_ball(), CENTRE, u32::MAX, false, None);
    let found = assert_drawn_where_seen(&plain);
    let hidden_transmitted = found
        .hidden
        .iter()
        .filter(|s| s.0 == SegmentKind::Transmitted)
        .count();
    assert!(hidden_transmitted >= 5, "{found:?}");
    assert!(count(&found.visible, SegmentKind::Eye) >= 3, "{found:?}");

    let xray = drawn(&glass_ball(), CENTRE, u32::MAX, true, None);
    let seen = samples(&xray);
    for &(kind, color) in &seen.visible {
        assert_eq!(color, kind.color(), "a visible {kind:?} sample in x-ray");
    }
    let dashed = seen
        .hidden
        .iter()
        .filter(|(kind, color, _)| *color == kind.color())
        .count();
    let gaps = seen
        .hidden
        .iter()
        .filter(|(_, color, base)| color == base)
        .count();
    assert!(
        dashed * 4 >= seen.hidden.len() && gaps * 4 >= seen.hidden.len(),
        "x-ray: {dashed} of {} hidden samples drawn, {gaps} left as the scene",
        seen.hidden.len()
    );
}

#[test]
fn a_shadow_ray_stopped_by_a_ball_ends_at_it_in_the_blocked_colour() {
    let d = drawn(&blocked_light(), CENTRE, u32::MAX, false, None);
    let shadows: Vec<_> = d
        .figure
        .segments
        .iter()
        .filter(|s| matches!(s.kind, SegmentKind::Shadow | SegmentKind::ShadowBlocked))
        .collect();
    assert_eq!(shadows.len(), 2, "{shadows:?}");
    let blocked = shadows
        .iter()
        .find(|s| s.kind == SegmentKind::ShadowBlocked)
        .expect("one blocked");
    // It ends on the blocker's surface, short of the light at (3, 5, 0).
    assert!(
        (blocked.to.distance(Vec3::new(1.5, 2.5, 0.0)) - 0.5).abs() < 1e-3,
        "{blocked:?}"
    );
    let clear = shadows
        .iter()
        .find(|s| s.kind == SegmentKind::Shadow)
        .expect("one clear");
    assert!(
        clear.to.distance(Vec3::new(-3.0, 5.0, 0.0)) < 1e-3,
        "{clear:?}"
    );
    let found = assert_drawn_where_seen(&d);
    assert!(
        count(&found.visible, SegmentKind::ShadowBlocked) >= 3,
        "{found:?}"
    );
    assert!(count(&found.visible, SegmentKind::Shadow) >= 3, "{found:?}");
}

#[test]
fn the_image_plane_shows_the_traced_image_and_the_pixels_cell_where_the_eye_ray_crosses_it() {
    // The observer stands behind the scene camera's eye, looking the same way.
    let eye = Vec3::new(0.0, 3.0, 6.0);
    let back = eye.normalize();
    let observer = CameraSpec {
        eye: eye + back * 0.8,
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        view_angle: 60.0,
        near: 0.1,
    };
    let d = drawn(&blocked_light(), CENTRE, u32::MAX, false, Some(observer));
    // The cell: the image plane's four lines after its frame's.
    let planes: Vec<_> = d
        .figure
        .segments
        .iter()
        .filter(|s| s.kind == SegmentKind::ImagePlane)
        .collect();
    assert_eq!(planes.len(), 8);
    let cell: Vec<Vec3> = planes[4..].iter().map(|s| s.from).collect();
    let centre = cell.iter().sum::<Vec3>() / 4.0;
    let eye_ray = d
        .figure
        .segments
        .iter()
        .find(|s| s.kind == SegmentKind::Eye)
        .unwrap();
    let [top_left, top_right, _, bottom_left] = d.figure.image_plane;
    let normal = (top_right - top_left).cross(bottom_left - top_left);
    let dir = eye_ray.to - eye_ray.from;
    let crossing = eye_ray.from + dir * ((top_left - eye_ray.from).dot(normal) / dir.dot(normal));
    assert!(
        crossing.distance(centre) < 1e-4,
        "{crossing} vs the cell's centre {centre}"
    );
    let side = cell[0].distance(cell[1]);
    assert!(
        side > 0.0 && cell.iter().all(|c| c.distance(crossing) < side),
        "{cell:?}"
    );

    // Each texel's centre on the plane shows the texel, away from the lines and the eye marker.
    let (w, h) = FIGURE;
    let projected: Vec<_> = d
        .figure
        .segments
        .iter()
        .filter_map(|s| d.observer.project_segment(s.from, s.to, w, h))
        .collect();
    let eye_marker = d.observer.project(d.figure.eye, w, h).unwrap();
    let mut checked = 0;
    for ty in 0..TRACED.1 {
        for tx in 0..TRACED.0 {
            let a = (tx as f32 + 0.5) / TRACED.0 as f32;
            let b = (ty as f32 + 0.5) / TRACED.1 as f32;
            let p = top_left + (top_right - top_left) * a + (bottom_left - top_left) * b;
            let q = d.observer.project(p, w, h).unwrap();
            let clear = projected.iter().all(|&s| segment_distance(q, s) > 8.0)
                && q.distance(eye_marker) > 16.0;
            if clear {
                assert_eq!(
                    d.image.at(q.x as u32, q.y as u32),
                    d.traced.at(tx, ty),
                    "texel ({tx}, {ty})"
                );
                checked += 1;
            }
        }
    }
    assert!(
        checked > TRACED.0 * TRACED.1 / 2,
        "{checked} texels checked"
    );
}
