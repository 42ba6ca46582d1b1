//! Screenshots of the window as drawn: the frame is painted once more into an offscreen texture of
//! the surface's size and format, read back to the CPU and written as a PNG. Reading back the
//! app's own frame avoids racing the window system (a capture after the app exits is black).

use std::path::Path;

use raylab::gpu::device::read_buffer;

use super::device::Gpu;
use super::painter::{FrameContent, Painter};

/// Paints `content` offscreen at `size` and saves it as a PNG at `path`.
pub fn save(
    gpu: &Gpu,
    painter: &mut Painter,
    format: wgpu::TextureFormat,
    size: (u32, u32),
    content: &FrameContent<'_>,
    path: &Path,
) -> Result<(), String> {
    let texture = offscreen_target(&gpu.device, "screenshot", size, format);
    painter.paint(gpu, &texture, content);
    let rgba = read_texture(&gpu.device, &gpu.queue, &texture)?;
    image::save_buffer(
        path,
        &rgba,
        texture.width(),
        texture.height(),
        image::ColorType::Rgba8,
    )
    .map_err(|e| format!("{}: cannot save the screenshot: {e}", path.display()))
}

/// A texture to paint into off screen and read back with [`read_texture`].
pub fn offscreen_target(
    device: &wgpu::Device,
    label: &str,
    (width, height): (u32, u32),
    format: wgpu::TextureFormat,
) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: width.max(1),
            height: height.max(1),
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

/// The texture's pixels as RGBA8 rows, row 0 at the top. The texture must be 8-bit RGBA or BGRA
/// and allow copies from it.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, String> {
    let swap_red_blue = match texture.format() {
        wgpu::TextureFormat::Rgba8Unorm | wgpu::TextureFormat::Rgba8UnormSrgb => false,
        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb => true,
        other => return Err(format!("cannot read back a texture of format {other:?}")),
    };
    let (width, height) = (texture.width(), texture.height());
    let row_bytes = width * 4;
    let padded_row = row_bytes.next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read back"),
        size: u64::from(padded_row) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row),
                rows_per_image: None,
            },
        },
        texture.size(),
    );
    queue.submit([encoder.finish()]);
    let bytes = read_buffer(device, &buffer)?;
    let mut rgba = Vec::with_capacity((row_bytes * height) as usize);
    for row in bytes.chunks(padded_row as usize) {
        rgba.extend_from_slice(&row[..row_bytes as usize]);
    }
    if swap_red_blue {
        for pixel in rgba.chunks_exact_mut(4) {
            pixel.swap(0, 2);
        }
    }
    Ok(rgba)
}
