//! The scene as the controls show it: a copy of a loaded scene given the controls' camera,
//! settings, light intensity, debug view and edited materials and lights, and the caustic photon
//! map it is traced with. The threads that trace (the render worker, the ray tree thread) each
//! keep one, copied once per loaded scene and updated in place for each job, so that moving the
//! camera or editing a material copies no geometry (and keeps the BVH). The render worker's
//! copy also keeps the scene uploaded to the GPU, once the GPU is asked to render it or to draw
//! its item buffers.

use std::sync::Arc;
use std::time::Duration;

use raylab::film::Film;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::item_raster::CpuItems;
use raylab::item_buffer::ItemBuffer;
use raylab::photon::PhotonMap;
use raylab::progressive::gpu::GpuRenderer;
use raylab::render::{Assembled, FirstHit};
use raylab::whitted::Tracer;

use crate::viewer::scene::controls::TraceSetup;
use crate::viewer::scene::source::LoadedScene;

/// How long one of the GPU tracer's dispatches takes at most in the viewer: the window draws on
/// the same GPU, and its frame waits for the dispatch in flight, so a dispatch takes about a
/// frame's share at 60 frames a second.
const FRAME_SHARE: Duration = Duration::from_millis(12);

/// A thread's copy of the scene it traces.
#[derive(Default)]
pub struct WorkingScene {
    copy: Option<(Arc<LoadedScene>, Assembled)>,
    /// The copy's scene on the GPU, or why the GPU does not render it.
    on_gpu: Option<Result<GpuRenderer, String>>,
    /// The copy's scene on the GPU for the CPU tracer's item buffers, or why the GPU does not
    /// draw them.
    items: Option<Result<CpuItems, String>>,
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
            self.on_gpu = None;
            self.items = None;
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

    /// The item buffer of the copy (as the last [`Self::tracer`] made it) for `film`, drawn on
    /// `gpu`, where the scene is uploaded the first time it is asked for; the error says why the
    /// GPU does not draw it.
    pub fn item_buffer(&mut self, gpu: &Arc<GpuDevice>, film: &Film) -> Result<ItemBuffer, String> {
        let (_, copy) = self
            .copy
            .as_ref()
            .ok_or("no scene to draw the item buffer of")?;
        let items = self
            .items
            .get_or_insert_with(|| CpuItems::new(Arc::clone(gpu), copy))
            .as_ref()
            .map_err(|e| e.clone())?;
        items.draw(&copy.scene, (film.origin(), (film.width(), film.height())))
    }

    /// The copy (as the last [`Self::tracer`] made it) and the renderer of its scene on `gpu`,
    /// uploaded the first time it is asked for, with the copy's caustic photon map, its eye
    /// rays finding their first hits as `first_hit` says; the error says why the GPU does not
    /// render it.
    pub fn on_gpu(
        &mut self,
        gpu: &Arc<GpuDevice>,
        first_hit: FirstHit,
    ) -> Result<(&Assembled, &GpuRenderer), String> {
        let (_, copy) = self.copy.as_ref().ok_or("no scene to upload to the GPU")?;
        let renderer = self
            .on_gpu
            .get_or_insert_with(|| {
                let mut renderer = GpuRenderer::new(Arc::clone(gpu), copy)?;
                renderer.set_dispatch_time(FRAME_SHARE);
                Ok(renderer)
            })
            .as_mut()
            .map_err(|e| e.clone())?;
        renderer.set_caustics(copy.caustics.as_ref())?;
        renderer.set_first_hit(first_hit);
        Ok((copy, renderer))
    }
}
