//! Camera navigation as plain functions of a [`CameraSpec`]: orbit around the look-at point, pan
//! in the image plane, dolly towards the look-at point and fly (the library's
//! [`CameraSpec::framing`] frames a bounding box). Each returns a new spec and keeps it valid (the
//! eye never reaches the look-at point, the view never lines up with the up vector).

use glam::{Quat, Vec3};
use raylab::aabb::Aabb;
use raylab::camera::CameraSpec;

/// Closest the view direction may come to the up vector, in degrees, when orbiting.
const MIN_POLAR_ANGLE: f32 = 1.0;
/// Closest the eye may come to the look-at point.
const MIN_DISTANCE: f32 = 1e-3;
/// Each wheel step brings the eye this much closer (as a fraction of the distance).
const DOLLY_PER_STEP: f32 = 0.9;

/// The camera's unit axes: `right`, `up` (in the image plane) and `back` (from the look-at point
/// towards the eye), as in [`raylab::camera::Camera`].
fn axes(spec: &CameraSpec) -> (Vec3, Vec3, Vec3) {
    let back = (spec.eye - spec.look_at).try_normalize().unwrap_or(Vec3::Z);
    let right = spec
        .up
        .cross(back)
        .try_normalize()
        .unwrap_or_else(|| back.any_orthonormal_vector());
    (right, back.cross(right), back)
}

fn world_up(spec: &CameraSpec) -> Vec3 {
    spec.up.try_normalize().unwrap_or(Vec3::Y)
}

/// Turns the eye around the look-at point: `yaw` degrees about the up vector, then `pitch` degrees
/// up (positive) or down, stopping short of looking straight along the up vector.
pub fn orbit(spec: &CameraSpec, yaw: f32, pitch: f32) -> CameraSpec {
    let up = world_up(spec);
    let offset = Quat::from_axis_angle(up, yaw.to_radians()) * (spec.eye - spec.look_at);
    let distance = offset.length().max(MIN_DISTANCE);
    let dir = offset.try_normalize().unwrap_or(Vec3::Z);
    let polar = dir.dot(up).clamp(-1.0, 1.0).acos();
    let new_polar = (polar - pitch.to_radians()).clamp(
        MIN_POLAR_ANGLE.to_radians(),
        (180.0 - MIN_POLAR_ANGLE).to_radians(),
    );
    let axis = up
        .cross(dir)
        .try_normalize()
        .unwrap_or_else(|| axes(spec).0);
    let dir = Quat::from_axis_angle(axis, new_polar - polar) * dir;
    CameraSpec {
        eye: spec.look_at + dir * distance,
        ..*spec
    }
}

/// Moves the eye and the look-at point together in the image plane so that the scene follows a
/// cursor dragged by `(dx, dy)` pixels (y down) in a view `view_height` pixels tall.
pub fn pan(spec: &CameraSpec, dx: f32, dy: f32, view_height: f32) -> CameraSpec {
    let (right, up, _) = axes(spec);
    let distance = (spec.eye - spec.look_at).length();
    let per_pixel =
        2.0 * distance * (spec.view_angle.to_radians() * 0.5).tan() / view_height.max(1.0);
    let shift = (-dx * right + dy * up) * per_pixel;
    CameraSpec {
        eye: spec.eye + shift,
        look_at: spec.look_at + shift,
        ..*spec
    }
}

/// Moves the eye towards the look-at point (`steps > 0`, as the wheel turns forward) or away from
/// it, by a constant fraction of the distance per step.
pub fn dolly(spec: &CameraSpec, steps: f32) -> CameraSpec {
    let offset = spec.eye - spec.look_at;
    let distance = offset.length();
    let new_distance = (distance * DOLLY_PER_STEP.powf(steps)).clamp(MIN_DISTANCE, 1e7);
    let dir = offset.try_normalize().unwrap_or(Vec3::Z);
    CameraSpec {
        eye: spec.look_at + dir * new_distance,
        ..*spec
    }
}

/// Moves the eye and the look-at point together by `motion` (`x` right, `y` along the up vector,
/// `z` forward), scaled by `distance`.
pub fn fly(spec: &CameraSpec, motion: Vec3, distance: f32) -> CameraSpec {
    let (right, _, back) = axes(spec);
    let shift = (motion.x * right + motion.y * world_up(spec) - motion.z * back) * distance;
    CameraSpec {
        eye: spec.eye + shift,
        look_at: spec.look_at + shift,
        ..*spec
    }
}

/// Flying speed in units per second: about half the scene's size, so crossing it takes a couple
/// of seconds; the eye's distance to the look-at point when the scene has no finite size.
pub fn fly_speed(spec: &CameraSpec, bounds: Aabb) -> f32 {
    let size = (bounds.max - bounds.min).length();
    if size.is_finite() && size > 0.0 {
        size * 0.5
    } else {
        (spec.eye - spec.look_at).length().max(MIN_DISTANCE) * 0.5
    }
}

