//! The GPU tracer: the WGSL of every part as one module, its pipelines, and the colours of a
//! list of pixel samples, traced by the ray tree on the GPU in dispatches small enough for an
//! operating system's GPU watchdog.

use super::record::gpu_record;
use bytemuck::Pod;
use wgpu::util::DeviceExt;

use std::sync::Arc;

use super::bvh::NodeLayout;
use super::device::{ComputeEntry, GpuDevice, read_buffer};
use super::prelude::{WORKGROUP, WorkBinding, prelude};
use super::scene::{GpuScene, scene_layout};
use super::shapes::shapes_wgsl;
use super::storage::storage_entry;

/// All the GPU tracer's WGSL but the prelude, the shapes' ([`shapes_wgsl`]) and the BVH's nodes'
/// ([`NodeLayout::wgsl`]), which go with it into one module: the scene's records, the camera
/// and the jitter, the triangles, the BVH's walk, the textures, the caustic photons, the
/// shading, the cut-outs, the media and the ray tree, the debug views, and the entry points.
pub const TRACER_WGSL: &str = concat!(
    include_str!("../../shaders/scene.wgsl"),
    include_str!("../../shaders/samples.wgsl"),
    include_str!("../../shaders/sampling.wgsl"),
    include_str!("../../shaders/camera.wgsl"),
    include_str!("../../shaders/shapes/triangle.wgsl"),
    include_str!("../../shaders/bvh/traverse.wgsl"),
    include_str!("../../shaders/primitive.wgsl"),
    include_str!("../../shaders/noise.wgsl"),
    include_str!("../../shaders/texture.wgsl"),
    include_str!("../../shaders/whitted/scattering.wgsl"),
    include_str!("../../shaders/caustics.wgsl"),
    include_str!("../../shaders/whitted/lighting.wgsl"),
    include_str!("../../shaders/whitted/cut_outs.wgsl"),
    include_str!("../../shaders/medium.wgsl"),
    include_str!("../../shaders/whitted/fog.wgsl"),
    include_str!("../../shaders/whitted/trace.wgsl"),
    include_str!("../../shaders/views.wgsl"),
    include_str!("../../shaders/trace_samples.wgsl"),
    include_str!("../../shaders/probe.wgsl"),
);

gpu_record! {
    /// WGSL's `PixelSample`: sample `k` of film pixel (x, y), and the distance `item_t` of its
    /// pixel's item in the item buffer, to which its eye ray's first search looks (0: none, all the
    /// way).
    pub struct PixelSample {
        pub x: u32,
        pub y: u32,
        pub k: u32,
        pub item_t: f32,
    }
}

gpu_record! {
    /// WGSL's `SampleColor`: a sample's colour and the rays its tree traced, or that the driver
    /// cut its work short (`cut_short` 1: a driver may bound the loop iterations of a shader, as
    /// Mesa's llvmpipe does at 65535, and the sample must be traced again).
    pub struct SampleColor {
        pub color: [f32; 3],
        pub primary_hits: u32,
        pub shadow: u32,
        pub reflected: u32,
        pub transmitted: u32,
        pub over_budget: u32,
        pub cut_short: u32,
        /// 1 where the eye ray's first hit is its pixel's item in the item buffer.
        pub from_item_buffer: u32,
        pub pad1: u32,
        pub pad2: u32,
    }
}

/// The compute pipeline of WGSL entry point `entry` of the GPU tracer's module on `gpu`, for
/// the BVH's nodes in `nodes`: bind group 0 the scene (any [`GpuScene`]'s of that layout: wgpu
/// takes equal layouts as one), bind group 1 a list read and a list written. It is compiled the
/// first time it is asked for on `gpu`.
pub fn pipeline(gpu: &GpuDevice, entry: &'static str, nodes: NodeLayout) -> Arc<ComputeEntry> {
    let module = match nodes {
        NodeLayout::Wide => "tracer, wide nodes",
        NodeLayout::Binary => "tracer, binary nodes",
    };
    gpu.pipeline((module, entry), |device| compile(device, entry, nodes))
}

