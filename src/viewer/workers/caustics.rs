//! The caustic photon map the viewer traces with. The render worker makes it when the scene,
//! its light intensity, its materials or lights (as edited), the photon count or the specular switches change, and not when the
//! camera moves or the gather count changes: the map does not depend on them. While the view
//! stays still it grows, a round at a time, each round shooting the photon count again, so the
//! estimates gather from nearer and the caustics sharpen (progressive photon mapping). The ray
//! tree thread borrows the worker's map and never shoots photons itself.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use raylab::light::Light;
use raylab::material::Material;
use raylab::photon::{Caustics, PhotonMap};
use raylab::whitted::Tracer;

use crate::viewer::scene::controls::TraceSetup;
use crate::viewer::scene::source::LoadedScene;

/// The most rounds of photons the viewer shoots for one view: the map grows to this many
/// times the photon count, then the viewer rests.
pub const MAX_ROUNDS: u32 = 8;

/// What a map depends on: the scene (by address), its light intensity, its materials and lights
/// as edited, the photons shot per round, and whether reflected and transmitted photons are
/// followed.
#[derive(Clone, Debug, PartialEq)]
struct MapKey {
    scene: usize,
    light_scale: f32,
    materials: Vec<Material>,
    lights: Vec<Light>,
    photons: u32,
    reflections: bool,
    transmission: bool,
}

impl MapKey {
    fn new(loaded: &Arc<LoadedScene>, setup: &TraceSetup) -> MapKey {
        MapKey {
            scene: Arc::as_ptr(loaded) as usize,
            light_scale: setup.light_scale,
            materials: setup.materials.clone(),
            lights: setup.lights.clone(),
            photons: setup.settings.caustic_photons,
            reflections: setup.settings.reflections,
            transmission: setup.settings.transmission,
        }
    }
}

/// Photons shot for a job, for the status line and `--stats`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shot {
    /// Photons shot for the map in all.
    pub photons: u32,
    /// Of them, shot for this job (all of them for a new map).
    pub added: u32,
    pub new_map: bool,
    pub time: Duration,
}

impl std::fmt::Display for Shot {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        let what = if self.new_map { "new map" } else { "sharpened" };
        write!(
            f,
            "caustics: {what}, {} photons ({} shot) in {:.1} ms",
            self.photons,
            self.added,
            self.time.as_secs_f64() * 1e3
        )
    }
}

/// The map a job traces with, and the photons shot for it.
pub struct JobMap {
    pub map: Arc<PhotonMap>,
    pub shot: Option<Shot>,
}

/// The photons shot for a map, the rounds they came in, and the map they make.
struct Grown {
    key: MapKey,
    caustics: Caustics,
    rounds: u32,
    map: Arc<PhotonMap>,
}

/// The worker's caustic map, shared with the ray tree thread.
#[derive(Clone, Default)]
pub struct SharedCaustics(Arc<Mutex<Option<Grown>>>);

impl SharedCaustics {
    /// The map for `loaded` set up as `setup`, with `setup.caustic_round + 1` rounds of photons
    /// shot by `tracer` (on the current thread pool): the map made before when it fits, grown
    /// when it has fewer rounds, made anew when the scene or the photon count changed. `None`
    /// with caustics off; the error says the photons would not fit in memory.
    pub fn grow(
        &self,
        loaded: &Arc<LoadedScene>,
        setup: &TraceSetup,
        tracer: &Tracer,
    ) -> Result<Option<JobMap>, String> {
        let photons = setup.settings.caustic_photons;
        if photons == 0 {
            return Ok(None);
        }
        let key = MapKey::new(loaded, setup);
        let mut grown = self.0.lock().map_err(|_| "the caustic map was lost")?;
        let start = Instant::now();
        let new_map = !grown.as_ref().is_some_and(|g| g.key == key);
        if new_map {
            *grown = Some(Grown {
                key,
                caustics: Caustics::new(tracer),
                rounds: 0,
                map: Arc::new(PhotonMap::default()),
            });
        }
        let grown = grown.as_mut().expect("just made");
        let wanted = (setup.caustic_round + 1).min(MAX_ROUNDS);
        let mut added = 0;
        while grown.rounds < wanted {
            grown.caustics.shoot(tracer, photons)?;
            grown.rounds += 1;
            added += photons;
        }
        if added > 0 {
            grown.map = Arc::new(grown.caustics.map()?);
        }
        let shot = (added > 0).then(|| Shot {
            photons: grown.caustics.shot(),
            added,
            new_map,
            time: start.elapsed(),
        });
        Ok(Some(JobMap {
            map: grown.map.clone(),
            shot,
        }))
    }

    /// The map the worker made for `loaded` as `setup` shows it, if it has made one.
    pub fn current(&self, loaded: &Arc<LoadedScene>, setup: &TraceSetup) -> Option<Arc<PhotonMap>> {
        let key = MapKey::new(loaded, setup);
        let grown = self.0.lock().ok()?;
        grown
            .as_ref()
            .filter(|g| g.key == key && setup.settings.caustic_photons > 0)
            .map(|g| g.map.clone())
    }
}
