//! The GPU: a wgpu instance, adapter, device and queue, for a window (with its surface): the
//! tracer's own where its adapter can draw into the window, so that the image it traces reaches
//! the window's texture on the GPU, else one of its own; or, in tests, without any display (a
//! software adapter such as Mesa's lavapipe).

use std::sync::Arc;

use raylab::gpu::device::GpuDevice;

use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

pub struct Gpu {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// A GPU that can draw into `window`, and the window's surface (not configured yet).
    pub fn for_window(
        event_loop: &ActiveEventLoop,
        window: Arc<Window>,
    ) -> Result<(Gpu, wgpu::Surface<'static>), String> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_with_display_handle_from_env(
                Box::new(event_loop.owned_display_handle()),
            ));
        let surface = instance
            .create_surface(window)
            .map_err(|e| format!("cannot draw into the window: {e}"))?;
        let gpu = pollster::block_on(Gpu::request(&instance, Some(&surface), false))?;
        Ok((gpu, surface))
    }

    /// The tracer's GPU, if its adapter can draw into `window`, and the window's surface (not
    /// configured yet).
    pub fn sharing(
        tracer: &GpuDevice,
        window: Arc<Window>,
    ) -> Result<Option<(Gpu, wgpu::Surface<'static>)>, String> {
        let surface = tracer
            .instance
            .create_surface(window)
            .map_err(|e| format!("cannot draw into the window: {e}"))?;
        if !tracer.adapter.is_surface_supported(&surface) {
            return Ok(None);
        }
        let gpu = Gpu {
            instance: tracer.instance.clone(),
            adapter: tracer.adapter.clone(),
            device: tracer.device.clone(),
            queue: tracer.queue.clone(),
        };
        Ok(Some((gpu, surface)))
    }

    /// A GPU with no display: the software fallback adapter if there is one, else any.
    #[cfg(test)]
    pub fn headless() -> Result<Gpu, String> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        pollster::block_on(async {
            match Gpu::request(&instance, None, true).await {
                Ok(gpu) => Ok(gpu),
                Err(_) => Gpu::request(&instance, None, false).await,
            }
        })
    }

    async fn request(
        instance: &wgpu::Instance,
        surface: Option<&wgpu::Surface<'_>>,
        force_fallback_adapter: bool,
    ) -> Result<Gpu, String> {
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::default(),
                force_fallback_adapter,
                compatible_surface: surface,
                apply_limit_buckets: false,
            })
            .await
            .map_err(|e| {
                format!(
                    "no GPU adapter can draw here ({e}); without a GPU, install Mesa's software \
                     Vulkan (Debian: apt-get install mesa-vulkan-drivers libvulkan1)"
                )
            })?;
        let limits = wgpu::Limits {
            max_texture_dimension_2d: adapter.limits().max_texture_dimension_2d,
            ..wgpu::Limits::downlevel_webgl2_defaults()
        };
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("raylab"),
                required_limits: limits,
                ..Default::default()
            })
            .await
            .map_err(|e| format!("cannot open the GPU device: {e}"))?;
        Ok(Gpu {
            instance: instance.clone(),
            adapter,
            device,
            queue,
        })
    }

    /// Largest texture side the device takes.
    pub fn max_texture_side(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }
}
