//! Render settings: image size, the ray tree's limits, progressive refinement and the switches
//! that turn parts of the shading off (for teaching and for the viewer), and the overrides of
//! them and of the camera that `render`, `inspect` and the viewer take from the command line.

use glam::Vec3;

use crate::camera::{Camera, CameraError, CameraSpec};
use crate::color::Color;
use crate::limits;

/// Largest starting block size.
pub const MAX_BLOCK_SIZE: u32 = 64;
/// Deepest ray tree allowed.
pub const MAX_DEPTH_LIMIT: u32 = 64;
/// Most samples per pixel.
pub const MAX_SAMPLES: u32 = 4096;
/// Most steps along a ray through fog.
pub const MAX_FOG_STEPS: u32 = 1024;
/// Most caustic photons: a hundred million, a few gigabytes of photon map.
pub const MAX_CAUSTIC_PHOTONS: u32 = 100_000_000;
/// Most photons one caustic estimate gathers.
pub const MAX_CAUSTIC_GATHER: u32 = 512;

#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Deepest level of the ray tree; the eye ray is depth 1.
    pub max_depth: u32,
    /// Adaptive depth control: a branch whose weight (product of the reflection and transmission
    /// coefficients from the eye) falls below this is not traced. 0 turns it off.
    pub min_weight: f32,
    /// Starting block size of progressive refinement: a power of two from 1 to 64.
    pub block_size: u32,
    /// Samples per pixel; more than 1 adds jittered samples after the block size 1 pass. With an
    /// `aa_threshold` it is the cap: the most samples any pixel takes.
    pub samples: u32,
    /// Adaptive anti-aliasing: after block size 1, only pixels whose displayed colour differs
    /// from a neighbour's by more than this (in any channel, on the 0–1 scale of the 8-bit
    /// sRGB values saved and shown) take more samples, in rounds up to `samples`
    /// ([`crate::progressive`]). 0: every pixel takes `samples` samples (uniform sampling).
    pub aa_threshold: f32,
    pub background: Color,
    /// Global ambient light.
    pub ambient: Color,
    pub shadows: bool,
    pub reflections: bool,
    /// Whether transmitted rays are traced (through transparent objects, `kt > 0`).
    pub transmission: bool,
    pub textures: bool,
    /// Sample points along each ray through fog where the light scattered into it is gathered
    /// (one shadow ray per light from each); only scenes with an `[atmosphere]` use it.
    pub fog_steps: u32,
    /// Photons shot for the caustic photon map; 0 turns caustics off.
    pub caustic_photons: u32,
    /// Photons each caustic estimate gathers (1 to [`MAX_CAUSTIC_GATHER`]).
    pub caustic_gather: u32,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 640,
            height: 480,
            max_depth: 5,
            min_weight: 0.01,
            block_size: 16,
            samples: 1,
            aa_threshold: 0.0,
            background: Color::new(0.05, 0.05, 0.08),
            ambient: Color::splat(0.2),
            shadows: true,
            reflections: true,
            transmission: true,
            textures: true,
            fog_steps: 16,
            caustic_photons: 0,
            caustic_gather: 64,
        }
    }
}

impl RenderSettings {
    /// Checks every setting; the message says what is wrong and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        limits::check_image_size(self.width, self.height)?;
        if self.max_depth == 0 || self.max_depth > MAX_DEPTH_LIMIT {
            return Err(format!(
                "max_depth must be between 1 and {MAX_DEPTH_LIMIT}, got {}",
                self.max_depth
            ));
        }
        if !(0.0..=1.0).contains(&self.min_weight) {
            return Err(format!(
                "min_weight must be between 0 and 1, got {}",
                self.min_weight
            ));
        }
        if !self.block_size.is_power_of_two() || self.block_size > MAX_BLOCK_SIZE {
            return Err(format!(
                "block_size must be a power of two from 1 to {MAX_BLOCK_SIZE}, got {}",
                self.block_size
            ));
        }
        if self.samples == 0 || self.samples > MAX_SAMPLES {
            return Err(format!(
                "samples must be between 1 and {MAX_SAMPLES}, got {}",
                self.samples
            ));
        }
        if !(0.0..=1.0).contains(&self.aa_threshold) {
            return Err(format!(
                "aa_threshold must be between 0 (uniform sampling) and 1, got {}",
                self.aa_threshold
            ));
        }
        if self.fog_steps == 0 || self.fog_steps > MAX_FOG_STEPS {
            return Err(format!(
                "fog_steps must be between 1 and {MAX_FOG_STEPS}, got {}",
                self.fog_steps
            ));
        }
        if self.caustic_photons > MAX_CAUSTIC_PHOTONS {
            return Err(format!(
                "caustic_photons must be at most {MAX_CAUSTIC_PHOTONS}, got {}",
                self.caustic_photons
            ));
        }
        if self.caustic_gather == 0 || self.caustic_gather > MAX_CAUSTIC_GATHER {
            return Err(format!(
                "caustic_gather must be between 1 and {MAX_CAUSTIC_GATHER}, got {}",
                self.caustic_gather
            ));
        }
        Ok(())
    }
}

