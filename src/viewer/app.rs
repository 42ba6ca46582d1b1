//! The viewer's window and event loop (winit): the app's state, opening the window and its GPU,
//! loading and watching scenes, and the events (window, loader, watcher). A frame is drawn in
//! [`crate::viewer::frame`]; while the tracer works (or a key is held) frames come at a steady rate,
//! otherwise the loop sleeps until an event arrives.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoopProxy};
use winit::window::{Window, WindowId};

use super::Options;
use crate::viewer::frame::timing::Timing;
use crate::viewer::gpu::device::Gpu;
use crate::viewer::gpu::painter::Painter;
use crate::viewer::gpu::surface::WindowSurface;
use crate::viewer::gpu::upload::Uploader;
use crate::viewer::input::action::Action;
use crate::viewer::input::synthetic::SyntheticInput;
use crate::viewer::scene::controls::Controls;
use crate::viewer::scene::source::{self, LoadedScene};
use crate::viewer::scene::watch::SceneWatcher;
use crate::viewer::tracing::picked_pixel::PickedPixel;
use crate::viewer::tracing::rendering::Rendering;
use crate::viewer::tracing::worker::Worker;
use crate::viewer::ui::layout::PixelRect;
use crate::viewer::ui::overlay::Overlay;
use crate::viewer::ui::panels::PanelState;

/// What other threads tell the event loop.
pub enum UserEvent {
    /// A scene finished loading (or failed to); `generation` tells stale loads apart.
    Loaded {
        generation: u64,
        result: Result<Box<LoadedScene>, String>,
    },
    /// The watched scene file changed on disk.
    SceneFileChanged,
    /// The ray tree thread has traced what it was asked.
    RayTreeTraced,
}

/// The window and what draws into it.
pub(super) struct Graphics {
    pub(super) window: Arc<Window>,
    pub(super) gpu: Gpu,
    pub(super) surface: WindowSurface,
    pub(super) painter: Painter,
    pub(super) egui_state: egui_winit::State,
}

/// The viewer: its window, the scene, the controls, the render worker and what is on screen.
pub struct App {
    pub(super) options: Options,
    pub(super) proxy: EventLoopProxy<UserEvent>,
    pub(super) egui_ctx: egui::Context,
    pub(super) gfx: Option<Graphics>,
    pub(super) worker: Worker,
    pub(super) scene: Option<Arc<LoadedScene>>,
    /// The controls as the scene file gives them (no overrides), to tell which a reloaded file
    /// changed.
    pub(super) file_controls: Option<Controls>,
    pub(super) controls: Option<Controls>,
    pub(super) rendering: Option<Rendering>,
    pub(super) uploader: Uploader,
    pub(super) panel: PanelState,
    /// The picked pixel's ray tree, and what is drawn of it over the image.
    pub(super) picked: PickedPixel,
    pub(super) overlay: Overlay,
    /// Scripted clicks on their way to egui.
    pub(super) synthetic: SyntheticInput,
    /// The scene file asked for last (watched even while it fails to load).
    pub(super) requested: Option<PathBuf>,
    pub(super) watcher: Option<SceneWatcher>,
    pub(super) generation: u64,
    pub(super) loading: bool,
    /// Scene loads finished (well or not), for the script's `wait-load`.
    pub(super) loads: u64,
    pub(super) timing: Timing,
    pub(super) last_frame: Instant,
    pub(super) fps: f32,
    pub(super) next_frame: Option<Instant>,
    pub(super) exiting: bool,
    /// Why the viewer had to stop.
    pub error: Option<String>,
}

