//! The camera against the lecture's formulas: `u, v, n`, `H = N·tan(θ/2)`, `W = H·aspect` and
//! `dir_rc = −N·n + W(2c/nCols − 1)·u + H(2r/nRows − 1)·v`; and the camera that frames a scene
//! whose format has none.

use std::path::Path;

use glam::Vec3;
use raylab::aabb::Aabb;
use raylab::camera::{self, Camera, CameraError, CameraSpec, PIXEL_CENTRE, THREE_QUARTER_VIEW};

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

fn camera(eye: Vec3, look_at: Vec3, up: Vec3, view_angle: f32, near: f32) -> Camera {
    Camera::new(CameraSpec {
        eye,
        look_at,
        up,
        view_angle,
        near,
    })
    .unwrap()
}

#[test]
fn axes_are_orthonormal_and_n_points_back_to_the_eye() {
    let cam = camera(
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(-2.0, 0.5, -1.0),
        Vec3::Y,
        60.0,
        1.0,
    );
    let back = (cam.eye - cam.spec.look_at).normalize();
    assert!(close(cam.n, back));
    for a in [cam.u, cam.v, cam.n] {
        assert!((a.length() - 1.0).abs() < 1e-6);
    }
    assert!(cam.u.dot(cam.v).abs() < 1e-6 && cam.u.dot(cam.n).abs() < 1e-6);
    assert!(close(cam.u.cross(cam.v), cam.n), "right-handed u, v, n");
    assert!(cam.v.dot(Vec3::Y) > 0.0, "v leans towards up");
}

#[test]
fn centre_ray_points_along_minus_n_with_length_n() {
    let cam = camera(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y, 90.0, 2.0);
    // Continuous (r, c) = (nRows/2, nCols/2) is the image centre.
    let d = cam.dir_rc(50.0, 100.0, 100, 200);
    assert!(close(d, Vec3::new(0.0, 0.0, -2.0)), "{d}");
}

#[test]
fn corner_rays_match_the_formula() {
    let (theta, near) = (90.0f32, 2.0);
    let cam = camera(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, theta, near);
    let h = near * (theta.to_radians() / 2.0).tan();
    let (rows, cols) = (100, 200);
    let w = h * cols as f32 / rows as f32;
    let corners = [
        ((0.0, 0.0), Vec3::new(-w, -h, -near)),        // bottom left
        ((0.0, cols as f32), Vec3::new(w, -h, -near)), // bottom right
        ((rows as f32, 0.0), Vec3::new(-w, h, -near)), // top left
        ((rows as f32, cols as f32), Vec3::new(w, h, -near)), // top right
    ];
    for ((r, c), expected) in corners {
        let d = cam.dir_rc(r, c, rows, cols);
        assert!(close(d, expected), "({r}, {c}): {d} != {expected}");
    }
}

#[test]
fn pixel_centres_are_half_a_pixel_in() {
    let cam = camera(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 90.0, 1.0);
    // 2×2 image, H = W = 1: pixel (0, 0)'s centre is at (−0.5, −0.5) on the plane z = −1.
    let d = cam.dir_rc(0.5, 0.5, 2, 2);
    assert!(close(d, Vec3::new(-0.5, -0.5, -1.0)), "{d}");
}

#[test]
fn the_image_plane_is_reached_at_t_equal_one() {
    let cam = camera(
        Vec3::new(3.0, 1.0, 2.0),
        Vec3::new(0.0, 0.5, -4.0),
        Vec3::Y,
        50.0,
        0.7,
    );
    for (r, c) in [(0.0, 0.0), (12.5, 33.0), (48.0, 64.0)] {
        let ray = cam.ray(r, c, 48, 64);
        let p = ray.at(1.0);
        // On the plane at distance N in front of the eye, perpendicular to n.
        assert!(((p - cam.eye).dot(-cam.n) - cam.near).abs() < 1e-5);
    }
}