/// Changes to a scene's render settings and camera from outside its file (the command line's
/// `--width`, `--max-depth`, `--eye`, …), the same for `render`, `inspect` and the viewer. Each
/// `None` keeps the scene's own value: a width alone keeps the scene's height, an eye alone the
/// scene's look-at point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SettingsOverrides {
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub max_depth: Option<u32>,
    pub min_weight: Option<f32>,
    pub block_size: Option<u32>,
    pub samples: Option<u32>,
    pub aa_threshold: Option<f32>,
    pub fog_steps: Option<u32>,
    pub caustic_photons: Option<u32>,
    pub caustic_gather: Option<u32>,
    pub eye: Option<Vec3>,
    pub look_at: Option<Vec3>,
    pub up: Option<Vec3>,
    /// Vertical, in degrees.
    pub view_angle: Option<f32>,
}

impl SettingsOverrides {
    /// Applies the overrides to `settings` and checks the result.
    pub fn apply(&self, settings: &mut RenderSettings) -> Result<(), String> {
        let s = settings;
        s.width = self.width.unwrap_or(s.width);
        s.height = self.height.unwrap_or(s.height);
        s.max_depth = self.max_depth.unwrap_or(s.max_depth);
        s.min_weight = self.min_weight.unwrap_or(s.min_weight);
        s.block_size = self.block_size.unwrap_or(s.block_size);
        s.samples = self.samples.unwrap_or(s.samples);
        s.aa_threshold = self.aa_threshold.unwrap_or(s.aa_threshold);
        s.fog_steps = self.fog_steps.unwrap_or(s.fog_steps);
        s.caustic_photons = self.caustic_photons.unwrap_or(s.caustic_photons);
        s.caustic_gather = self.caustic_gather.unwrap_or(s.caustic_gather);
        s.validate()
    }

    /// The camera `spec` with the camera overrides applied, checked as a scene file's camera is.
    pub fn apply_camera(&self, spec: CameraSpec) -> Result<Camera, String> {
        Camera::new(CameraSpec {
            eye: self.eye.unwrap_or(spec.eye),
            look_at: self.look_at.unwrap_or(spec.look_at),
            up: self.up.unwrap_or(spec.up),
            view_angle: self.view_angle.unwrap_or(spec.view_angle),
            near: spec.near,
        })
        .map_err(camera_error)
    }

    /// Checks the camera overrides that are wrong whatever the scene's camera (before a scene is
    /// read): a view angle out of range, an eye or look-at point out of range, both given and
    /// equal, an up vector of zero or, with both points given, along the view.
    pub fn check_camera(&self) -> Result<(), String> {
        // With a point not given, the view goes across the up vector (seen from the origin),
        // which is right for any up vector but zero; the point given is checked after, in the
        // order the camera checks its own.
        let default = CameraSpec::default();
        let up = self.up.unwrap_or(default.up);
        let (eye, look_at) = match (self.eye, self.look_at) {
            (Some(eye), Some(look_at)) => (eye, look_at),
            _ => (Vec3::ZERO, up.normalize_or_zero().any_orthonormal_vector()),
        };
        let spec = CameraSpec {
            eye,
            look_at,
            up,
            view_angle: self.view_angle.unwrap_or(default.view_angle),
            near: default.near,
        };
        Camera::new(spec).map_err(camera_error)?;
        if let Some(eye) = self.eye.filter(|&p| !limits::within_range(p)) {
            return Err(camera_error(CameraError::Eye(eye)));
        }
        if let Some(look_at) = self.look_at.filter(|&p| !limits::within_range(p)) {
            return Err(camera_error(CameraError::LookAt(look_at)));
        }
        Ok(())
    }
}

