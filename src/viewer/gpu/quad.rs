//! The GPU quad: one texture of the image's size, sampled with nearest filtering (so coarse
//! passes show as fat pixels), drawn on two triangles by `shaders/quad.wgsl` into the letterboxed
//! image rectangle, set as the render pass's viewport.

use crate::viewer::ui::layout::PixelRect;

/// The image texture and the bind group that samples it.
struct ImageTexture {
    texture: wgpu::Texture,
    bind_group: wgpu::BindGroup,
}

pub struct QuadRenderer {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    image: Option<ImageTexture>,
}

impl QuadRenderer {
    /// A renderer drawing into targets of `format` (which should not be sRGB: the texture
    /// already holds sRGB bytes).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> QuadRenderer {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("quad.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../../shaders/quad.wgsl").into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("image"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: true },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("quad"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("quad"),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &shader,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            fragment: Some(wgpu::FragmentState {
                module: &shader,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(format.into())],
            }),
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            multiview_mask: None,
            cache: None,
        });
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("nearest"),
            mag_filter: wgpu::FilterMode::Nearest,
            min_filter: wgpu::FilterMode::Nearest,
            ..Default::default()
        });
        QuadRenderer {
            pipeline,
            layout,
            sampler,
            image: None,
        }
    }

    /// The image texture, made `width × height` (a new, black one when the size changed). The
    /// flag says whether it is new.
    pub fn image_texture(
        &mut self,
        device: &wgpu::Device,
        width: u32,
        height: u32,
    ) -> (&wgpu::Texture, bool) {
        let fits = self
            .image
            .as_ref()
            .is_some_and(|i| i.texture.width() == width && i.texture.height() == height);
        if !fits {
            let texture = device.create_texture(&wgpu::TextureDescriptor {
                label: Some("image"),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: wgpu::TextureFormat::Rgba8Unorm,
                usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            });
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("image"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Sampler(&self.sampler),
                    },
                ],
            });
            self.image = Some(ImageTexture {
                texture,
                bind_group,
            });
        }
        let image = self.image.as_ref().map(|i| &i.texture);
        (
            image.unwrap_or_else(|| unreachable!("the texture was just made")),
            !fits,
        )
    }

    /// Draws the image into `shown` (whole pixels, inside a target of `target_size`).
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, shown: PixelRect, target_size: (u32, u32)) {
        let Some(image) = &self.image else { return };
        // The viewport must lie inside the target.
        let x = shown.x.max(0.0);
        let y = shown.y.max(0.0);
        let width = shown.width.min(target_size.0 as f32 - x);
        let height = shown.height.min(target_size.1 as f32 - y);
        if shown.is_empty() || width < 1.0 || height < 1.0 {
            return;
        }
        pass.set_viewport(x, y, width, height, 0.0, 1.0);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &image.bind_group, &[]);
        pass.draw(0..6, 0..1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::gpu::device::Gpu;
    use crate::viewer::gpu::screenshot::{offscreen_target, read_texture};
    use crate::viewer::gpu::upload::write_rows;
    use crate::viewer::ui::layout::letterbox;

    const CLEAR: [u8; 4] = [0, 0, 255, 255];

    /// Renders a `iw × ih` image of distinct texels into a `tw × th` target and returns the
    /// target's RGBA bytes, the image and where it went.
    fn render(iw: u32, ih: u32, tw: u32, th: u32) -> (Vec<u8>, Vec<u8>, PixelRect) {
        let gpu = Gpu::headless().expect("a software GPU adapter (install mesa-vulkan-drivers)");
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let mut quad = QuadRenderer::new(&gpu.device, format);
        let image: Vec<u8> = (0..iw * ih)
            .flat_map(|i| {
                [
                    (i * 37 % 256) as u8,
                    (i * 11 % 256) as u8,
                    (i % 7 * 40) as u8,
                    255,
                ]
            })
            .collect();
        let (texture, created) = quad.image_texture(&gpu.device, iw, ih);
        assert!(created);
        write_rows(&gpu.queue, texture, &image, std::slice::from_ref(&(0..ih)));
        let target = offscreen_target(&gpu.device, "target", (tw, th), format);
        let area = PixelRect {
            x: 0.0,
            y: 0.0,
            width: tw as f32,
            height: th as f32,
        };
        let shown = letterbox(area, iw, ih);
        let view = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("test"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    resolve_target: None,
                    depth_slice: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLUE),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            quad.draw(&mut pass, shown, (tw, th));
        }
        gpu.queue.submit([encoder.finish()]);
        let pixels = read_texture(&gpu.device, &gpu.queue, &target).expect("read back");
        (pixels, image, shown)
    }

    fn check(iw: u32, ih: u32, tw: u32, th: u32) {
        let (pixels, image, shown) = render(iw, ih, tw, th);
        assert_eq!(pixels.len(), (tw * th * 4) as usize);
        for y in 0..th {
            for x in 0..tw {
                let got = &pixels[((y * tw + x) * 4) as usize..][..4];
                let (fx, fy) = (x as f32, y as f32);
                let inside = fx >= shown.x
                    && fx < shown.x + shown.width
                    && fy >= shown.y
                    && fy < shown.y + shown.height;
                let expected = if inside {
                    // Nearest texel, row 0 at the top.
                    let tx = ((fx + 0.5 - shown.x) / shown.width * iw as f32) as u32;
                    let ty = ((fy + 0.5 - shown.y) / shown.height * ih as f32) as u32;
                    &image[((ty * iw + tx) * 4) as usize..][..4]
                } else {
                    &CLEAR[..]
                };
                assert_eq!(
                    got, expected,
                    "pixel ({x}, {y}) of {tw}×{th}, shown {shown:?}"
                );
            }
        }
    }

    #[test]
    fn the_quad_shows_the_image_pixel_for_pixel() {
        check(8, 6, 8, 6);
    }

    #[test]
    fn coarse_texels_become_fat_pixels_in_the_right_orientation() {
        check(4, 2, 40, 20);
    }

    #[test]
    fn a_wide_target_letterboxes_left_and_right() {
        let (_, _, shown) = render(4, 4, 60, 20);
        assert_eq!((shown.x, shown.width), (20.0, 20.0));
        check(4, 4, 60, 20);
    }

    #[test]
    fn a_tall_target_letterboxes_above_and_below() {
        check(5, 3, 20, 50);
    }
}