#[test]
fn eye_rays_count_pixels_from_the_top_left_and_rows_from_the_bottom() {
    let cam = camera(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, Vec3::Y, 45.0, 1.0);
    let size = (64, 48);
    // Pixel (0, 0) is the top-left one: row r counts up from the bottom of the image plane.
    assert_eq!(
        cam.eye_ray((0, 0), PIXEL_CENTRE, size),
        cam.ray(47.5, 0.5, 48, 64)
    );
    assert_eq!(
        cam.eye_ray((63, 47), PIXEL_CENTRE, size),
        cam.ray(0.5, 63.5, 48, 64)
    );
    // The offset is measured from the pixel's top-left corner, y down.
    assert_eq!(
        cam.eye_ray((10, 20), (0.25, 0.75), size),
        cam.ray(27.25, 10.25, 48, 64)
    );
    let top_left = cam.eye_ray((0, 0), (0.0, 0.0), size).at(1.0);
    assert!((top_left - cam.eye).dot(cam.u) < 0.0 && (top_left - cam.eye).dot(cam.v) > 0.0);
}

#[test]
fn aspect_stretches_the_width_not_the_height() {
    let cam = camera(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0), Vec3::Y, 60.0, 1.0);
    let h = (30.0f32).to_radians().tan();
    let wide = cam.dir_rc(100.0, 400.0, 100, 400); // top right, aspect 4
    let square = cam.dir_rc(100.0, 100.0, 100, 100);
    assert!((wide.y - h).abs() < 1e-6 && (square.y - h).abs() < 1e-6);
    assert!((wide.x - 4.0 * h).abs() < 1e-5 && (square.x - h).abs() < 1e-6);
}

#[test]
fn degenerate_cameras_are_errors_not_nans() {
    let spec = CameraSpec::default();
    let up_along_view = CameraSpec {
        up: spec.look_at - spec.eye,
        ..spec
    };
    assert_eq!(
        Camera::new(up_along_view),
        Err(CameraError::UpParallelToView)
    );
    let zero_up = CameraSpec {
        up: Vec3::ZERO,
        ..spec
    };
    assert_eq!(Camera::new(zero_up), Err(CameraError::UpParallelToView));
    let same = CameraSpec {
        look_at: spec.eye,
        ..spec
    };
    assert_eq!(Camera::new(same), Err(CameraError::EyeAtLookAt));
    assert!(matches!(
        Camera::new(CameraSpec {
            view_angle: 180.0,
            ..spec
        }),
        Err(CameraError::ViewAngle(_))
    ));
    assert!(matches!(
        Camera::new(CameraSpec { near: 0.0, ..spec }),
        Err(CameraError::Near(_))
    ));
}

/// A scene read from TOML `text`.
fn scene(text: &str) -> raylab::scene::Scene {
    raylab::formats::toml::parse_scene(text, Path::new("test.toml"), Path::new("")).unwrap()
}

/// Whether every corner of every finite object's bounds lands inside the `width × height` image.
fn every_object_in_view(scene: &raylab::scene::Scene, width: u32, height: u32) -> bool {
    let geometry = &scene.geometry;
    geometry
        .prim_ids()
        .filter_map(|id| geometry.bounds(id))
        .flat_map(|bounds| bounds.corners())
        .all(|corner| {
            scene
                .camera
                .project(corner, width, height)
                .is_some_and(|p| {
                    (0.0..=width as f32).contains(&p.x) && (0.0..=height as f32).contains(&p.y)
                })
        })
}

#[test]
fn the_default_camera_is_the_default_specs() {
    assert_eq!(
        Camera::default(),
        Camera::new(CameraSpec::default()).unwrap()
    );
}

