//! The window's surface: configured for the window's size in physical pixels, reconfigured after
//! a resize or when outdated, recreated when lost, and left alone while the window has no area
//! (minimised), so none of these stops the viewer. Its sides never pass the GPU's largest
//! texture side: a window the window system made larger is drawn into its top-left part.

use std::sync::Arc;

use winit::window::Window;

use super::device::Gpu;

/// What became of a request for the next frame's texture.
pub enum Acquired {
    Frame(wgpu::SurfaceTexture),
    /// Nothing to draw into now (minimised, occluded, timed out); wait for the next event.
    Skip,
    /// The surface was reconfigured or recreated; try again on the next frame.
    Retry,
}

/// Mailbox (no tearing, never waits) where the surface has it, else Immediate, else Fifo (which
/// every surface has). The viewer paces its own frames, so it never needs to wait in `present`.
fn present_mode(modes: &[wgpu::PresentMode]) -> wgpu::PresentMode {
    [wgpu::PresentMode::Mailbox, wgpu::PresentMode::Immediate]
        .into_iter()
        .find(|m| modes.contains(m))
        .unwrap_or(wgpu::PresentMode::Fifo)
}

pub struct WindowSurface {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    window: Arc<Window>,
    needs_configure: bool,
    /// The GPU's largest texture side: the most either side of the surface may be.
    max_side: u32,
}

impl WindowSurface {
    pub fn new(
        gpu: &Gpu,
        surface: wgpu::Surface<'static>,
        window: Arc<Window>,
    ) -> Result<WindowSurface, String> {
        let caps = surface.get_capabilities(&gpu.adapter);
        // egui wants a target that is not sRGB; the image's texture holds sRGB bytes too.
        let format = egui_wgpu::preferred_framebuffer_format(&caps.formats)
            .map_err(|e| format!("the window's surface offers no usable format: {e}"))?;
        let max_side = gpu.max_texture_side();
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.min(max_side),
            height: size.height.min(max_side),
            present_mode: present_mode(&caps.present_modes),
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
            desired_maximum_frame_latency: 2,
            ..surface
                .get_default_config(&gpu.adapter, size.width.max(1), size.height.max(1))
                .ok_or("the window's surface does not work with this GPU adapter")?
        };
        Ok(WindowSurface {
            surface,
            config,
            window,
            needs_configure: true,
            max_side,
        })
    }

    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// Size in physical pixels.
    pub fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Follows the window to `width × height` physical pixels, at most the GPU's largest side.
    pub fn resize(&mut self, width: u32, height: u32) {
        let (width, height) = (width.min(self.max_side), height.min(self.max_side));
        if (width, height) != self.size() {
            self.config.width = width;
            self.config.height = height;
            self.needs_configure = true;
        }
    }

    fn configure(&mut self, gpu: &Gpu) {
        self.surface.configure(&gpu.device, &self.config);
        self.needs_configure = false;
    }

    /// The texture to draw the next frame into.
    pub fn acquire(&mut self, gpu: &Gpu) -> Acquired {
        if self.config.width == 0 || self.config.height == 0 {
            return Acquired::Skip;
        }
        if self.needs_configure {
            self.configure(gpu);
        }
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(frame) => Acquired::Frame(frame),
            wgpu::CurrentSurfaceTexture::Suboptimal(frame) => {
                self.needs_configure = true;
                Acquired::Frame(frame)
            }
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                Acquired::Skip
            }
            wgpu::CurrentSurfaceTexture::Outdated => {
                self.needs_configure = true;
                Acquired::Retry
            }
            wgpu::CurrentSurfaceTexture::Lost | wgpu::CurrentSurfaceTexture::Validation => {
                match gpu.instance.create_surface(self.window.clone()) {
                    Ok(surface) => self.surface = surface,
                    Err(e) => eprintln!("warning: cannot recreate the window's surface: {e}"),
                }
                self.needs_configure = true;
                Acquired::Retry
            }
        }
    }
}
