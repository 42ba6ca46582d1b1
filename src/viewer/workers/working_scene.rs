//! The scene as the controls show it: a copy of a loaded scene given the controls' camera,
//! settings, light intensity, debug view and edited materials and lights, and the caustic photon
//! map it is traced with. The threads that trace (the render worker, the ray tree thread) each
//! keep one, copied once per loaded scene and updated in place for each job, so that moving the
//! camera or editing a material copies no geometry and keeps the BVH (and with it the scene the
//! render worker's [`raylab::progressive::Backend`] holds on the GPU).

use std::sync::Arc;

use raylab::photon::PhotonMap;
use raylab::render::Assembled;

use crate::viewer::scene::controls::TraceSetup;
use crate::viewer::scene::source::LoadedScene;

/// A thread's copy of the scene it traces.
#[derive(Default)]
pub struct WorkingScene {
    copy: Option<(Arc<LoadedScene>, Assembled)>,
}

impl WorkingScene {
    /// `loaded` as `setup` shows it, with the light of the photon map `caustics` if given.
    pub fn assembled(
        &mut self,
        loaded: &Arc<LoadedScene>,
        setup: &TraceSetup,
        caustics: Option<Arc<PhotonMap>>,
    ) -> &Assembled {
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
        copy
    }
}
