//! Everything that talks to the GPU (wgpu): the device, the window's surface, the image quad and
//! egui drawn into a frame, the film's changed rows put into the image texture (uploaded, or
//! made on the GPU from the GPU tracer's film when the window shares its device), and
//! screenshots read back from the GPU. It paints what it is given: a film and egui's shapes.

pub mod device;
pub mod painter;
pub mod quad;
pub mod screenshot;
pub mod surface;
pub mod upload;

use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

use raylab::film::Film;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::film::{FilmShow, GpuFilm};
use raylab::srgb_image::SrgbImage;
use winit::event::WindowEvent;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

use self::device::Gpu;
use self::painter::{FrameContent, Painter};
use self::quad::Display;
use self::surface::{Acquired, WindowSurface};
use self::upload::{Uploader, write_rows};
use crate::viewer::layout::{PixelRect, check_window_size};

/// The window and what draws into it.
pub struct Graphics {
    window: Arc<Window>,
    gpu: Gpu,
    surface: WindowSurface,
    painter: Painter,
    egui_state: egui_winit::State,
    /// What of the film the image texture shows.
    uploader: Uploader,
    /// The tracer's GPU, when the window draws with it, and what shows its films on it.
    shared: Option<(Arc<GpuDevice>, FilmShow)>,
    /// How the image is shown (exposure, tone curve, split, difference).
    display: Display,
    /// The pixels of the image compared with (the snapshot's): made the snapshot when an image
    /// texture of its size is made, and what the difference display measures against.
    compared: Option<Arc<SrgbImage>>,
}

/// What painting a frame did.
pub struct Painted {
    /// The frame reached the window.
    pub presented: bool,
    /// The time the film's changed rows took to reach the image texture, if any had changed,
    /// and whether they were made on the GPU from the GPU tracer's film.
    pub upload: Option<(Duration, bool)>,
    /// Why the screenshot could not be saved.
    pub screenshot_error: Option<String>,
}

