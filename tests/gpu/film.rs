//! The film on the GPU against the film on the CPU: samples put into it as the CPU's film takes
//! them (a block painted for a pixel's first sample of a pass, otherwise a sample added to the
//! mean) give the CPU's pixels and sample counts; and the rows shown from it into a texture are
//! the bytes `Tone::map` gives, for every tone curve and several exposures. These tests need a
//! GPU adapter: without one they fail, saying what to install (Mesa's lavapipe will do).

use crate::gpu;
use glam::Vec3;
use raylab::color::Color;
use raylab::film::Film;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::film::{FilmShow, GpuFilm};
use raylab::gpu::tracer::PixelSample;
use raylab::tone::{Tone, ToneCurve};
use strum::IntoEnumIterator;

/// A small deterministic generator of colours.
fn colour(i: u32) -> Color {
    let h = i.wrapping_mul(2_654_435_761) ^ 0x9e37_79b9;
    Vec3::new(
        (h & 0xff) as f32 / 97.0,
        ((h >> 8) & 0xff) as f32 / 151.0,
        ((h >> 16) & 0xff) as f32 / 255.0,
    )
}

#[test]
fn samples_put_on_the_gpu_give_the_cpu_films_pixels_and_counts() {
    let gpu = gpu();
    let (width, height) = (37, 23);
    let cpu = Film::new(width, height);
    let on_gpu = GpuFilm::new(&gpu, &cpu).unwrap();
    let mut i = 0;
    // Block passes of 8, 4, 2 and 1, then two rounds of three more samples a pixel.
    for step in [8, 4, 2, 1] {
        let mut samples = Vec::new();
        let mut colours = Vec::new();
        for y in (0..height).step_by(step as usize) {
            for x in (0..width).step_by(step as usize) {
                i += 1;
                samples.push(PixelSample {
                    x,
                    y,
                    k: 0,
                    item_t: 0.0,
                });
                colours.push(colour(i));
                cpu.fill_block(x, y, step, colour(i));
            }
        }
        on_gpu.put(&gpu, &samples, &colours, step).unwrap();
    }
    for round in 0..2 {
        let mut samples = Vec::new();
        let mut colours = Vec::new();
        for y in 0..height {
            for x in 0..width {
                for k in 1 + 3 * round..4 + 3 * round {
                    i += 1;
                    samples.push(PixelSample {
                        x,
                        y,
                        k,
                        item_t: 0.0,
                    });
                    colours.push(colour(i));
                    cpu.add_sample(x, y, colour(i));
                }
            }
        }
        on_gpu.put(&gpu, &samples, &colours, 1).unwrap();
    }
    let back = Film::new(width, height);
    on_gpu.read_into(&gpu, &back).unwrap();
    for y in 0..height {
        for x in 0..width {
            assert_eq!(
                back.samples(x, y),
                cpu.samples(x, y),
                "samples at ({x}, {y})"
            );
            let (got, want) = (back.get(x, y), cpu.get(x, y));
            assert!(
                (got - want).abs().max_element() <= 1e-6 * want.max_element().max(1.0),
                "pixel ({x}, {y}): GPU {got}, CPU {want}"
            );
        }
    }
}

/// The bytes of `texture` (`Rgba8Unorm`), row by row, four a texel.
fn texture_bytes(gpu: &GpuDevice, texture: &wgpu::Texture) -> Vec<u8> {
    let (width, height) = (texture.width(), texture.height());
    let row_bytes = (width * 4).div_ceil(256) * 256;
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(row_bytes * height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row_bytes),
                rows_per_image: Some(height),
            },
        },
        texture.size(),
    );
    gpu.queue.submit([encoder.finish()]);
    let bytes = raylab::gpu::device::read_buffer(&gpu.device, &buffer).unwrap();
    bytes
        .chunks(row_bytes as usize)
        .flat_map(|row| row[..width as usize * 4].to_vec())
        .collect()
}

#[test]
fn rows_shown_on_the_gpu_are_the_bytes_tone_mapping_gives() {
    let gpu = gpu();
    // Linear values from 10⁻⁶ to 10⁴, spaced by 0.1 %, with zero, negatives, infinity and NaN.
    let mut values = vec![0.0, -1.0, -0.0, f32::INFINITY, f32::NAN, 1.0, 0.5];
    let mut v = 1e-6f32;
    while v < 1e4 {
        values.push(v);
        v *= 1.001;
    }
    let width = 101;
    let height = values.len().div_ceil(width as usize) as u32;
    let cpu = Film::new(width, height);
    let mut samples = Vec::new();
    let mut colours = Vec::new();
    for (i, &v) in values.iter().enumerate() {
        let (x, y) = (i as u32 % width, i as u32 / width);
        let c = Color::new(v, v * 0.37, v * 2.9);
        samples.push(PixelSample {
            x,
            y,
            k: 1,
            item_t: 0.0,
        });
        colours.push(c);
        cpu.add_sample(x, y, c);
    }
    let on_gpu = GpuFilm::new(&gpu, &cpu).unwrap();
    on_gpu.put(&gpu, &samples, &colours, 1).unwrap();
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: None,
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::COPY_DST | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let mut show = FilmShow::new(&gpu);
    for curve in ToneCurve::iter() {
        for exposure in [-3.0, 0.0, 1.5] {
            let tone = Tone::new(exposure, curve).unwrap();
            // Two runs of rows, as the changed rows of a film come.
            show.show(&gpu, &on_gpu, tone, 0..height / 2, &texture);
            show.show(&gpu, &on_gpu, tone, height / 2..height, &texture);
            let bytes = texture_bytes(&gpu, &texture);
            let mut off_by_one = 0;
            for (i, texel) in bytes.chunks(4).enumerate().take(values.len()) {
                let (x, y) = (i as u32 % width, i as u32 / width);
                let want = tone.map(cpu.get(x, y));
                assert_eq!(texel[3], 255, "alpha of pixel {i}");
                for (got, want) in texel[..3].iter().zip(want) {
                    let gap = got.abs_diff(want);
                    assert!(
                        gap == 0 || (gap == 1 && curve != ToneCurve::Clamp),
                        "{tone:?} at {}: GPU {:?}, CPU {want:?}",
                        cpu.get(x, y),
                        &texel[..3]
                    );
                    off_by_one += usize::from(gap);
                }
            }
            // A curve with a division may round its last bit otherwise on the GPU: a byte one
            // off, where the value falls on a byte's threshold.
            assert!(
                off_by_one * 1000 <= values.len() * 3,
                "{tone:?}: {off_by_one} bytes one off"
            );
        }
    }
}
