//! Views and camera paths: the bookmarked cameras of a scene ([`Views`], numbered 1 to 9, as the
//! viewer's `Ctrl+1…9` stores them and `formats::toml` reads and writes them as
//! `NAME.views.toml`), and the camera of each frame of an image sequence: a [`turntable`] (the
//! eye orbiting the look-at point) or a [`path`] through the views in order.
//!
//! Frames are numbered from 0, and frame 0 is always the first camera exactly (the scene's, or
//! the first view), so that the sequence starts on the still image.

use std::collections::BTreeMap;
use std::ops::RangeInclusive;

use glam::{Quat, Vec3};

use crate::camera::{Camera, CameraSpec};

/// The numbers a view may have: the viewer's keys 1 to 9.
pub const VIEW_NUMBERS: RangeInclusive<u8> = 1..=9;

/// The most frames a sequence may have (at 30 frames a second, over five minutes): more is
/// surely a mistyped number, and each frame is a whole render.
pub const MAX_FRAMES: u32 = 10_000;

/// A scene's bookmarked cameras, by number ([`VIEW_NUMBERS`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Views {
    views: BTreeMap<u8, CameraSpec>,
}

impl Views {
    /// The view numbered `number`, if one is stored.
    pub fn get(&self, number: u8) -> Option<CameraSpec> {
        self.views.get(&number).copied()
    }

    /// Stores `camera` as view `number`, replacing any; a number outside [`VIEW_NUMBERS`] is an
    /// error.
    pub fn set(&mut self, number: u8, camera: CameraSpec) -> Result<(), String> {
        if !VIEW_NUMBERS.contains(&number) {
            return Err(format!(
                "view numbers are {} to {}, got {number}",
                VIEW_NUMBERS.start(),
                VIEW_NUMBERS.end()
            ));
        }
        self.views.insert(number, camera);
        Ok(())
    }

    /// The views with their numbers, in order.
    pub fn iter(&self) -> impl Iterator<Item = (u8, CameraSpec)> + '_ {
        self.views.iter().map(|(&n, &camera)| (n, camera))
    }

    /// The cameras in the order of their numbers: the stops of a [`path`].
    pub fn cameras(&self) -> Vec<CameraSpec> {
        self.views.values().copied().collect()
    }
}

/// Checks a sequence's frame count: from `least` to [`MAX_FRAMES`].
fn check_frames(frames: u32, least: u32, what: &str) -> Result<(), String> {
    if frames < least || frames > MAX_FRAMES {
        return Err(format!(
            "{what} takes {least} to {MAX_FRAMES} frames, got {frames}"
        ));
    }
    Ok(())
}

/// Builds each frame's camera, saying which frame is wrong if one cannot be built.
fn cameras(specs: impl Iterator<Item = CameraSpec>, what: &str) -> Result<Vec<Camera>, String> {
    specs
        .enumerate()
        .map(|(k, spec)| Camera::new(spec).map_err(|e| format!("frame {k} of the {what}: {e}")))
        .collect()
}

/// The cameras of a turntable of `frames` frames: the eye orbits the look-at point once, about
/// the camera's up axis through it (counter-clockwise seen from above), by 360°/`frames` a
/// frame, keeping its distance and height. Frame 0 is `camera` exactly. `frames` is 1 to
/// [`MAX_FRAMES`].
pub fn turntable(camera: &CameraSpec, frames: u32) -> Result<Vec<Camera>, String> {
    check_frames(frames, 1, "a turntable")?;
    let axis = camera.up.normalize_or_zero();
    let offset = camera.eye - camera.look_at;
    let specs = (0..frames).map(|k| {
        if k == 0 {
            return *camera;
        }
        let angle = std::f32::consts::TAU * k as f32 / frames as f32;
        CameraSpec {
            eye: camera.look_at + Quat::from_axis_angle(axis, angle) * offset,
            ..*camera
        }
    });
    cameras(specs, "turntable")
}

