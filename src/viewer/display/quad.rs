//! The GPU quad: a texture of the image's size holding the bytes the display shows (the upload
//! has applied exposure, tone curve and sRGB, [`super::upload`]), and maybe a snapshot of it,
//! drawn on two triangles by `shaders/quad.wgsl` into the image rectangle, set as the render
//! pass's viewport. The shader shows each screen pixel's nearest texel (so coarse passes show as
//! fat pixels), and the snapshot left of the divider when comparing.

use raylab::gpu::prelude::numbered;
use raylab::srgb_image::SrgbImage;
use raylab::tone::Tone;

use crate::viewer::layout::PixelRect;

/// The bindings of the quad's bind group: the live image, the snapshot beside it and the
/// display's settings, numbered for `shaders/quad.wgsl` as `QUAD_LIVE`, … .
#[derive(Clone, Copy, Debug, strum::EnumIter)]
enum QuadBinding {
    Live,
    Snapshot,
    Display,
}

/// The quad's WGSL, after its binding numbers.
fn quad_wgsl() -> String {
    let mut wgsl = String::new();
    numbered::<QuadBinding>(&mut wgsl, "QUAD_");
    wgsl + include_str!("../../../shaders/quad.wgsl")
}

/// The texture format of the image and the snapshot: sRGB bytes, passed to the (non-sRGB) target
/// unchanged.
pub const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Bytes of the shader's uniforms: the divider and three unused.
const DISPLAY_BYTES: usize = 16;

/// How the image is shown: the tone its texels are made with, the split view, and whether the
/// texels show the image's difference from the snapshot instead of its colours.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Display {
    pub tone: Tone,
    /// Image x (0 left, 1 right) left of which the snapshot is shown; 0 shows none of it.
    pub divider: f32,
    /// Show the heat map of each pixel's difference from the snapshot (see
    /// [`super::upload`]).
    pub difference: bool,
}

/// The image texture, the snapshot (if any, of the same size) and the bind group that reads
/// them.
struct ImageTexture {
    texture: wgpu::Texture,
    snapshot: Option<wgpu::Texture>,
    bind_group: wgpu::BindGroup,
}

pub struct QuadRenderer {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    display: wgpu::Buffer,
    image: Option<ImageTexture>,
}