#[test]
fn framing_keeps_the_view_direction_and_fits_every_corner_of_the_box() {
    let spec = CameraSpec {
        eye: Vec3::new(0.0, 0.0, 10.0),
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        view_angle: 60.0,
        near: 1.0,
    };
    let bounds = Aabb::new(Vec3::new(3.0, -1.0, 2.0), Vec3::new(7.0, 2.0, 4.0));
    for (width, height) in [(50, 100), (100, 100), (200, 100)] {
        let framed = spec.framing(&bounds, width as f32 / height as f32).unwrap();
        assert!(close(framed.look_at, Vec3::new(5.0, 0.5, 3.0)));
        assert!(close((framed.eye - framed.look_at).normalize(), Vec3::Z));
        let camera = Camera::new(framed).unwrap();
        for corner in bounds.corners() {
            let p = camera.project(corner, width, height).unwrap();
            assert!(p.x >= 0.0 && p.x <= width as f32, "{width}×{height}: {p}");
            assert!(p.y >= 0.0 && p.y <= height as f32, "{width}×{height}: {p}");
        }
    }
    assert_eq!(spec.framing(&Aabb::EMPTY, 1.0), None);
    let infinite = Aabb::new(Vec3::splat(f32::NEG_INFINITY), Vec3::ZERO);
    assert_eq!(spec.framing(&infinite, 1.0), None);
}

#[test]
fn a_scene_without_a_camera_is_framed_from_a_three_quarter_view() {
    // Objects far from the default camera's view, a mesh among them, and a floor plane that
    // must not blow the bounds up.
    let mut s = scene(
        r#"
        [render]
        width = 320
        height = 120

        [[objects]]
        type = "sphere"
        center = [40, 3, -20]
        radius = 2

        [[objects]]
        type = "box"
        min = [30, 0, -30]
        max = [34, 8, -26]
        transform = [ { rotate = { axis = [0, 1, 0], degrees = 30 } } ]

        [[objects]]
        type = "mesh"
        positions = [[44, 0, -24], [46, 0, -24], [45, 5, -22]]
        faces = [[0, 1, 2]]

        [[objects]]
        type = "plane"
        point = [0, -1, 0]
        normal = [0, 1, 0]
        "#,
    );
    // Far from the origin, where the lecture's default camera looks: a TOML file without
    // `[camera]` is framed as it is read, as a format without a camera is.
    assert!(every_object_in_view(&s, 320, 120));
    let spec = s.camera.spec;
    s = raylab::formats::with_framing_camera(s);
    assert_eq!(s.camera.spec, spec);
    // A three-quarter view: from the right, above and in front of the scene's centre.
    let bounds = s.geometry.finite_bounds();
    let from_centre = s.camera.eye - bounds.center();
    assert!(close(s.camera.spec.look_at, bounds.center()));
    assert!(from_centre.x > 0.0 && from_centre.y > 0.0 && from_centre.z > 0.0);
    assert!(close(
        from_centre.normalize(),
        THREE_QUARTER_VIEW.normalize()
    ));
    // The same scene tall and narrow fits too.
    let tall = camera::frame(&bounds, 0.25);
    s.camera = tall;
    assert!(every_object_in_view(&s, 40, 160));
}

#[test]
fn framing_works_from_tiny_to_huge_scenes() {
    for scale in [1e-3f32, 1.0, 1e3] {
        let bounds = Aabb::new(Vec3::splat(-scale), Vec3::new(2.0, 1.0, 0.5) * scale);
        let camera = camera::frame(&bounds, 4.0 / 3.0);
        for corner in bounds.corners() {
            let p = camera.project(corner, 400, 300).unwrap();
            assert!(
                p.x >= 0.0 && p.x <= 400.0 && p.y >= 0.0 && p.y <= 300.0,
                "{scale}: {p}"
            );
        }
        let from_centre = (camera.eye - bounds.center()).length();
        assert!(
            from_centre > scale && from_centre < 10.0 * scale,
            "{scale}: {from_centre}"
        );
    }
}

#[test]
fn a_scene_of_only_planes_or_nothing_gets_the_default_camera() {
    let planes = scene(
        r#"
        [[objects]]
        type = "plane"
        point = [0, -1, 0]
        normal = [0, 1, 0]
        [[objects]]
        type = "plane"
        point = [0, 0, -50]
        normal = [0, 0, 1]
        "#,
    );
    assert!(planes.geometry.finite_bounds().is_empty());
    let framed = raylab::formats::with_framing_camera(planes);
    assert_eq!(framed.camera, Camera::default());
    assert!(framed.camera.eye.is_finite());
    assert_eq!(camera::frame(&Aabb::EMPTY, 1.0), Camera::default());
}
