//! The shapes on the GPU: their WGSL (`shaders/shapes/`), the structs the GPU reads them in, and
//! a test entry point (`shaders/first_hits.wgsl`) that gives each ray its closest hit among a
//! list of shapes, tried one by one, to check the WGSL against the CPU's intersection on the
//! same rays.

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use super::device::{GpuDevice, read_buffer};
use crate::ray::Ray;
use crate::shapes::Sphere;

/// The shapes' WGSL and the test entry point, as one module.
pub const FIRST_HITS_WGSL: &str = concat!(
    include_str!("../../shaders/shapes/sphere.wgsl"),
    include_str!("../../shaders/first_hits.wgsl"),
);

/// WGSL's `Sphere`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuSphere {
    pub center: [f32; 3],
    pub radius: f32,
}

impl From<&Sphere> for GpuSphere {
    fn from(s: &Sphere) -> GpuSphere {
        GpuSphere {
            center: s.center.to_array(),
            radius: s.radius,
        }
    }
}

/// WGSL's `Ray`: a ray and the range of `t` it looks in.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuRay {
    pub origin: [f32; 3],
    pub t_min: f32,
    pub dir: [f32; 3],
    pub t_max: f32,
}

impl GpuRay {
    pub fn new(ray: &Ray, t_min: f32, t_max: f32) -> GpuRay {
        GpuRay {
            origin: ray.origin.to_array(),
            t_min,
            dir: ray.dir.to_array(),
            t_max,
        }
    }
}

/// WGSL's `Hit`: the closest hit's `t` and the index of its shape ([`NO_OBJECT`]: none, `t`
/// is then the ray's `t_max`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuHit {
    pub t: f32,
    pub object: u32,
}

/// [`GpuHit::object`] of a ray that hits nothing.
pub const NO_OBJECT: u32 = u32::MAX;

/// Invocations per workgroup of the entry point (`@workgroup_size`).
const WORKGROUP: u32 = 64;

/// Each ray's closest hit among `spheres` (by index), traced on the GPU. The error says what
/// does not fit the GPU, or that it failed.
pub fn first_hits(
    gpu: &GpuDevice,
    spheres: &[Sphere],
    rays: &[GpuRay],
) -> Result<Vec<GpuHit>, String> {
    let miss = |r: &GpuRay| GpuHit {
        t: r.t_max,
        object: NO_OBJECT,
    };
    if spheres.is_empty() || rays.is_empty() {
        return Ok(rays.iter().map(miss).collect());
    }
    let spheres: Vec<GpuSphere> = spheres.iter().map(GpuSphere::from).collect();
    let hits_bytes = (rays.len() * std::mem::size_of::<GpuHit>()) as u64;
    gpu.check_storage("the spheres", std::mem::size_of_val(&spheres[..]) as u64)?;
    gpu.check_storage("the rays", std::mem::size_of_val(rays) as u64)?;
    gpu.check_storage("their hits", hits_bytes)?;
    let groups = (rays.len() as u64).div_ceil(u64::from(WORKGROUP));
    let max_groups = u64::from(gpu.device.limits().max_compute_workgroups_per_dimension);
    if groups > max_groups {
        return Err(format!(
            "{} rays need {groups} workgroups of {WORKGROUP}; the GPU runs at most {max_groups}",
            rays.len()
        ));
    }
    let device = &gpu.device;
    let storage = |label, contents: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage: wgpu::BufferUsages::STORAGE,
        })
    };
    let sphere_buffer = storage("spheres", bytemuck::cast_slice(&spheres));
    let ray_buffer = storage("rays", bytemuck::cast_slice(rays));
    let hit_buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("hits"),
        size: hits_bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read_back = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("hits read back"),
        size: hits_bytes,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("first_hits.wgsl"),
        source: wgpu::ShaderSource::Wgsl(FIRST_HITS_WGSL.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("first hits"),
        layout: None,
        module: &module,
        entry_point: Some("first_hits"),
        compilation_options: Default::default(),
        cache: None,
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("first hits"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: sphere_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: ray_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: hit_buffer.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(groups as u32, 1, 1);
    }
    encoder.copy_buffer_to_buffer(&hit_buffer, 0, &read_back, 0, hits_bytes);
    gpu.queue.submit([encoder.finish()]);
    let bytes = read_buffer(&gpu.device, &read_back)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