/// The message of a camera override that cannot be: the camera's own, after the flags it is about.
fn camera_error(error: CameraError) -> String {
    let flags = match error {
        CameraError::EyeAtLookAt => "--eye, --look-at",
        CameraError::UpParallelToView => "--up",
        CameraError::ViewAngle(_) => "--view-angle",
        CameraError::Eye(_) => "--eye",
        CameraError::LookAt(_) => "--look-at",
        CameraError::Near(_) => "camera",
    };
    format!("{flags}: {error}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_change_only_what_they_give() {
        let mut settings = RenderSettings::default();
        let overrides = SettingsOverrides {
            width: Some(100),
            min_weight: Some(0.5),
            fog_steps: Some(4),
            ..SettingsOverrides::default()
        };
        overrides.apply(&mut settings).unwrap();
        let expected = RenderSettings {
            width: 100,
            min_weight: 0.5,
            fog_steps: 4,
            ..RenderSettings::default()
        };
        assert_eq!(settings, expected, "a width alone keeps the height");
    }

    #[test]
    fn camera_overrides_change_only_what_they_give() {
        let spec = CameraSpec::default();
        let overrides = SettingsOverrides {
            eye: Some(Vec3::new(1.0, 2.0, 3.0)),
            view_angle: Some(30.0),
            ..SettingsOverrides::default()
        };
        let camera = overrides.apply_camera(spec).unwrap();
        let expected = CameraSpec {
            eye: Vec3::new(1.0, 2.0, 3.0),
            view_angle: 30.0,
            ..spec
        };
        assert_eq!(camera.spec, expected);
        assert!(overrides.check_camera().is_ok());
        assert!(SettingsOverrides::default().check_camera().is_ok());
        // A point alone, however far, is right for some scene.
        for eye in [Vec3::new(1e9, 0.0, 0.0), Vec3::new(0.0, 5.0, 0.0)] {
            let far = SettingsOverrides {
                eye: Some(eye),
                ..SettingsOverrides::default()
            };
            assert!(far.check_camera().is_ok(), "{eye}");
        }
    }

    #[test]
    fn camera_overrides_are_checked_with_the_scenes_camera_and_alone() {
        let looking_down = SettingsOverrides {
            look_at: Some(Vec3::new(0.0, -10.0, 5.0)),
            ..SettingsOverrides::default()
        };
        // Alone it may be right; with the default camera's eye at (0, 0, 5) it looks along up.
        assert!(looking_down.check_camera().is_ok());
        let error = looking_down
            .apply_camera(CameraSpec::default())
            .unwrap_err();
        assert!(
            error.starts_with("--up: the up vector is parallel"),
            "{error}"
        );
        let wrong_alone = [
            (
                Some(Vec3::ONE),
                Some(Vec3::ONE),
                None,
                None,
                "--eye, --look-at:",
            ),
            (None, None, Some(Vec3::ZERO), None, "--up:"),
            (Some(Vec3::Y), Some(Vec3::ZERO), None, None, "--up:"),
            (None, None, None, Some(0.0), "--view-angle:"),
            (None, Some(Vec3::splat(1e16)), None, None, "--look-at:"),
            (
                Some(Vec3::X),
                Some(Vec3::splat(1e16)),
                None,
                None,
                "--look-at:",
            ),
            (Some(Vec3::splat(-2e15)), None, None, None, "--eye:"),
        ];
        for (eye, look_at, up, view_angle, flags) in wrong_alone {
            let overrides = SettingsOverrides {
                eye,
                look_at,
                up,
                view_angle,
                ..SettingsOverrides::default()
            };
            let error = overrides.check_camera().unwrap_err();
            assert!(error.starts_with(flags), "{error}");
        }
    }

    #[test]
    fn overridden_settings_are_checked() {
        let mut settings = RenderSettings::default();
        let overrides = SettingsOverrides {
            block_size: Some(3),
            ..SettingsOverrides::default()
        };
        let error = overrides.apply(&mut settings).unwrap_err();
        assert!(error.contains("block_size"), "{error}");
    }
}
