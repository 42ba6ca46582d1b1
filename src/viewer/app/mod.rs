//! The viewer's app and its event loop (winit): the app is a handful of parts, each owning its
//! state ([`Graphics`] the window and GPU, [`Ui`] egui, [`Input`] the script, [`SceneSlot`] the
//! scene and its loads, [`Tracing`] the render and the picked pixel, [`FrameClock`] when frames
//! come); here the window opens and the events (window, loader, watcher) reach them. A frame is
//! drawn in [`frame`], and the actions of its input carried out in [`apply`]; while the tracer
//! works (or a key is held) frames come at a steady rate ([`clock`]), otherwise the loop sleeps
//! until an event arrives.

use std::sync::Arc;

use raylab::gpu::device::GpuDevice;
use raylab::render::Device;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, EventLoopProxy, OwnedDisplayHandle};
use winit::window::WindowId;

mod apply;
mod clock;
mod frame;
mod rays3d;

use self::clock::FrameClock;
use super::Options;
use crate::viewer::display::Graphics;
use crate::viewer::input::Input;
use crate::viewer::input::action::Action;
use crate::viewer::layout::{PixelRect, Resolution};
use crate::viewer::scene::source::LoadedScene;
use crate::viewer::scene::{SceneNews, SceneSlot};
use crate::viewer::ui::Ui;
use crate::viewer::ui::display::DisplayControls;
use crate::viewer::ui::panels::PanelState;
use crate::viewer::workers::Tracing;

/// What other threads tell the event loop.
pub enum UserEvent {
    /// The scene's loader or watcher has news.
    Scene(SceneNews),
    /// The ray tree thread has traced what it was asked.
    RayTreeTraced,
}

/// The viewer: its window, what it shows, the script, the scene, the tracing and the frames.
pub struct App {
    /// The window and what draws into it, once it is open.
    pub(super) gpu: Option<Graphics>,
    /// The GPU the tracer opened at the start, if the window is to share it ([`window_shares`]).
    shared_gpu: Option<Arc<GpuDevice>>,
    pub(super) ui: Ui,
    pub(super) input: Input,
    pub(super) scene: SceneSlot,
    pub(super) tracing: Tracing,
    pub(super) clock: FrameClock,
    /// Set once the viewer stops: `Err` says why it had to.
    pub(super) ended: Option<Result<(), String>>,
}

impl App {
    /// The viewer for `options`; `display` is the display its window will open on, which the
    /// tracer's GPU is opened for.
    pub fn new(
        options: Options,
        proxy: EventLoopProxy<UserEvent>,
        display: OwnedDisplayHandle,
    ) -> Result<App, String> {
        let Options {
            scene,
            format,
            overrides,
            debug_view,
            threads,
            device,
            first_hit,
            window,
            save_path,
            screenshot,
            exit_when_done,
            stats,
            script,
            max_fps,
            compare,
        } = options;
        let (device, tracer_gpu) = pick_device(device, display)?;
        let wake = proxy.clone();
        let shared_gpu = tracer_gpu.clone().filter(|gpu| window_shares(gpu, device));
        let tracing = Tracing::start(threads, tracer_gpu, move || {
            let _ = wake.send_event(UserEvent::RayTreeTraced);
        })?;
        let panel = PanelState {
            open_field: scene
                .as_ref()
                .map(|p| p.display().to_string())
                .unwrap_or_default(),
            save_field: save_path.display().to_string(),
            message: None,
            resolution: Resolution::at_start(overrides.width, overrides.height),
            max_side: 2048,
            display: DisplayControls {
                snapshot: compare.as_ref().map(|image| (image.width, image.height)),
                compare: compare.is_some(),
                snapshot_is_yours: compare.is_some(),
                ..Default::default()
            },
            compared: compare,
        };
        Ok(App {
            gpu: None,
            shared_gpu,
            ui: Ui::new(panel, window),
            input: Input::new(script, exit_when_done, screenshot),
            scene: SceneSlot::new(
                scene,
                format,
                overrides,
                debug_view,
                (device, first_hit),
                Arc::new(move |news| {
                    let _ = proxy.send_event(UserEvent::Scene(news));
                }),
            ),
            tracing,
            clock: FrameClock::new(stats, max_fps),
            ended: None,
        })
    }

    /// How the viewer ended: `Err` says why it had to stop.
    pub fn result(self) -> Result<(), String> {
        self.ended.unwrap_or(Ok(()))
    }

    pub(super) fn fail(&mut self, event_loop: &ActiveEventLoop, message: String) {
        self.ended = Some(Err(message));
        self.exit(event_loop);
    }

    pub(super) fn exit(&mut self, event_loop: &ActiveEventLoop) {
        self.tracing.cancel();
        self.ended.get_or_insert(Ok(()));
        event_loop.exit();
    }

    pub(super) fn request_redraw(&self) {
        if let Some(gfx) = &self.gpu {
            gfx.window().request_redraw();
        }
    }