impl App {
    pub fn new(options: Options, proxy: EventLoopProxy<UserEvent>) -> Result<App, String> {
        let worker = Worker::start(options.threads)?;
        let wake = proxy.clone();
        let picked = PickedPixel::start(options.threads, move || {
            let _ = wake.send_event(UserEvent::RayTreeTraced);
        })?;
        let timing = Timing::new(options.stats);
        let save_field = options.save_path.display().to_string();
        let open_field = options
            .scene
            .as_ref()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        Ok(App {
            proxy,
            egui_ctx: egui::Context::default(),
            gfx: None,
            worker,
            scene: None,
            file_controls: None,
            controls: None,
            rendering: None,
            uploader: Uploader::new(),
            panel: PanelState {
                scene_name: "loading…".into(),
                scene_files: Vec::new(),
                current_path: None,
                open_field,
                save_field,
                load_error: None,
                load_warnings: Vec::new(),
                control_error: None,
                message: None,
                square: options.size.is_some_and(|(w, h)| w == h),
                light_count: 0,
                max_side: 2048,
            },
            picked,
            overlay: Overlay::default(),
            synthetic: SyntheticInput::default(),
            requested: None,
            watcher: None,
            generation: 0,
            loading: false,
            loads: 0,
            timing,
            last_frame: Instant::now(),
            fps: 0.0,
            next_frame: None,
            exiting: false,
            error: None,
            options,
        })
    }

    pub(super) fn fail(&mut self, event_loop: &ActiveEventLoop, message: String) {
        self.error = Some(message);
        self.exit(event_loop);
    }

    pub(super) fn exit(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(r) = &self.rendering {
            r.control.cancel();
        }
        self.exiting = true;
        event_loop.exit();
    }

    pub(super) fn request_redraw(&self) {
        if let Some(gfx) = &self.gfx {
            gfx.window.request_redraw();
        }
    }

    fn open_window(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let (w, h) = self.options.window;
        let attributes = Window::default_attributes()
            .with_title("raylab")
            .with_inner_size(winit::dpi::LogicalSize::new(w, h));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| format!("cannot open a window: {e}"))?,
        );
        let (gpu, surface) = Gpu::for_window(event_loop, window.clone())?;
        let surface = WindowSurface::new(&gpu, surface, window.clone())?;
        let painter = Painter::new(&gpu, surface.format());
        let max_side = gpu.max_texture_side();
        self.panel.max_side = max_side;
        let egui_state = egui_winit::State::new(
            self.egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            window.theme(),
            Some(max_side as usize),
        );
        self.gfx = Some(Graphics {
            window,
            gpu,
            surface,
            painter,
            egui_state,
        });
        Ok(())
    }

    /// Starts loading `path` (the default scene for `None`) and watches it.
    pub(super) fn start_load(&mut self, path: Option<PathBuf>) {
        self.generation += 1;
        self.loading = true;
        if self.requested != path || (path.is_some() && self.watcher.is_none()) {
            // Only files are watched (not `spd:` names).
            self.watcher = path.as_deref().filter(|p| p.is_file()).and_then(|p| {
                let proxy = self.proxy.clone();
                SceneWatcher::new(p, move || {
                    let _ = proxy.send_event(UserEvent::SceneFileChanged);
                })
                .map_err(|e| self.panel.message = Some(e))
                .ok()
            });
        }
        self.requested = path.clone();
        self.panel.scene_files = source::scene_files_beside(path.as_deref());
        let (proxy, generation) = (self.proxy.clone(), self.generation);
        source::spawn_load(path, move |result| {
            let result = result.map(Box::new);
            let _ = proxy.send_event(UserEvent::Loaded { generation, result });
        });
    }

    /// The scene's controls with the command line's overrides.
    fn controls_for(&self, scene: &LoadedScene) -> Controls {
        let mut c = Controls::from_scene(&scene.scene);
        let o = &self.options;
        if let Some((w, h)) = o.size {
            (c.settings.width, c.settings.height) = (w, h);
        }
        c.settings.block_size = o.block_size.unwrap_or(c.settings.block_size);
        c.settings.max_depth = o.max_depth.unwrap_or(c.settings.max_depth);
        c.settings.samples = o.samples.unwrap_or(c.settings.samples);
        c.view = o.view;
        c
    }

    fn loaded(&mut self, event_loop: &ActiveEventLoop, result: Result<Box<LoadedScene>, String>) {
        self.loading = false;
        self.loads += 1;
        let loaded = match result {
            Ok(loaded) => loaded,
            Err(message) => {
                eprintln!("error: {message}");
                if self.scene.is_none() && self.options.exit_when_done {
                    return self.fail(event_loop, message);
                }
                self.panel.load_error = Some(message);
                return;
            }
        };
        // The file's own controls, to tell on the next reload what the file changed.
        let file_controls = Controls::from_scene(&loaded.scene);
        let same_file = self.scene.as_ref().is_some_and(|s| s.path == loaded.path);
        let with_overrides = self.controls_for(&loaded);
        match (&mut self.controls, &self.file_controls) {
            (Some(controls), Some(old)) if same_file => {
                // Keep the user's view unless the file itself changed the camera or settings.
                if old.camera != file_controls.camera {
                    controls.camera = file_controls.camera;
                }
                if old.settings != file_controls.settings {
                    controls.settings = with_overrides.settings;
                }
            }
            _ => self.controls = Some(with_overrides),
        }
        self.file_controls = Some(file_controls);
        self.panel.load_error = None;
        for warning in &loaded.scene.warnings {
            eprintln!("warning: {warning}");
        }
        self.panel.load_warnings = loaded.scene.warnings.clone();
        self.panel.scene_name = loaded.name();
        self.panel.current_path = loaded.path.clone();
        self.panel.light_count = loaded.scene.lights.len();
        if let Some(gfx) = &self.gfx {
            gfx.window.set_title(&format!("raylab — {}", loaded.name()));
        }
        if self.timing.enabled() {
            eprintln!(
                "stats: loaded {} in {:.1} ms",
                loaded.name(),
                loaded.load_time.as_secs_f64() * 1e3
            );
        }
        self.scene = Some(Arc::from(loaded));
    }
}

