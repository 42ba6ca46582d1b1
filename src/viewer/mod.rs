//! The interactive viewer: a winit window where the library's progressive renderer refines the
//! image from coarse blocks down to single pixels on background threads, the current image is
//! drawn by wgpu on a textured quad every frame, and egui panels change the camera and the
//! settings (any change restarts refinement). Only the binary knows about it; the data still
//! flows one way: scene file → scene → BVH → tracer → film → texture → window.
//!
//! Its rooms, each owning one part of the [`app::App`], from the bottom up; each room uses only
//! rooms above it in this list:
//! - `layout.rs`: where things are in the window (pixel rectangles, the image's resolution);
//!   `timing.rs`: the viewer's own measurements (`--stats`); `save.rs`: the image and camera
//!   written to files;
//! - `scene/`: loading and watching scene files, the scene's state and the user's controls;
//! - `workers/`: the threads that trace: the render worker, the render in progress, the caustic
//!   photons they share, the picked pixel's ray tree thread, the status line;
//! - `display/`: the window's GPU (wgpu): device, surface, image quad, upload, painting,
//!   screenshots;
//! - `input/`: mouse, keys and the script, and the [`input::action::Action`]s they make;
//! - `ui/`: what egui shows: side panel, ray tree panel, overlay, legend, display controls;
//! - `app/`: the event loop, one frame (update, then paint) and when the next one comes, and
//!   carrying out the actions: the only room that changes several others at once.

mod app;
mod display;
mod input;
pub mod layout;
mod save;
mod scene;
mod timing;
mod ui;
mod workers;

use std::path::PathBuf;
use std::sync::Arc;

use raylab::formats::SceneFormat;
use raylab::inspect::DebugView;
use raylab::render::{Device, FirstHit};
use raylab::settings::SettingsOverrides;
use raylab::srgb_image::SrgbImage;
use winit::event_loop::EventLoop;

pub use input::script::Script;
pub use input::script_steps;

/// How the viewer starts.
pub struct Options {
    /// Scene file; the built-in default scene when `None`.
    pub scene: Option<PathBuf>,
    /// The scene file's format, whatever its name ends in; by its name when `None`.
    pub format: Option<SceneFormat>,
    /// The command line's overrides of each scene's settings, applied on every load.
    pub overrides: SettingsOverrides,
    /// What the image shows at the start: the shaded colour or a debug view.
    pub debug_view: DebugView,
    /// Tracing threads (0: one per core).
    pub threads: usize,
    /// Which tracer renders the shaded image; `None`: the GPU when it is real hardware, the CPU
    /// when the only adapter is a software rasterizer (llvmpipe) or there is none.
    pub device: Option<Device>,
    /// Where the eye rays find their first hits at the start.
    pub first_hit: FirstHit,
    /// Window size in logical pixels.
    pub window: (u32, u32),
    /// Where Save writes the image.
    pub save_path: PathBuf,
    /// Save a screenshot of the window here before exiting (with `exit_when_done`).
    pub screenshot: Option<PathBuf>,
    /// Exit once the script has run and refinement is over.
    pub exit_when_done: bool,
    /// Print frame rate and refinement times.
    pub stats: bool,
    pub script: Script,
    /// Most frames per second while refining.
    pub max_fps: f32,
    /// An image to compare with, shown from the start as the snapshot, in the split view (the
    /// image is rendered at its size).
    pub compare: Option<Arc<SrgbImage>>,
}

/// Opens the window and runs until it is closed; the error is the message to print.
pub fn run(options: Options) -> Result<(), String> {
    let event_loop = EventLoop::<app::UserEvent>::with_user_event()
        .build()
        .map_err(|e| {
            format!(
                "cannot open a window: {e}. The viewer needs a display (is DISPLAY or \
                 WAYLAND_DISPLAY set?); without one, use `raylab render` to render to a file"
            )
        })?;
    let display = event_loop.owned_display_handle();
    let mut app = app::App::new(options, event_loop.create_proxy(), display)?;
    event_loop
        .run_app(&mut app)
        .map_err(|e| format!("the window's event loop failed: {e}"))?;
    app.result()
}