/// The camera turned to look at `point` from where it is (the new orbit centre); `None` when the
/// point is the eye itself or straight along the up vector.
pub fn look_at_point(spec: &CameraSpec, point: Vec3) -> Option<CameraSpec> {
    let dir = (point - spec.eye).try_normalize()?;
    let up = world_up(spec);
    (up.cross(dir).length() > 1e-3).then_some(CameraSpec {
        look_at: point,
        ..*spec
    })
}

#[cfg(test)]
mod tests {
    use raylab::camera::Camera;

    use super::*;

    fn spec() -> CameraSpec {
        CameraSpec {
            eye: Vec3::new(0.0, 0.0, 10.0),
            look_at: Vec3::ZERO,
            up: Vec3::Y,
            view_angle: 60.0,
            near: 1.0,
        }
    }

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-4
    }

    #[test]
    fn orbiting_keeps_the_distance_and_the_centre() {
        let s = orbit(&spec(), 37.0, 21.0);
        assert!(close(s.look_at, Vec3::ZERO));
        assert!((s.eye.length() - 10.0).abs() < 1e-4);
        assert!(Camera::new(s).is_ok());
    }

    #[test]
    fn a_quarter_turn_of_yaw_moves_the_eye_round_the_up_axis() {
        let s = orbit(&spec(), 90.0, 0.0);
        assert!(close(s.eye, Vec3::new(10.0, 0.0, 0.0)), "{:?}", s.eye);
        let s = orbit(&spec(), 0.0, 30.0);
        let expected = Vec3::new(
            0.0,
            10.0 * 30f32.to_radians().sin(),
            10.0 * 30f32.to_radians().cos(),
        );
        assert!(close(s.eye, expected), "{:?}", s.eye);
    }

    #[test]
    fn pitch_stops_before_the_up_vector() {
        for pitch in [89.5, 120.0, 400.0, -400.0] {
            let s = orbit(&spec(), 0.0, pitch);
            let polar = s.eye.normalize().dot(Vec3::Y).acos().to_degrees();
            assert!((MIN_POLAR_ANGLE - 1e-3..=180.0 - MIN_POLAR_ANGLE + 1e-3).contains(&polar));
            assert!(Camera::new(s).is_ok(), "pitch {pitch}");
        }
    }

    #[test]
    fn panning_follows_the_cursor_in_the_image_plane() {
        let s = spec();
        // Dragging right by the view's height moves the scene right by the visible height at the
        // look-at point (2·d·tan(θ/2)), so the camera moves left by as much.
        let visible = 2.0 * 10.0 * 30f32.to_radians().tan();
        let p = pan(&s, 500.0, 0.0, 500.0);
        assert!(close(p.eye, Vec3::new(-visible, 0.0, 10.0)), "{:?}", p.eye);
        assert!(close(p.eye - p.look_at, s.eye - s.look_at));
        let p = pan(&s, 0.0, 250.0, 500.0);
        assert!(close(p.look_at, Vec3::new(0.0, visible / 2.0, 0.0)));
    }

    #[test]
    fn dolly_moves_along_the_view_and_never_reaches_the_centre() {
        let s = dolly(&spec(), 1.0);
        assert!(close(s.eye, Vec3::new(0.0, 0.0, 9.0)));
        let s = dolly(&spec(), -1.0);
        assert!((s.eye.z - 10.0 / 0.9).abs() < 1e-4);
        let s = dolly(&spec(), 1e6);
        assert!(s.eye.z >= MIN_DISTANCE && Camera::new(s).is_ok());
    }

    #[test]
    fn flying_moves_eye_and_look_at_together() {
        let s = fly(&spec(), Vec3::new(0.0, 0.0, 1.0), 2.0);
        assert!(close(s.eye, Vec3::new(0.0, 0.0, 8.0)));
        assert!(close(s.look_at, Vec3::new(0.0, 0.0, -2.0)));
        let s = fly(&spec(), Vec3::new(1.0, 1.0, 0.0), 1.0);
        assert!(close(s.eye, Vec3::new(1.0, 1.0, 10.0)));
    }

    #[test]
    fn fly_speed_scales_with_the_scene() {
        let small = Aabb::new(Vec3::ZERO, Vec3::splat(1.0));
        let large = Aabb::new(Vec3::ZERO, Vec3::splat(100.0));
        assert!(fly_speed(&spec(), large) > 50.0 * fly_speed(&spec(), small));
        assert_eq!(fly_speed(&spec(), Aabb::EMPTY), 5.0);
    }

    #[test]
    fn looking_at_a_point_turns_the_camera_but_keeps_the_eye() {
        let s = look_at_point(&spec(), Vec3::new(1.0, 2.0, 0.0)).unwrap();
        assert_eq!(s.eye, spec().eye);
        assert_eq!(s.look_at, Vec3::new(1.0, 2.0, 0.0));
        assert_eq!(look_at_point(&spec(), spec().eye), None);
        assert_eq!(look_at_point(&spec(), Vec3::new(0.0, 20.0, 10.0)), None);
    }
}
