//! One frame on the GPU: clear, the image quad in its letterboxed rectangle, then egui's panels on
//! top, into any target texture (the window's surface, or an offscreen copy for a screenshot).

use super::device::Gpu;
use super::quad::QuadRenderer;
use crate::viewer::layout::PixelRect;

/// The colour of the bars around the image.
const BACKGROUND: wgpu::Color = wgpu::Color {
    r: 0.02,
    g: 0.02,
    b: 0.02,
    a: 1.0,
};

/// What a frame shows.
pub struct FrameContent<'a> {
    pub primitives: &'a [egui::ClippedPrimitive],
    pub pixels_per_point: f32,
    /// Where the image goes, in physical pixels.
    pub image_rect: PixelRect,
}

pub struct Painter {
    pub quad: QuadRenderer,
    egui: egui_wgpu::Renderer,
}

impl Painter {
    pub fn new(gpu: &Gpu, format: wgpu::TextureFormat) -> Painter {
        Painter {
            quad: QuadRenderer::new(&gpu.device, &gpu.queue, format),
            egui: egui_wgpu::Renderer::new(&gpu.device, format, Default::default()),
        }
    }

    /// Applies egui's new and changed textures (before painting).
    pub fn set_textures(&mut self, gpu: &Gpu, delta: &mut egui::TexturesDelta) {
        for (id, images) in delta.set.drain() {
            for image in images {
                self.egui
                    .update_texture(&gpu.device, &gpu.queue, id, &image);
            }
        }
    }

    /// Frees the textures egui no longer needs (after painting).
    pub fn free_textures(&mut self, delta: &mut egui::TexturesDelta) {
        for id in delta.free.drain() {
            self.egui.free_texture(&id);
        }
    }

    /// Paints a frame into `target` and submits it.
    pub fn paint(&mut self, gpu: &Gpu, target: &wgpu::Texture, content: &FrameContent<'_>) {
        let size = (target.width(), target.height());
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [size.0, size.1],
            pixels_per_point: content.pixels_per_point,
        };
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("frame"),
            });
        let egui_commands = self.egui.update_buffers(
            &gpu.device,
            &gpu.queue,
            &mut encoder,
            content.primitives,
            &screen,
        );
        let view = target.create_view(&wgpu::TextureViewDescriptor::default());
        {
            let mut pass = encoder
                .begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("frame"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        resolve_target: None,
                        depth_slice: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(BACKGROUND),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: None,
                    occlusion_query_set: None,
                    multiview_mask: None,
                })
                .forget_lifetime();
            self.quad.draw(&mut pass, content.image_rect, size);
            // egui sets its own viewport and scissor per primitive.
            self.egui.render(&mut pass, content.primitives, &screen);
        }
        gpu.queue
            .submit(egui_commands.into_iter().chain([encoder.finish()]));
    }
}