    /// Starts loading `path` (the default scene for `None`) and watches it.
    pub(super) fn start_load(&mut self, path: Option<std::path::PathBuf>) {
        if let Err(e) = self.scene.start_load(path) {
            self.ui.panel.message = Some(e);
        }
    }

    /// A load has finished: the scene is shown (its warnings printed, its name in the title), or
    /// its error printed (and the viewer stopped, if it exits when done and has no scene).
    fn loaded(
        &mut self,
        event_loop: &ActiveEventLoop,
        generation: u64,
        result: Result<Box<LoadedScene>, String>,
    ) {
        if !self.scene.is_latest(generation) {
            return;
        }
        let had_scene = self.scene.shown().is_some();
        match self.scene.finish_load(result) {
            Err(message) => {
                eprintln!("error: {message}");
                if !had_scene && self.input.exit_when_done() {
                    self.fail(event_loop, message);
                }
            }
            Ok(loaded) => {
                for warning in &loaded.scene().warnings {
                    eprintln!("warning: {warning}");
                }
                for note in &loaded.scene().notes {
                    eprintln!("note: {note}");
                }
                if let Some(gfx) = &self.gpu {
                    gfx.window()
                        .set_title(&format!("raylab — {}", loaded.name()));
                }
                if self.clock.timing.enabled() {
                    eprintln!(
                        "stats: loaded {} in {:.1} ms",
                        loaded.name(),
                        loaded.load_time.as_secs_f64() * 1e3
                    );
                }
            }
        }
    }
}

impl ApplicationHandler<UserEvent> for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gpu.is_some() {
            return;
        }
        let (size, shared_gpu) = (self.ui.window_size, self.shared_gpu.as_ref());
        match Graphics::open(event_loop, size, &self.ui.egui, shared_gpu) {
            Ok(gfx) => {
                self.ui.panel.max_side = gfx.max_side();
                self.gpu = Some(gfx);
            }
            Err(e) => return self.fail(event_loop, e),
        }
        let first = self.scene.requested();
        self.start_load(first);
    }

    fn user_event(&mut self, event_loop: &ActiveEventLoop, event: UserEvent) {
        match event {
            UserEvent::Scene(SceneNews::Loaded { generation, result }) => {
                self.loaded(event_loop, generation, result);
            }
            UserEvent::RayTreeTraced => {}
            UserEvent::Scene(SceneNews::FileChanged(changed)) => {
                if let Some(path) = self.scene.requested()
                    && !self.scene.wrote_it(&changed)
                {
                    self.start_load(Some(path));
                }
            }
        }
        self.request_redraw();
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        if self.ended.is_some() {
            return;
        }
        let Some(gfx) = &mut self.gpu else { return };
        gfx.window_event(&event);
        match event {
            WindowEvent::CloseRequested => self.exit(event_loop),
            WindowEvent::DroppedFile(path) => {
                self.apply(Action::Open(Some(path)), PixelRect::ZERO);
                self.request_redraw();
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.ended.is_some() {
            return;
        }
        let (flow, due) = self.clock.wait();
        if due {
            self.request_redraw();
        }
        event_loop.set_control_flow(flow);
    }

    fn exiting(&mut self, _event_loop: &ActiveEventLoop) {
        self.tracing.cancel();
    }
}

/// Whether the window draws with the tracer's GPU `gpu`, so that the GPU tracer's image goes
/// straight into the window's texture: when the viewer starts on the GPU (`device`), or the
/// adapter is real hardware. Not on a software adapter when the viewer starts on the CPU: Mesa's
/// lavapipe compiles a shader under the lock of its device's queue, so the window would stand
/// still for the minute or two of the GPU tracer's first compile, should the device switch
/// hand it the render.
fn window_shares(gpu: &GpuDevice, device: Device) -> bool {
    device == Device::Gpu || gpu.adapter.get_info().device_type != wgpu::DeviceType::Cpu
}

/// The tracer the viewer starts with, and the GPU if it opened one (on `display`, so that the
/// window can share it, whichever tracer starts: the device switch may hand the render to the
/// GPU later): the one asked for, else the GPU when its adapter is real hardware and the CPU
/// when it is a software rasterizer or there is none. The error says why the GPU asked for
/// cannot be opened.
fn pick_device(
    asked: Option<Device>,
    display: OwnedDisplayHandle,
) -> Result<(Device, Option<Arc<GpuDevice>>), String> {
    let open = || {
        let instance = wgpu::Instance::new(
            wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(display)),
        );
        GpuDevice::on_instance(instance).map(Arc::new)
    };
    match asked {
        Some(Device::Cpu) => Ok((Device::Cpu, open().ok())),
        Some(Device::Gpu) => {
            let gpu = open().map_err(|e| format!("--device gpu: {e}"))?;
            Ok((Device::Gpu, Some(gpu)))
        }
        None => match open() {
            Ok(gpu) if gpu.adapter.get_info().device_type != wgpu::DeviceType::Cpu => {
                Ok((Device::Gpu, Some(gpu)))
            }
            Ok(gpu) => Ok((Device::Cpu, Some(gpu))),
            Err(_) => Ok((Device::Cpu, None)),
        },
    }
}
