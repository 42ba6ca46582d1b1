//! What the user controls: the camera, the render settings, the lights' intensity, the debug
//! view, and the scene's materials and lights as edited. The panels
//! and the navigation edit a [`Controls`]; whenever it differs from the one being rendered, the
//! app restarts refinement with it.

use raylab::camera::{Camera, CameraSpec};
use raylab::inspect::DebugView;
use raylab::light::Light;
use raylab::material::Material;
use raylab::render::{Device, FirstHit};
use raylab::scene::Scene;
use raylab::settings::{RenderSettings, SettingsOverrides};

use super::edits;

/// The viewer refines a scene that asks for one sample per pixel to a clean image: adaptive
/// anti-aliasing up to this many samples per pixel…
pub const VIEWER_SAMPLES: u32 = 16;
/// …where a pixel differs from a neighbour by more than this (see `RenderSettings::aa_threshold`).
pub const VIEWER_AA_THRESHOLD: f32 = 0.03;

/// What the controls change in a scene before it is traced.
#[derive(Clone, Debug)]
pub struct TraceSetup {
    pub camera: Camera,
    pub settings: RenderSettings,
    /// Multiplies the colour of every light of the scene.
    pub light_scale: f32,
    /// What the image shows.
    pub debug_view: DebugView,
    /// The scene's materials and lights as edited (the lights before `light_scale`).
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    /// The rounds of caustic photons the map holds already, of which the render wants one more
    /// (see `caustics`): 0 for a new render, which takes the map as it is if it has any.
    pub caustic_round: u32,
    /// Which tracer renders the shaded image (the debug views trace on the CPU).
    pub device: Device,
    /// Where the eye rays find their first hits.
    pub first_hit: FirstHit,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Controls {
    pub camera: CameraSpec,
    pub settings: RenderSettings,
    /// Multiplies the colour of every light of the scene.
    pub light_scale: f32,
    /// What the image shows: the shaded colour or a debug view.
    pub debug_view: DebugView,
    /// The scene's materials, index for index, as the Materials panel edits them.
    pub materials: Vec<Material>,
    /// The scene's lights, index for index, as the Lights panel edits them (before
    /// `light_scale`).
    pub lights: Vec<Light>,
    /// The viewer picks the starting block size from the tracing speed it measures; otherwise
    /// refinement starts at the settings' `block_size` (given on the command line or chosen in
    /// the panel).
    pub auto_block: bool,
    /// Which tracer renders the shaded image.
    pub device: Device,
    /// Where the eye rays find their first hits.
    pub first_hit: FirstHit,
}

impl Controls {
    /// The scene's own camera and settings, lights as the file says.
    pub fn from_scene(scene: &Scene) -> Controls {
        Controls {
            camera: scene.camera.spec,
            settings: scene.settings.clone(),
            light_scale: 1.0,
            debug_view: DebugView::Shaded,
            materials: scene.materials.clone(),
            lights: scene.lights.clone(),
            auto_block: true,
            device: Device::Cpu,
            first_hit: FirstHit::Rays,
        }
    }

    /// The scene's controls as the viewer starts them: its camera and settings with the command
    /// line's `overrides` applied, showing `debug_view`. The error says which override is wrong.
    ///
    /// Unlike `raylab render`, the viewer anti-aliases by default: when the scene asks for one
    /// sample per pixel and the command line gives neither `--samples` nor `--aa-threshold`, it
    /// refines up to [`VIEWER_SAMPLES`] with [`VIEWER_AA_THRESHOLD`]. A scene that asks for more
    /// samples, or either flag, is taken as it says.
    pub fn with_overrides(
        scene: &Scene,
        overrides: &SettingsOverrides,
        debug_view: DebugView,
    ) -> Result<Controls, String> {
        let mut controls = Controls::from_scene(scene);
        let sampling_given = overrides.samples.is_some() || overrides.aa_threshold.is_some();
        if !sampling_given && controls.settings.samples == 1 {
            controls.settings.samples = VIEWER_SAMPLES;
            controls.settings.aa_threshold = VIEWER_AA_THRESHOLD;
        }
        overrides.apply(&mut controls.settings)?;
        controls.camera = overrides.apply_camera(controls.camera)?.spec;
        controls.debug_view = debug_view;
        controls.auto_block = overrides.block_size.is_none();
        Ok(controls)
    }

    /// Whether the edited materials and lights can be traced (and saved); the error says which
    /// is wrong and how.
    pub fn check_edits(&self) -> Result<(), String> {
        for (index, material) in self.materials.iter().enumerate() {
            edits::check_material(material).map_err(|e| format!("material {index}: {e}"))?;
        }
        for (index, light) in self.lights.iter().enumerate() {
            edits::check_light(light).map_err(|e| format!("light {}: {e}", index + 1))?;
        }
        Ok(())
    }