impl QuadRenderer {
    /// A renderer drawing into targets of `format` (which should not be sRGB: the texels are
    /// sRGB already).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        format: wgpu::TextureFormat,
    ) -> QuadRenderer {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("quad.wgsl"),
            source: wgpu::ShaderSource::Wgsl(quad_wgsl().into()),
        });
        let texture_entry = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("image"),
            entries: &[
                texture_entry(QuadBinding::Live as u32),
                texture_entry(QuadBinding::Snapshot as u32),
                wgpu::BindGroupLayoutEntry {
                    binding: QuadBinding::Display as u32,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
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
        let display = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("display"),
            size: DISPLAY_BYTES as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let quad = QuadRenderer {
            pipeline,
            layout,
            display,
            image: None,
        };
        quad.set_divider(queue, 0.0);
        quad
    }

    /// Shows the snapshot left of image x `divider` (0 left, 1 right; 0: none of it) from the
    /// next frame on.
    pub fn set_divider(&self, queue: &wgpu::Queue, divider: f32) {
        let uniforms: Vec<u8> = [divider.to_ne_bytes(), [0; 4], [0; 4], [0; 4]].concat();
        queue.write_buffer(&self.display, 0, &uniforms);
    }

    /// The image texture, made `width × height` (a new, black one without a snapshot when the
    /// size changed). The flag says whether it is new.
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
            let texture = image_texture(device, "image", width, height);
            let bind_group = self.bind_group(device, &texture, None);
            self.image = Some(ImageTexture {
                texture,
                snapshot: None,
                bind_group,
            });
        }
        let image = self.image.as_ref().map(|i| &i.texture);
        (
            image.unwrap_or_else(|| unreachable!("the texture was just made")),
            !fits,
        )
    }

    /// Keeps a copy of the image texture as it is now, to compare with; returns its size (none
    /// before the first image).
    pub fn take_snapshot(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Option<(u32, u32)> {
        let image = self.image.as_ref()?;
        let size = image.texture.size();
        let snapshot = image_texture(device, "snapshot", size.width, size.height);
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_texture(
            image.texture.as_image_copy(),
            snapshot.as_image_copy(),
            size,
        );
        queue.submit([encoder.finish()]);
        let bind_group = self.bind_group(device, &image.texture, Some(&snapshot));
        let image = self.image.as_mut()?;
        image.snapshot = Some(snapshot);
        image.bind_group = bind_group;
        Some((size.width, size.height))
    }

    /// Makes `image` the snapshot, if the image texture has its size; returns whether it did.
    pub fn put_snapshot(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        image: &SrgbImage,
    ) -> bool {
        let Some(live) = self.image.as_ref() else {
            return false;
        };
        let size = live.texture.size();
        if (size.width, size.height) != (image.width, image.height) {
            return false;
        }
        let snapshot = image_texture(device, "snapshot", size.width, size.height);
        let texels: Vec<u8> = image
            .pixels
            .iter()
            .flat_map(|&[r, g, b]| [r, g, b, 255])
            .collect();
        queue.write_texture(
            snapshot.as_image_copy(),
            &texels,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(size.width * 4),
                rows_per_image: None,
            },
            size,
        );
        let bind_group = self.bind_group(device, &live.texture, Some(&snapshot));
        if let Some(live) = self.image.as_mut() {
            live.snapshot = Some(snapshot);
            live.bind_group = bind_group;
        }
        true
    }

    /// The size of the snapshot, if there is one (the image has the same).
    pub fn snapshot_size(&self) -> Option<(u32, u32)> {
        let snapshot = self.image.as_ref()?.snapshot.as_ref()?;
        Some((snapshot.width(), snapshot.height()))
    }

    /// The bind group of `image` and `snapshot` (the image again if none) with the uniforms.
    fn bind_group(
        &self,
        device: &wgpu::Device,
        image: &wgpu::Texture,
        snapshot: Option<&wgpu::Texture>,
    ) -> wgpu::BindGroup {
        let view = |t: &wgpu::Texture| t.create_view(&wgpu::TextureViewDescriptor::default());
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("image"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: QuadBinding::Live as u32,
                    resource: wgpu::BindingResource::TextureView(&view(image)),
                },
                wgpu::BindGroupEntry {
                    binding: QuadBinding::Snapshot as u32,
                    resource: wgpu::BindingResource::TextureView(&view(snapshot.unwrap_or(image))),
                },
                wgpu::BindGroupEntry {
                    binding: QuadBinding::Display as u32,
                    resource: self.display.as_entire_binding(),
                },
            ],
        })
    }

    /// Draws the image into `shown` (whole pixels, inside a target of `target_size`).
    pub fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        image_rect: PixelRect,
        target_size: (u32, u32),
    ) {
        let Some(image) = &self.image else { return };
        // The viewport must lie inside the target.
        let x = image_rect.x.max(0.0);
        let y = image_rect.y.max(0.0);
        let width = image_rect.width.min(target_size.0 as f32 - x);
        let height = image_rect.height.min(target_size.1 as f32 - y);
        if image_rect.is_empty() || width < 1.0 || height < 1.0 {
            return;
        }
        pass.set_viewport(x, y, width, height, 0.0, 1.0);
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &image.bind_group, &[]);
        pass.draw(0..6, 0..1);
    }
}

/// A `width × height` texture of [`IMAGE_FORMAT`] to upload into, copy from and read.
fn image_texture(device: &wgpu::Device, label: &str, width: u32, height: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: IMAGE_FORMAT,
        usage: wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_DST
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    })
}

#[cfg(test)]
mod tests {
    use raylab::color::{Color, srgb_to_linear};
    use raylab::tone::ToneCurve;

    use super::*;
    use crate::viewer::display::device::Gpu;
    use crate::viewer::display::screenshot::{offscreen_target, read_texture};
    use crate::viewer::display::upload::{TEXEL_BYTES, texel, write_rows};
    use crate::viewer::layout::letterbox;

    const CLEAR: [u8; 4] = [0, 0, 255, 255];

    /// A quad drawing into `Rgba8Unorm` targets on a software GPU.
    fn quad() -> (Gpu, QuadRenderer) {
        let gpu = Gpu::headless().expect("a software GPU adapter (install mesa-vulkan-drivers)");
        let quad = QuadRenderer::new(&gpu.device, &gpu.queue, wgpu::TextureFormat::Rgba8Unorm);
        (gpu, quad)
    }

    /// Uploads `pixels` as the quad's `width`-wide image.
    fn upload(gpu: &Gpu, quad: &mut QuadRenderer, width: u32, pixels: &[Color]) {
        let height = pixels.len() as u32 / width;
        let encoder = raylab::color::SrgbEncoder::shared();
        let mut bytes = vec![0; pixels.len() * TEXEL_BYTES];
        for (c, out) in pixels.iter().zip(bytes.chunks_exact_mut(TEXEL_BYTES)) {
            texel(encoder, *c, 1.0, ToneCurve::Clamp, out);
        }
        let (texture, _) = quad.image_texture(&gpu.device, width, height);
        write_rows(
            &gpu.queue,
            texture,
            &bytes,
            std::slice::from_ref(&(0..height)),
        );
    }