/// All the tracer's WGSL, for the BVH's nodes in `nodes`, after the prelude.
pub fn tracer_wgsl(nodes: NodeLayout) -> String {
    prelude() + &shapes_wgsl() + &nodes.wgsl() + TRACER_WGSL
}

/// Compiles `entry` of all the tracer's WGSL for `device`.
fn compile(device: &wgpu::Device, entry: &str, nodes: NodeLayout) -> ComputeEntry {
    let source = tracer_wgsl(nodes);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("the GPU tracer"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let work = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(entry),
        entries: &[
            storage_entry(WorkBinding::Input as u32, true),
            storage_entry(WorkBinding::Output as u32, false),
        ],
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(entry),
        bind_group_layouts: &[
            Some(&scene_layout(device, wgpu::ShaderStages::COMPUTE)),
            Some(&work),
        ],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry),
        layout: Some(&layout),
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    });
    ComputeEntry { pipeline, work }
}

/// A list on the GPU: its entries, and a buffer for one result per entry.
pub struct WorkList {
    pub input: wgpu::Buffer,
    pub output: wgpu::Buffer,
    pub len: usize,
}

/// Uploads `input` and makes a buffer of `out_bytes` for its results (which may also be written
/// from the CPU, for results made there); the error says if either
/// does not fit the GPU, or the list needs more workgroups than one dispatch runs.
pub fn upload_list<In: Pod>(
    gpu: &GpuDevice,
    input: &[In],
    out_bytes: u64,
) -> Result<WorkList, String> {
    let device = &gpu.device;
    gpu.check_storage("the work list", std::mem::size_of_val(input) as u64)?;
    gpu.check_storage("its results", out_bytes)?;
    let groups = (input.len() as u64).div_ceil(u64::from(WORKGROUP));
    let max_groups = u64::from(device.limits().max_compute_workgroups_per_dimension);
    if groups > max_groups {
        return Err(format!(
            "{} entries need {groups} workgroups of {WORKGROUP}; the GPU runs at most {max_groups}",
            input.len()
        ));
    }
    let input_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("work list"),
        contents: bytemuck::cast_slice(input),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("work results"),
        size: out_bytes,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    Ok(WorkList {
        input: input_buffer,
        output,
        len: input.len(),
    })
}

/// Encodes `entry` run over `list` (one invocation per entry) into `encoder`.
pub fn dispatch_list(
    gpu: &GpuDevice,
    scene: &GpuScene,
    ComputeEntry { pipeline, work }: &ComputeEntry,
    list: &WorkList,
    encoder: &mut wgpu::CommandEncoder,
) {
    let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("work"),
        layout: work,
        entries: &[
            wgpu::BindGroupEntry {
                binding: WorkBinding::Input as u32,
                resource: list.input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: WorkBinding::Output as u32,
                resource: list.output.as_entire_binding(),
            },
        ],
    });
    let mut pass = encoder.begin_compute_pass(&Default::default());
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, &scene.bind_group, &[]);
    pass.set_bind_group(1, &bind_group, &[]);
    pass.dispatch_workgroups((list.len as u32).div_ceil(WORKGROUP), 1, 1);
}

/// Runs `entry` over `input` (one invocation per entry) and reads back one `Out` per entry.
pub fn run_list<In: Pod, Out: Pod>(
    gpu: &GpuDevice,
    scene: &GpuScene,
    entry: &ComputeEntry,
    input: &[In],
) -> Result<Vec<Out>, String> {
    if input.is_empty() {
        return Ok(Vec::new());
    }
    let device = &gpu.device;
    let out_bytes = (input.len() * std::mem::size_of::<Out>()) as u64;
    let list = upload_list(gpu, input, out_bytes)?;
    let read_back = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("work results read back"),
        size: out_bytes,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    dispatch_list(gpu, scene, entry, &list, &mut encoder);
    encoder.copy_buffer_to_buffer(&list.output, 0, &read_back, 0, out_bytes);
    gpu.queue.submit([encoder.finish()]);
    let bytes = read_buffer(device, &read_back)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}