impl ApplicationHandler<UserEvent> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gfx.is_some() {
            return;
        }
        if let Err(e) = self.open_window(event_loop) {
            return self.fail(event_loop, e);
        }
        let scene = self.options.scene.clone();
        self.start_load(scene);
    }

    fn user_event(&mut self, event_loop: &ActiveEventLoop, event: UserEvent) {
        match event {
            UserEvent::Loaded { generation, result } if generation == self.generation => {
                self.loaded(event_loop, result);
            }
            UserEvent::Loaded { .. } => {}
            UserEvent::RayTreeTraced => {}
            UserEvent::SceneFileChanged => {
                if self.requested.is_some() {
                    let path = self.requested.clone();
                    self.start_load(path);
                }
            }
        }
        self.request_redraw();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        if self.exiting {
            return;
        }
        let Some(gfx) = &mut self.gfx else { return };
        // egui asks to repaint after any event, a redraw included: that would never stop.
        if !matches!(event, WindowEvent::RedrawRequested)
            && gfx.egui_state.on_window_event(&gfx.window, &event).repaint
        {
            gfx.window.request_redraw();
        }
        match event {
            WindowEvent::CloseRequested => self.exit(event_loop),
            WindowEvent::Resized(size) => {
                gfx.surface.resize(size.width, size.height);
                gfx.window.request_redraw();
            }
            WindowEvent::DroppedFile(path) => {
                self.apply(Action::Open(Some(path)), PixelRect::ZERO);
                self.request_redraw();
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.exiting {
            return;
        }
        match self.next_frame {
            Some(t) if Instant::now() >= t => {
                self.next_frame = None;
                self.request_redraw();
                event_loop.set_control_flow(ControlFlow::Wait);
            }
            Some(t) => event_loop.set_control_flow(ControlFlow::WaitUntil(t)),
            None => event_loop.set_control_flow(ControlFlow::Wait),
        }
    }

    fn exiting(&mut self, _event_loop: &ActiveEventLoop) {
        if let Some(r) = &self.rendering {
            r.control.cancel();
        }
    }
}