/// The cameras of a path of `frames` frames through `stops` in order: a Catmull-Rom spline
/// through the eyes and another through the look-at points (the end points doubled, so the path
/// starts and ends at the first and last stops), the up vector, view angle and near distance
/// going linearly from stop to stop. Each stretch between two stops gets the same share of the
/// frames; frame 0 is the first stop exactly and the last frame the last stop, and a frame that
/// falls on a stop is that stop. Needs at least 2 stops and 2 to [`MAX_FRAMES`] frames.
pub fn path(stops: &[CameraSpec], frames: u32) -> Result<Vec<Camera>, String> {
    if stops.len() < 2 {
        return Err(format!(
            "a camera path needs at least 2 views, got {}",
            stops.len()
        ));
    }
    check_frames(frames, 2, "a camera path")?;
    let stretches = stops.len() as u64 - 1;
    let last_frame = u64::from(frames) - 1;
    let specs = (0..u64::from(frames)).map(|k| {
        // Frame k is at stop (k · stretches / last_frame), kept as a whole part and a fraction.
        let position = k * stretches;
        let (i, rest) = ((position / last_frame) as usize, position % last_frame);
        if rest == 0 {
            return stops[i];
        }
        let t = rest as f32 / last_frame as f32;
        let stop = |j: isize| stops[j.clamp(0, stops.len() as isize - 1) as usize];
        let i = i as isize;
        let (p0, p1, p2, p3) = (stop(i - 1), stop(i), stop(i + 1), stop(i + 2));
        CameraSpec {
            eye: catmull_rom([p0.eye, p1.eye, p2.eye, p3.eye], t),
            look_at: catmull_rom([p0.look_at, p1.look_at, p2.look_at, p3.look_at], t),
            up: p1.up.normalize_or_zero().lerp(p2.up.normalize_or_zero(), t),
            view_angle: p1.view_angle + (p2.view_angle - p1.view_angle) * t,
            near: p1.near + (p2.near - p1.near) * t,
        }
    });
    cameras(specs, "path")
}