    /// Draws the quad's image letterboxed into a `tw × th` target; returns the target's RGBA
    /// bytes and where the image went.
    fn draw(gpu: &Gpu, quad: &QuadRenderer, (tw, th): (u32, u32)) -> (Vec<u8>, PixelRect) {
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let target = offscreen_target(&gpu.device, "target", (tw, th), format);
        let area = PixelRect {
            x: 0.0,
            y: 0.0,
            width: tw as f32,
            height: th as f32,
        };
        let image = quad.image.as_ref().expect("an image").texture.size();
        let image_rect = letterbox(area, image.width, image.height);
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
            quad.draw(&mut pass, image_rect, (tw, th));
        }
        gpu.queue.submit([encoder.finish()]);
        let pixels = read_texture(&gpu.device, &gpu.queue, &target).expect("read back");
        (pixels, image_rect)
    }

    /// A `iw × ih` image of distinct sRGB bytes, and the linear colours that show as them.
    fn distinct_image(iw: u32, ih: u32) -> (Vec<u8>, Vec<Color>) {
        let bytes: Vec<u8> = (0..iw * ih)
            .flat_map(|i| {
                [
                    (i * 37 % 256) as u8,
                    (i * 11 % 256) as u8,
                    (i % 7 * 40) as u8,
                    255,
                ]
            })
            .collect();
        let linear = bytes
            .chunks_exact(4)
            .map(|b| Color::from_array([0, 1, 2].map(|c| srgb_to_linear(b[c] as f32 / 255.0))))
            .collect();
        (bytes, linear)
    }

    fn check(iw: u32, ih: u32, tw: u32, th: u32) {
        let (gpu, mut quad) = quad();
        let (image, linear) = distinct_image(iw, ih);
        upload(&gpu, &mut quad, iw, &linear);
        let (pixels, image_rect) = draw(&gpu, &quad, (tw, th));
        assert_eq!(pixels.len(), (tw * th * 4) as usize);
        for y in 0..th {
            for x in 0..tw {
                let got = &pixels[((y * tw + x) * 4) as usize..][..4];
                let (fx, fy) = (x as f32, y as f32);
                let inside = fx >= image_rect.x
                    && fx < image_rect.x + image_rect.width
                    && fy >= image_rect.y
                    && fy < image_rect.y + image_rect.height;
                let expected = if inside {
                    // Nearest texel, row 0 at the top.
                    let tx = ((fx + 0.5 - image_rect.x) / image_rect.width * iw as f32) as u32;
                    let ty = ((fy + 0.5 - image_rect.y) / image_rect.height * ih as f32) as u32;
                    &image[((ty * iw + tx) * 4) as usize..][..4]
                } else {
                    &CLEAR[..]
                };
                assert_eq!(
                    got, expected,
                    "pixel ({x}, {y}) of {tw}×{th}, image_rect {image_rect:?}"
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
        check(4, 4, 60, 20);
    }

    #[test]
    fn a_tall_target_letterboxes_above_and_below() {
        check(5, 3, 20, 50);
    }

    #[test]
    fn the_snapshot_shows_left_of_the_divider() {
        let (gpu, mut quad) = quad();
        assert_eq!(quad.take_snapshot(&gpu.device, &gpu.queue), None);
        upload(&gpu, &mut quad, 8, &[Color::ONE; 32]);
        assert_eq!(quad.take_snapshot(&gpu.device, &gpu.queue), Some((8, 4)));
        upload(&gpu, &mut quad, 8, &[Color::new(0.0, 1.0, 0.0); 32]);
        quad.set_divider(&gpu.queue, 0.25);
        let (pixels, _) = draw(&gpu, &quad, (8, 4));
        for (i, got) in pixels.chunks_exact(4).enumerate() {
            let expected = if i % 8 < 2 {
                [255, 255, 255, 255]
            } else {
                [0, 255, 0, 255]
            };
            assert_eq!(got, expected, "pixel {i}");
        }
        // A new size has no snapshot.
        assert_eq!(quad.snapshot_size(), Some((8, 4)));
        upload(&gpu, &mut quad, 4, &[Color::ONE; 4]);
        assert_eq!(quad.snapshot_size(), None);
    }
}
