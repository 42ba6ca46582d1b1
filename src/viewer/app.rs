//! The viewer's window and event loop (winit): each frame runs the egui panels and the navigation,
//! carries out the actions, restarts refinement when the controls changed, uploads the film if
//! it changed, and draws. While the tracer works (or a key is held) frames come at a steady rate;
//! otherwise the loop sleeps until an event arrives.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use raylab::camera::Camera;
use raylab::film::Film;
use raylab::progressive::{Progress, RenderControl};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoopProxy};
use winit::window::{Window, WindowId};

use super::Options;
use super::action::Action;
use super::controls::Controls;
use super::gpu::Gpu;
use super::input::{self, ImageArea};
use super::layout::{PixelRect, letterbox};
use super::navigation;
use super::painter::{FrameContent, Painter};
use super::panels::{self, PanelState};
use super::pick;
use super::save;
use super::scene_source::{self, LoadedScene};
use super::screenshot;
use super::status::{RenderStatus, status_line};
use super::surface::{Acquired, WindowSurface};
use super::timing::Timing;
use super::upload::{Uploader, write_texture};
use super::watch::SceneWatcher;
use super::worker::{Job, JobReport, Outcome, Worker};

/// What other threads tell the event loop.
pub enum UserEvent {
    /// A scene finished loading (or failed to); `generation` tells stale loads apart.
    Loaded {
        generation: u64,
        result: Result<Box<LoadedScene>, String>,
    },
    /// The watched scene file changed on disk.
    SceneFileChanged,
}

/// The window and what draws into it.
struct Graphics {
    window: Arc<Window>,
    gpu: Gpu,
    surface: WindowSurface,
    painter: Painter,
    egui_state: egui_winit::State,
}

/// The render in progress (or the last one), and what of it has reached the screen.
struct Rendering {
    scene: Arc<LoadedScene>,
    controls: Controls,
    film: Arc<Film>,
    control: Arc<RenderControl>,
    report: Arc<JobReport>,
    /// When the change that started it was made.
    changed_at: Instant,
    first_image_shown: bool,
    block_one_shown: bool,
    /// The last pass is on screen (or the render failed): nothing more will come.
    settled: bool,
}

impl Rendering {
    /// Number of block passes (the block size 1 pass is the last of them).
    fn block_passes(&self) -> u32 {
        self.controls.settings.block_size.max(1).ilog2() + 1
    }

    /// Notes what a frame just put on screen: the film as it was at `progress`.
    fn shown(&mut self, progress: Progress, timing: &mut Timing) {
        let after = self.changed_at.elapsed();
        if !self.first_image_shown && (progress.pass >= 1 || progress.finished) {
            self.first_image_shown = true;
            timing.first_image(after, self.controls.settings.block_size);
        }
        if !self.block_one_shown && (progress.pass >= self.block_passes() || progress.finished) {
            self.block_one_shown = true;
            let s = &self.controls.settings;
            timing.block_one(after, (s.width, s.height));
        }
        if progress.finished {
            self.settled = true;
        }
    }
}

pub struct App {
    options: Options,
    proxy: EventLoopProxy<UserEvent>,
    egui_ctx: egui::Context,
    gfx: Option<Graphics>,
    worker: Worker,
    scene: Option<Arc<LoadedScene>>,
    /// The controls as the scene file gives them, to tell which a reloaded file changed.
    file_controls: Option<Controls>,
    controls: Option<Controls>,
    rendering: Option<Rendering>,
    uploader: Uploader,
    panel: PanelState,
    /// The scene file asked for last (watched even while it fails to load).
    requested: Option<PathBuf>,
    watcher: Option<SceneWatcher>,
    generation: u64,
    loading: bool,
    /// Scene loads finished (well or not), for the script's `wait-load`.
    loads: u64,
    timing: Timing,
    last_frame: Instant,
    fps: f32,
    next_frame: Option<Instant>,
    exiting: bool,
    /// Why the viewer had to stop.
    pub error: Option<String>,
}

impl App {
    pub fn new(options: Options, proxy: EventLoopProxy<UserEvent>) -> Result<App, String> {
        let worker = Worker::start(options.threads)?;
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
                control_error: None,
                message: None,
                square: options.size.is_some_and(|(w, h)| w == h),
                light_count: 0,
                max_side: 2048,
            },
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

    fn fail(&mut self, event_loop: &ActiveEventLoop, message: String) {
        self.error = Some(message);
        self.exit(event_loop);
    }

    fn exit(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(r) = &self.rendering {
            r.control.cancel();
        }
        self.exiting = true;
        event_loop.exit();
    }