impl Graphics {
    /// Opens a window of `size` (logical pixels) for `egui` to draw into, with the tracer's GPU
    /// where its adapter can draw into the window, else a GPU of its own.
    pub fn open(
        event_loop: &ActiveEventLoop,
        size: (u32, u32),
        egui: &egui::Context,
        tracer_gpu: Option<&Arc<GpuDevice>>,
    ) -> Result<Graphics, String> {
        let attributes = Window::default_attributes()
            .with_title("raylab")
            .with_inner_size(winit::dpi::LogicalSize::new(size.0, size.1));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| format!("cannot open a window: {e}"))?,
        );
        let mut shared = None;
        let mut sharing = None;
        if let Some(tracer) = tracer_gpu {
            sharing = Gpu::sharing(tracer, window.clone())?;
            if sharing.is_some() {
                shared = Some((Arc::clone(tracer), FilmShow::new(tracer)));
            }
        }
        let (gpu, surface) = match sharing {
            Some(both) => both,
            None => Gpu::for_window(event_loop, window.clone())?,
        };
        let physical = window.inner_size();
        check_window_size(
            physical.width,
            physical.height,
            gpu.max_texture_side(),
            "the largest surface this GPU draws; choose a smaller --window",
        )?;
        let surface = WindowSurface::new(&gpu, surface, window.clone())?;
        let painter = Painter::new(&gpu, surface.format());
        let egui_state = egui_winit::State::new(
            egui.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            window.theme(),
            Some(gpu.max_texture_side() as usize),
        );
        Ok(Graphics {
            window,
            gpu,
            surface,
            painter,
            egui_state,
            uploader: Uploader::new(),
            shared,
            display: Display::default(),
            compared: None,
        })
    }

    /// Largest image side the GPU takes.
    pub fn max_side(&self) -> u32 {
        self.gpu.max_texture_side()
    }

    pub fn window(&self) -> &Window {
        &self.window
    }

    /// Gives a window event to egui (asking for a frame if egui wants one) and follows a resize.
    pub fn window_event(&mut self, event: &WindowEvent) {
        // egui asks to repaint after any event, a redraw included: that would never stop.
        if !matches!(event, WindowEvent::RedrawRequested)
            && self.egui_state.on_window_event(&self.window, event).repaint
        {
            self.window.request_redraw();
        }
        if let WindowEvent::Resized(size) = event {
            self.surface.resize(size.width, size.height);
            self.window.request_redraw();
        }
    }

    /// The window's input since the last frame, for egui.
    pub fn take_egui_input(&mut self) -> egui::RawInput {
        self.egui_state.take_egui_input(&self.window)
    }

    /// The window system resized the window and the surface has not caught up yet.
    pub fn resizing(&self) -> bool {
        let size = self.window.inner_size();
        let max = self.max_side();
        self.surface.size() != (size.width.min(max), size.height.min(max))
    }

    /// Shows the image through `display` from the next frame on (the split only while there is
    /// a snapshot).
    pub fn set_display(&mut self, display: Display) {
        self.display = display;
    }

    /// Paints a frame: egui's `output` over the image (`film`, its changed rows put into the
    /// texture, from `on_gpu`, its twin on the GPU, where there is one) shown at `shown`,
    /// presented in the window; then, if it was presented and `screenshot` is given, saved there
    /// as a PNG.
    pub fn paint(
        &mut self,
        egui: &egui::Context,
        output: egui::FullOutput,
        image_rect: PixelRect,
        (film, on_gpu): (Option<&Arc<Film>>, Option<&GpuFilm>),
        screenshot: Option<&Path>,
    ) -> Painted {
        let egui::FullOutput {
            platform_output,
            mut textures_delta,
            shapes,
            pixels_per_point,
            ..
        } = output;
        self.egui_state
            .handle_platform_output(&self.window, platform_output);
        let primitives = egui.tessellate(shapes, pixels_per_point);
        self.painter.set_textures(&self.gpu, &mut textures_delta);
        let upload = film.and_then(|film| self.upload(film, on_gpu));
        let quad = &self.painter.quad;
        let divider = if quad.snapshot_size().is_some() {
            self.display.divider
        } else {
            0.0
        };
        quad.set_divider(&self.gpu.queue, divider);
        let content = FrameContent {
            primitives: &primitives,
            pixels_per_point,
            image_rect,
        };
        let mut presented = false;
        match self.surface.acquire(&self.gpu) {
            Acquired::Frame(frame) => {
                self.painter.paint(&self.gpu, &frame.texture, &content);
                self.window.pre_present_notify();
                self.gpu.queue.present(frame);
                presented = true;
            }
            Acquired::Retry => self.window.request_redraw(),
            Acquired::Skip => {}
        }
        let screenshot_error = match screenshot {
            Some(path) if presented => self.screenshot(&content, path).err(),
            _ => None,
        };
        self.painter.free_textures(&mut textures_delta);
        Painted {
            presented,
            upload,
            screenshot_error,
        }
    }

    /// Keeps the image texture as it is now as the snapshot to compare with; returns its size
    /// (none before the first image).
    pub fn snapshot(&mut self) -> Option<(u32, u32)> {
        self.painter
            .quad
            .take_snapshot(&self.gpu.device, &self.gpu.queue)
    }

    /// Sets the pixels of the image compared with (see [`Graphics::compared`]'s field).
    pub fn set_compared(&mut self, compared: Option<Arc<SrgbImage>>) {
        self.compared = compared;
    }

    /// Puts the rows of `film` that changed since the last time into the texture, from
    /// `on_gpu` on the GPU where the window shares the tracer's device, else uploaded from the
    /// CPU; returns the time it took, if any had changed, and whether it was on the GPU.
    fn upload(&mut self, film: &Arc<Film>, on_gpu: Option<&GpuFilm>) -> Option<(Duration, bool)> {
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        let quad = &mut self.painter.quad;
        if quad.image_texture(device, film.width(), film.height()).1 {
            self.uploader.invalidate();
            if let Some(compared) = &self.compared {
                quad.put_snapshot(device, queue, compared);
            }
        }
        let texture = quad.image_texture(device, film.width(), film.height()).0;
        let start = Instant::now();
        let tone = self.display.tone;
        let against = self.compared.clone().filter(|_| self.display.difference);
        self.uploader.show_difference(against);
        let same_size = |g: &&GpuFilm| (g.width(), g.height()) == (film.width(), film.height());
        let on_gpu = on_gpu
            .filter(same_size)
            .filter(|_| !self.uploader.shows_difference());
        match (&mut self.shared, on_gpu) {
            (Some((tracer, show)), Some(on_gpu)) => {
                let rows = self.uploader.changed_rows(film, tone)?;
                let span = rows.first()?.start..rows.last()?.end;
                show.show(tracer, on_gpu, tone, span, texture);
                Some((start.elapsed(), true))
            }
            _ => {
                let (texels, rows) = self.uploader.changed_pixels(film, tone)?;
                write_rows(&self.gpu.queue, texture, texels, &rows);
                Some((start.elapsed(), false))
            }
        }
    }

    /// Saves the frame as painted into `path` and says so on the terminal.
    fn screenshot(&mut self, content: &FrameContent<'_>, path: &Path) -> Result<(), String> {
        let size = self.surface.size();
        let format = self.surface.format();
        screenshot::save(&self.gpu, &mut self.painter, format, size, content, path)?;
        let s = content.image_rect;
        println!(
            "screenshot {}: {}×{} window, image at x {} y {} size {}×{}",
            path.display(),
            size.0,
            size.1,
            s.x,
            s.y,
            s.width,
            s.height
        );
        Ok(())
    }
}
