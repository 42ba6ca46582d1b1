//! The scene as the controls show it: a copy of a loaded scene given the controls' camera,
//! settings, light intensity, debug view and edited materials and lights, and the caustic photon map it is traced with. The
//! threads that trace (the render worker, the ray tree thread) each keep one, copied once per
//! loaded scene and updated in place for each job, so that moving the camera or editing a
//! material copies no geometry (and keeps the BVH).

use std::sync::Arc;

use raylab::camera::Camera;
use raylab::inspect::DebugView;
use raylab::light::Light;
use raylab::material::Material;
use raylab::photon::PhotonMap;
use raylab::render::Assembled;
use raylab::settings::RenderSettings;
use raylab::whitted::Tracer;

use crate::viewer::scene::source::LoadedScene;

/// What the controls change in a scene before it is traced.
#[derive(Clone, Debug)]
pub struct TraceSetup {
    pub camera: Camera,
    pub settings: RenderSettings,
    /// Multiplies the colour of every light of the scene.
    pub light_scale: f32,
    /// What the image shows.
    pub view: DebugView,
    /// The scene's materials and lights as edited (the lights before `light_scale`).
    pub materials: Vec<Material>,
    pub lights: Vec<Light>,
    /// The rounds of caustic photons the map holds already, of which the render wants one more
    /// (see `caustics`): 0 for a new view, which takes the map as it is if it has any.
    pub caustic_round: u32,
}

/// A thread's copy of the scene it traces.
#[derive(Default)]
pub struct WorkingScene {
    copy: Option<(Arc<LoadedScene>, Assembled)>,
}

impl WorkingScene {
    /// A tracer for `loaded` as `setup` shows it, adding the light of the photon map
    /// `caustics` if given.
    pub fn tracer<'a>(
        &'a mut self,
        loaded: &Arc<LoadedScene>,
        setup: &TraceSetup,
        caustics: Option<Arc<PhotonMap>>,
    ) -> Tracer<'a> {
        if !self
            .copy
            .as_ref()
            .is_some_and(|(copied, _)| Arc::ptr_eq(copied, loaded))
        {
            self.copy = None;
        }
        let (_, copy) = self
            .copy
            .get_or_insert_with(|| (loaded.clone(), loaded.assembled.clone()));
        copy.caustics = caustics;
        let scene = &mut copy.scene;
        scene.camera = setup.camera;
        scene.settings = setup.settings.clone();
        scene.materials.clone_from(&setup.materials);
        scene.lights = setup
            .lights
            .iter()
            .map(|l| l.scaled(setup.light_scale))
            .collect();
        copy.tracer()
    }
}
