//! Test entry points (`shaders/probe.wgsl`) that check the GPU's parts against the CPU's on the
//! same input: each ray's closest hit among all objects tried one by one, which checks the
//! shapes' WGSL, and through the BVH, which checks the walk and the triangles too; with the
//! surface there; and the colours of the scene's textures at given points.

use super::record::gpu_record;

use super::device::GpuDevice;
use super::scene::GpuScene;
use super::tracer::{pipeline, run_list};
use crate::ray::Ray;

gpu_record! {
    /// WGSL's `ProbeRay`: a ray and the range of `t` it looks in.
    pub struct ProbeRay {
        pub origin: [f32; 3],
        pub t_min: f32,
        pub dir: [f32; 3],
        pub t_max: f32,
    }
}

impl ProbeRay {
    pub fn new(ray: &Ray, t_min: f32, t_max: f32) -> ProbeRay {
        ProbeRay {
            origin: ray.origin.to_array(),
            t_min,
            dir: ray.dir.to_array(),
            t_max,
        }
    }
}

gpu_record! {
    /// WGSL's `ProbeHit`: the closest hit's `t` (the ray's `t_max` for none), its primitive's
    /// [`crate::primitive::PrimId`] ([`NO_PRIM`] for none) and part, and the unit world normal and
    /// texture coordinates there.
    pub struct ProbeHit {
        pub normal: [f32; 3],
        pub t: f32,
        pub uv: [f32; 2],
        pub prim: u32,
        pub part: u32,
    }
}

/// [`ProbeHit::prim`] of a ray that hits nothing.
pub const NO_PRIM: u32 = u32::MAX;

/// Which of the probe's searches to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Search {
    /// Every object tried one by one (meshes left out).
    Objects,
    /// The walk through the BVH.
    Bvh,
}

/// Each ray's closest hit in `scene` by `search`, found on the GPU.
pub fn closest_hits(
    gpu: &GpuDevice,
    scene: &GpuScene,
    search: Search,
    rays: &[ProbeRay],
) -> Result<Vec<ProbeHit>, String> {
    let entry = match search {
        Search::Objects => "probe_objects",
        Search::Bvh => "probe_bvh",
    };
    run_list(gpu, scene, &pipeline(gpu, entry, scene.node_layout), rays)
}

gpu_record! {
    /// WGSL's `TextureProbe`: where to colour texture `texture` of the scene.
    pub struct TextureProbe {
        pub point: [f32; 3],
        pub texture: u32,
        pub uv: [f32; 2],
        pub pad0: u32,
        pub pad1: u32,
    }
}

/// The colour of each probe's texture at its texture coordinates and object point, found on the
/// GPU (the fourth component is 0).
pub fn texture_colors(
    gpu: &GpuDevice,
    scene: &GpuScene,
    probes: &[TextureProbe],
) -> Result<Vec<[f32; 4]>, String> {
    run_list(
        gpu,
        scene,
        &pipeline(gpu, "probe_textures", scene.node_layout),
        probes,
    )
}