    fn request_redraw(&self) {
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

    // ---- scenes ------------------------------------------------------------------------------

    /// Starts loading `path` (the default scene for `None`) and watches it.
    fn start_load(&mut self, path: Option<PathBuf>) {
        self.generation += 1;
        self.loading = true;
        if self.requested != path || (path.is_some() && self.watcher.is_none()) {
            self.watcher = path.as_deref().and_then(|p| {
                let proxy = self.proxy.clone();
                SceneWatcher::new(p, move || {
                    let _ = proxy.send_event(UserEvent::SceneFileChanged);
                })
                .map_err(|e| self.panel.message = Some(e))
                .ok()
            });
        }
        self.requested = path.clone();
        self.panel.scene_files = scene_source::scene_files_beside(path.as_deref());
        let (proxy, generation) = (self.proxy.clone(), self.generation);
        scene_source::spawn_load(path, move |result| {
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
        let file_controls = self.controls_for(&loaded);
        let same_file = self.scene.as_ref().is_some_and(|s| s.path == loaded.path);
        match (&mut self.controls, &self.file_controls) {
            (Some(controls), Some(old)) if same_file => {
                // Keep the user's view unless the file itself changed the camera or settings.
                if old.camera != file_controls.camera {
                    controls.camera = file_controls.camera;
                }
                if old.settings != file_controls.settings {
                    controls.settings = file_controls.settings.clone();
                }
            }
            _ => self.controls = Some(file_controls.clone()),
        }
        self.file_controls = Some(file_controls);
        self.panel.load_error = None;
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

    // ---- rendering ---------------------------------------------------------------------------

    /// Restarts refinement if the scene or the controls differ from what is being rendered.
    fn sync_render(&mut self, changed_at: Instant) {
        let (Some(scene), Some(controls)) = (&self.scene, &self.controls) else {
            return;
        };
        let current = self
            .rendering
            .as_ref()
            .is_some_and(|r| Arc::ptr_eq(&r.scene, scene) && r.controls == *controls);
        if current {
            return;
        }
        let camera = match controls.check(self.panel.max_side) {
            Ok(camera) => camera,
            Err(e) => {
                self.panel.control_error = Some(e);
                return;
            }
        };
        self.panel.control_error = None;
        let settings = controls.settings.clone();
        if self.options.size.is_some()
            || self.file_controls.as_ref().is_some_and(|f| {
                (f.settings.width, f.settings.height) != (settings.width, settings.height)
            })
        {
            // A size the user chose stays for the next scenes.
            self.options.size = Some((settings.width, settings.height));
        }
        let film = match &self.rendering {
            // The film is reused at the same size: the new render's first pass paints over
            // every pixel, and until then the old image stays on screen.
            Some(r) if (r.film.width(), r.film.height()) == (settings.width, settings.height) => {
                r.film.clone()
            }
            _ => Arc::new(Film::new(settings.width, settings.height)),
        };
        if let Some(old) = &self.rendering {
            old.control.cancel();
        }
        let control = Arc::new(RenderControl::default());
        let report = Arc::new(JobReport::new());
        let job = Job {
            scene: scene.clone(),
            camera,
            settings,
            light_scale: controls.light_scale,
            film: film.clone(),
            control: control.clone(),
            report: report.clone(),
        };
        if let Err(e) = self.worker.submit(job) {
            self.panel.control_error = Some(e);
        }
        self.rendering = Some(Rendering {
            scene: scene.clone(),
            controls: controls.clone(),
            film,
            control,
            report,
            changed_at,
            first_image_shown: false,
            block_one_shown: false,
            settled: false,
        });
    }

    /// Refinement of the current scene and controls is over and on screen, and no scene is
    /// loading.
    fn idle(&self) -> bool {
        let settled = match (&self.rendering, &self.scene, &self.controls) {
            (Some(r), Some(scene), Some(controls)) => {
                let current = Arc::ptr_eq(&r.scene, scene) && r.controls == *controls;
                // Controls that cannot be rendered leave the last render as the final one.
                r.settled && (current || self.panel.control_error.is_some())
            }
            _ => false,
        };
        !self.loading && settled
    }

    fn status(&self) -> String {
        let Some(r) = &self.rendering else {
            return if self.loading {
                "loading…"
            } else {
                "no scene"
            }
            .to_string();
        };
        let outcome = r.report.outcome();
        if let Some(Outcome::Failed(e)) = &outcome {
            return e.clone();
        }
        let elapsed = match (&outcome, r.report.passes().last()) {
            (Some(_), Some(_)) => r.report.passes().iter().map(|p| p.time).sum(),
            _ => r.report.started.elapsed(),
        };
        status_line(&RenderStatus {
            progress: r.control.progress(),
            last_pass: r.report.last_pass_time(),
            rays: r.control.rays(),
            elapsed,
            fps: self.fps,
        })
    }

    // ---- actions -----------------------------------------------------------------------------

    fn apply(&mut self, action: Action, shown: PixelRect) {
        let bounds = self.scene.as_ref().map(|s| s.bounds);
        match action {
            Action::Open(path) => {
                if let Some(p) = &path {
                    self.panel.open_field = p.display().to_string();
                }
                self.start_load(path);
            }
            Action::Save => self.save(),
            Action::PrintCamera => {
                if let Some(c) = &self.controls {
                    println!("{}", save::camera_snippet(&c.camera));
                    self.panel.message = Some("camera printed on the terminal".into());
                }
            }
            Action::PickCentre { x, y } => self.pick_centre(x, y),
            other => {
                let (Some(controls), Some(bounds)) = (&mut self.controls, bounds) else {
                    return;
                };
                let spec = &controls.camera;
                let size = (controls.settings.width, controls.settings.height);
                let new = match other {
                    Action::Orbit { yaw, pitch } => Some(navigation::orbit(spec, yaw, pitch)),
                    Action::Pan { dx, dy } => {
                        let height = if shown.is_empty() {
                            size.1 as f32
                        } else {
                            shown.height
                        };
                        Some(navigation::pan(spec, dx, dy, height))
                    }
                    Action::Dolly(steps) => Some(navigation::dolly(spec, steps)),
                    Action::Fly { motion, seconds } => {
                        let distance = navigation::fly_speed(spec, bounds) * seconds;
                        Some(navigation::fly(spec, motion, distance))
                    }
                    Action::Frame => {
                        navigation::frame(spec, bounds, size.0 as f32 / size.1.max(1) as f32)
                    }
                    Action::ResetCamera => self.scene.as_ref().map(|s| s.scene.camera.spec),
                    _ => None,
                };
                if let Some(new) = new {
                    controls.camera = new;
                }
            }
        }
    }

    fn pick_centre(&mut self, x: f32, y: f32) {
        let (Some(scene), Some(controls)) = (&self.scene, &mut self.controls) else {
            return;
        };
        let Ok(camera) = Camera::new(controls.camera) else {
            return;
        };
        let size = (controls.settings.width, controls.settings.height);
        let point = pick::surface_point(&scene.scene, &scene.bvh, &camera, size, (x, y));
        match point.and_then(|p| navigation::look_at_point(&controls.camera, p)) {
            Some(spec) => controls.camera = spec,
            None => self.panel.message = Some("no surface under the cursor".into()),
        }
    }

    fn save(&mut self) {
        let (Some(r), Some(controls)) = (&self.rendering, &self.controls) else {
            return;
        };
        let path = PathBuf::from(self.panel.save_field.trim());
        let message = save::save_view(&path, &r.film, &controls.camera)
            .unwrap_or_else(|e| format!("cannot save: {e}"));
        println!("{message}");
        self.panel.message = Some(message);
    }

    // ---- frames ------------------------------------------------------------------------------

    /// The panels, the status line and the image area; returns the actions and where the image
    /// goes (physical pixels).
    fn ui(&mut self, ui: &mut egui::Ui, seconds: f32) -> (Vec<Action>, PixelRect) {
        let mut actions = Vec::new();
        let status = self.status();
        panels::status_bar(ui, &status, &self.panel);
        if let Some(controls) = &mut self.controls {
            actions.extend(panels::side_panel(ui, controls, &mut self.panel));
        }
        let ppp = ui.ctx().pixels_per_point();
        let image_size = self
            .rendering
            .as_ref()
            .map_or((0, 0), |r| (r.film.width(), r.film.height()));
        let mut shown = PixelRect {
            x: 0.0,
            y: 0.0,
            width: 0.0,
            height: 0.0,
        };
        egui::CentralPanel::no_frame().show(ui, |ui| {
            let rect = ui.available_rect_before_wrap();
            let response = ui.allocate_rect(rect, egui::Sense::click_and_drag());
            let area = PixelRect {
                x: rect.min.x * ppp,
                y: rect.min.y * ppp,
                width: rect.width() * ppp,
                height: rect.height() * ppp,
            };
            shown = letterbox(area, image_size.0, image_size.1);
            if self.rendering.is_none() {
                let text = self
                    .panel
                    .load_error
                    .as_deref()
                    .unwrap_or("loading the scene…");
                ui.put(rect, egui::Label::new(text));
            }
            let area = ImageArea {
                shown,
                pixels_per_point: ppp,
                image_size,
            };
            actions.extend(input::actions(ui.ctx(), &response, &area, seconds));
        });
        (actions, shown)
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        let dt = now - self.last_frame;
        self.last_frame = now;
        let Some(gfx) = &mut self.gfx else { return };
        let raw_input = gfx.egui_state.take_egui_input(&gfx.window);
        let ctx = self.egui_ctx.clone();
        let mut actions = Vec::new();
        let mut shown = None;
        let mut output = ctx.run_ui(raw_input, |ui| {
            let (a, s) = self.ui(ui, dt.as_secs_f32().min(0.1));
            actions = a;
            shown = Some(s);
        });
        let shown = shown.unwrap_or(PixelRect {
            x: 0.0,
            y: 0.0,
            width: 0.0,
            height: 0.0,
        });
        if let Some(action) = self.options.script.next(self.idle(), self.loads) {
            actions.push(action);
        }
        for action in actions {
            self.apply(action, shown);
        }
        self.sync_render(now);
        let idle = self.idle();

        let Some(gfx) = &mut self.gfx else { return };
        gfx.egui_state
            .handle_platform_output(&gfx.window, output.platform_output);
        let primitives =
            ctx.tessellate(std::mem::take(&mut output.shapes), output.pixels_per_point);
        gfx.painter
            .set_textures(&gfx.gpu, &mut output.textures_delta);

        // Upload the film if it changed; remember how far the render was when it was read.
        let mut uploaded = None;
        if let Some(r) = &self.rendering {
            let progress = r.control.progress();
            let (texture, created) =
                gfx.painter
                    .quad
                    .image_texture(&gfx.gpu.device, r.film.width(), r.film.height());
            if created {
                self.uploader.invalidate();
            }
            let start = Instant::now();
            if let Some(rgba) = self.uploader.changed_pixels(&r.film) {
                write_texture(&gfx.gpu.queue, texture, rgba);
                self.timing.upload(start.elapsed());
                uploaded = Some(progress);
            } else if r.report.outcome().is_some() {
                uploaded = Some(progress);
            }
        }

        let content = FrameContent {
            primitives: &primitives,
            pixels_per_point: output.pixels_per_point,
            shown,
        };
        let mut presented = false;
        match gfx.surface.acquire(&gfx.gpu) {
            Acquired::Frame(frame) => {
                gfx.painter.paint(&gfx.gpu, &frame.texture, &content);
                gfx.window.pre_present_notify();
                gfx.gpu.queue.present(frame);
                presented = true;
            }
            Acquired::Retry => gfx.window.request_redraw(),
            Acquired::Skip => {}
        }
        let done =
            self.options.exit_when_done && presented && self.options.script.is_done() && idle;
        if done && let Some(path) = &self.options.screenshot {
            let size = gfx.surface.size();
            let format = gfx.surface.format();
            match screenshot::save(&gfx.gpu, &mut gfx.painter, format, size, &content, path) {
                Ok(()) => {
                    let s = shown;
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
                }
                Err(e) => self.error = Some(e),
            }
        }
        gfx.painter.free_textures(&mut output.textures_delta);

        let tracing = self.rendering.as_ref().is_some_and(|r| !r.settled);
        if presented {
            self.fps = 0.9 * self.fps + 0.1 / dt.as_secs_f32().max(1e-4);
            self.timing.frame(dt, tracing);
            if let (Some(r), Some(progress)) = (&mut self.rendering, uploaded) {
                r.shown(progress, &mut self.timing);
                if matches!(r.report.outcome(), Some(Outcome::Failed(_))) {
                    r.settled = true;
                }
            }
        }
        if done {
            if self.timing.enabled() {
                eprintln!("{}", self.timing.summary());
            }
            self.exit(event_loop);
            return;
        }

        // The next frame: soon while something moves, else when egui or an event asks.
        let animating =
            tracing || self.loading || input::flying(&ctx) || !self.options.script.is_done();
        let egui_delay = output
            .viewport_output
            .get(&egui::ViewportId::ROOT)
            .map_or(Duration::MAX, |v| v.repaint_delay);
        let frame_time = Duration::from_secs_f32(1.0 / self.options.max_fps.max(1.0));
        self.next_frame = if animating {
            Some(now + frame_time)
        } else if egui_delay < Duration::from_secs(3600) {
            Some(now + egui_delay.max(frame_time))
        } else {
            None
        };
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
                self.apply(
                    Action::Open(Some(path)),
                    PixelRect {
                        x: 0.0,
                        y: 0.0,
                        width: 0.0,
                        height: 0.0,
                    },
                );
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