    /// What these controls change in the scene, if they are all valid; otherwise what is wrong.
    /// `max_side` is the largest texture the GPU takes.
    pub fn setup(&self, max_side: u32) -> Result<TraceSetup, String> {
        self.settings.validate()?;
        let (w, h) = (self.settings.width, self.settings.height);
        if w > max_side || h > max_side {
            return Err(format!(
                "{w}×{h} is larger than this GPU's largest texture ({max_side} pixels a side)"
            ));
        }
        if !(self.light_scale.is_finite() && self.light_scale >= 0.0) {
            return Err(format!(
                "light intensity must be zero or more, got {}",
                self.light_scale
            ));
        }
        self.check_edits()?;
        Ok(TraceSetup {
            camera: Camera::new(self.camera).map_err(|e| format!("camera: {e}"))?,
            settings: self.settings.clone(),
            light_scale: self.light_scale,
            debug_view: self.debug_view,
            materials: self.materials.clone(),
            lights: self.lights.iter().map(edits::normalized).collect(),
            caustic_round: 0,
            device: self.device,
            first_hit: self.first_hit,
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn controls() -> Controls {
        let camera = Camera::new(CameraSpec::default()).unwrap();
        Controls::from_scene(&Scene::new(RenderSettings::default(), camera))
    }

    #[test]
    fn the_command_lines_overrides_apply_as_in_render() {
        let camera = Camera::new(CameraSpec::default()).unwrap();
        let scene = Scene::new(RenderSettings::default(), camera);
        let overrides = SettingsOverrides {
            width: Some(100),
            min_weight: Some(0.5),
            ..SettingsOverrides::default()
        };
        let c = Controls::with_overrides(&scene, &overrides, DebugView::Normals).unwrap();
        let mut expected = scene.settings.clone();
        overrides.apply(&mut expected).unwrap();
        (expected.samples, expected.aa_threshold) = (VIEWER_SAMPLES, VIEWER_AA_THRESHOLD);
        assert_eq!(c.settings, expected);
        assert_eq!((c.settings.width, c.settings.height), (100, 480));
        assert_eq!(c.settings.min_weight, 0.5);
        assert_eq!(c.debug_view, DebugView::Normals);
        assert!(c.auto_block, "no --block-size: the viewer picks it");
        let fixed_start = SettingsOverrides {
            block_size: Some(4),
            ..SettingsOverrides::default()
        };
        let c = Controls::with_overrides(&scene, &fixed_start, DebugView::Shaded).unwrap();
        assert!(!c.auto_block);
        assert_eq!(c.settings.block_size, 4);
        let looking = SettingsOverrides {
            eye: Some(Vec3::new(0.0, 1.0, 9.0)),
            view_angle: Some(20.0),
            ..SettingsOverrides::default()
        };
        let c = Controls::with_overrides(&scene, &looking, DebugView::Shaded).unwrap();
        assert_eq!(c.camera, looking.apply_camera(camera.spec).unwrap().spec);
        assert_eq!((c.camera.eye.z, c.camera.view_angle), (9.0, 20.0));
        let along_up = SettingsOverrides {
            up: Some(Vec3::Z),
            ..SettingsOverrides::default()
        };
        let error = Controls::with_overrides(&scene, &along_up, DebugView::Shaded).unwrap_err();
        assert!(error.contains("--up"), "{error}");
        let too_deep = SettingsOverrides {
            max_depth: Some(0),
            ..SettingsOverrides::default()
        };
        let error = Controls::with_overrides(&scene, &too_deep, DebugView::Shaded).unwrap_err();
        assert!(error.contains("max_depth"), "{error}");
    }

    #[test]
    fn valid_controls_give_their_camera() {
        let c = controls();
        assert_eq!(c.setup(4096).unwrap().camera.spec, c.camera);
    }

    #[test]
    fn bad_settings_cameras_and_sizes_are_reported() {
        let mut c = controls();
        c.camera.look_at = c.camera.eye;
        assert!(c.setup(4096).unwrap_err().contains("camera"));
        let mut c = controls();
        c.camera.up = Vec3::ZERO;
        assert!(c.setup(4096).is_err());
        let mut c = controls();
        c.settings.block_size = 3;
        assert!(c.setup(4096).unwrap_err().contains("block_size"));
        let mut c = controls();
        c.settings.width = 5000;
        assert!(c.setup(4096).unwrap_err().contains("largest texture"));
        let mut c = controls();
        c.light_scale = f32::NAN;
        assert!(c.setup(4096).is_err());
        let mut c = controls();
        c.materials.push(raylab::material::Material {
            transparency: 2.0,
            ..Default::default()
        });
        assert!(c.setup(4096).unwrap_err().contains("kt"));
        assert!(c.check_edits().unwrap_err().contains("material 0"));
    }

    #[test]
    fn the_viewer_anti_aliases_unless_the_scene_or_the_command_line_chose_the_sampling() {
        let camera = Camera::new(CameraSpec::default()).unwrap();
        let sampling = |samples, overrides: SettingsOverrides| {
            let settings = RenderSettings {
                samples,
                ..RenderSettings::default()
            };
            let scene = Scene::new(settings, camera);
            let c = Controls::with_overrides(&scene, &overrides, DebugView::Shaded).unwrap();
            (c.settings.samples, c.settings.aa_threshold)
        };
        let none = SettingsOverrides::default();
        assert_eq!(sampling(1, none), (16, 0.03), "one sample: refined");
        assert_eq!(sampling(4, none), (4, 0.0), "the scene's own anti-aliasing");
        let one = SettingsOverrides {
            samples: Some(1),
            ..none
        };
        assert_eq!(sampling(1, one), (1, 0.0), "--samples 1: one sample");
        let uniform = SettingsOverrides {
            aa_threshold: Some(0.0),
            ..none
        };
        assert_eq!(sampling(1, uniform), (1, 0.0), "--aa-threshold 0: uniform");
        let capped = SettingsOverrides {
            samples: Some(8),
            ..none
        };
        assert_eq!(sampling(1, capped), (8, 0.0), "--samples alone: uniform");
    }
}
