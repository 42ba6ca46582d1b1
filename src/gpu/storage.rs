//! The storage buffers of a bind group, as its layout entries: what every pipeline of the GPU
//! tracer binds its records with.

/// A storage buffer at `binding` of a compute shader's bind group.
pub fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    storage_entry_in(binding, read_only, wgpu::ShaderStages::COMPUTE)
}

/// A storage buffer at `binding` of a bind group seen by `stages`.
pub fn storage_entry_in(
    binding: u32,
    read_only: bool,
    stages: wgpu::ShaderStages,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: stages,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}