/// The uniform Catmull-Rom spline through `p[1]` (at t = 0) and `p[2]` (at t = 1), its
/// tangents there set by the points before and after.
fn catmull_rom(p: [Vec3; 4], t: f32) -> Vec3 {
    let (t2, t3) = (t * t, t * t * t);
    0.5 * (2.0 * p[1]
        + (p[2] - p[0]) * t
        + (2.0 * p[0] - 5.0 * p[1] + 4.0 * p[2] - p[3]) * t2
        + (3.0 * p[1] - p[0] - 3.0 * p[2] + p[3]) * t3)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> CameraSpec {
        CameraSpec {
            eye: Vec3::new(3.0, 2.0, 4.0),
            look_at: Vec3::new(1.0, 0.5, 0.0),
            up: Vec3::Y,
            view_angle: 40.0,
            near: 1.0,
        }
    }

    #[test]
    fn a_turntable_starts_on_the_camera_and_orbits_at_its_distance_and_height() {
        let frames = turntable(&camera(), 8).unwrap();
        assert_eq!(frames.len(), 8);
        assert_eq!(frames[0].spec, camera());
        let start = camera().eye - camera().look_at;
        let flat = |v: Vec3| Vec3::new(v.x, 0.0, v.z);
        for (k, frame) in frames.iter().enumerate() {
            let offset = frame.spec.eye - frame.spec.look_at;
            assert_eq!(frame.spec.look_at, camera().look_at);
            assert!((offset.length() - start.length()).abs() < 1e-4, "{k}");
            assert!(
                (offset.y - start.y).abs() < 1e-5,
                "frame {k} keeps its height"
            );
            // Turned k·45° counter-clockwise about +y (seen from above).
            let angle = flat(start).angle_between(flat(offset));
            let expected = (k as f32 * 45.0).min(360.0 - k as f32 * 45.0).to_radians();
            assert!((angle - expected).abs() < 1e-3, "frame {k}: {angle}");
            let turn = flat(start).cross(flat(offset)).y;
            assert!(
                k % 4 == 0 || (turn > 0.0) == (k < 4),
                "frame {k} turns the right way"
            );
        }
    }

    #[test]
    fn a_turntable_turns_about_a_tilted_up_axis() {
        let tilted = CameraSpec {
            up: Vec3::new(0.0, 1.0, 1.0),
            ..camera()
        };
        let axis = tilted.up.normalize();
        for frame in turntable(&tilted, 5).unwrap() {
            let offset = frame.spec.eye - frame.spec.look_at;
            let start = tilted.eye - tilted.look_at;
            assert!((offset.dot(axis) - start.dot(axis)).abs() < 1e-4);
        }
    }

    fn stops() -> Vec<CameraSpec> {
        vec![
            camera(),
            CameraSpec {
                eye: Vec3::new(-4.0, 1.0, 2.0),
                view_angle: 60.0,
                ..camera()
            },
            CameraSpec {
                eye: Vec3::new(0.0, 5.0, -6.0),
                look_at: Vec3::ZERO,
                view_angle: 30.0,
                near: 0.5,
                up: Vec3::new(0.1, 1.0, 0.0),
            },
        ]
    }

    #[test]
    fn a_path_starts_and_ends_on_its_views_and_passes_through_the_middle_one() {
        let frames = path(&stops(), 9).unwrap();
        assert_eq!(frames.len(), 9);
        assert_eq!(frames[0].spec, stops()[0]);
        assert_eq!(frames[4].spec, stops()[1]);
        assert_eq!(frames[8].spec, stops()[2]);
        // Between two stops: the view angle halfway, the eye near the chord's middle.
        let between = frames[2].spec;
        assert!((between.view_angle - 50.0).abs() < 1e-4);
        let middle = (stops()[0].eye + stops()[1].eye) * 0.5;
        assert!(between.eye.distance(middle) < 1.5, "{between:?}");
    }

    #[test]
    fn a_path_between_two_views_is_smooth_and_ends_on_them() {
        let two = &stops()[..2];
        let frames = path(two, 2).unwrap();
        assert_eq!(
            frames.iter().map(|c| c.spec).collect::<Vec<_>>(),
            two.to_vec()
        );
        let frames = path(two, 101).unwrap();
        let steps: Vec<f32> = frames
            .windows(2)
            .map(|w| w[0].spec.eye.distance(w[1].spec.eye))
            .collect();
        let longest = steps.iter().copied().fold(0.0, f32::max);
        assert!(longest < 0.2, "no jumps: {longest}");
    }

    #[test]
    fn bad_sequences_are_errors() {
        for (result, expected) in [
            (
                turntable(&camera(), 0),
                "a turntable takes 1 to 10000 frames, got 0",
            ),
            (turntable(&camera(), MAX_FRAMES + 1), "got 10001"),
            (path(&stops()[..1], 10), "at least 2 views, got 1"),
            (path(&[], 10), "at least 2 views, got 0"),
            (
                path(&stops(), 1),
                "a camera path takes 2 to 10000 frames, got 1",
            ),
        ] {
            let error = result.unwrap_err();
            assert!(error.contains(expected), "{error}");
        }
        // Halfway from a view to the same view upside down, the up vector is zero.
        let flipped = [
            camera(),
            CameraSpec {
                up: Vec3::NEG_Y,
                ..camera()
            },
        ];
        let error = path(&flipped, 3).unwrap_err();
        assert!(
            error.starts_with("frame 1 of the path: the up vector"),
            "{error}"
        );
    }

    #[test]
    fn views_are_numbered_1_to_9() {
        let mut views = Views::default();
        views.set(9, camera()).unwrap();
        views.set(2, stops()[1]).unwrap();
        assert_eq!(views.get(9), Some(camera()));
        assert_eq!(views.get(1), None);
        assert_eq!(views.cameras(), vec![stops()[1], camera()]);
        assert!(
            views
                .set(0, camera())
                .unwrap_err()
                .contains("1 to 9, got 0")
        );
        assert!(views.set(10, camera()).is_err());
    }
}
