//! `raylab view` (and `raylab` with no subcommand): the viewer's command-line options.

use std::path::PathBuf;
use std::sync::Arc;

use clap::Args;
use raylab::formats::SceneFormat;
use raylab::inspect::DebugView;
use raylab::output::check_writable;
use raylab::render::{Device, FirstHit};
use raylab::settings::{RenderSettings, SettingsOverrides};
use raylab::srgb_image::SrgbImage;

use super::overrides::{OverrideArgs, parse_size};

use crate::viewer::layout::{MAX_WINDOW_SIDE, check_window_size};
use crate::viewer::{self, Options, Script, script_steps};

#[derive(Args, Debug)]
pub struct ViewArgs {
    /// Scene to open: a .toml, .nff, SDL (.dat, .sdl), .obj, .ply, .gltf or .glb file, or spd:NAME[:SIZE]; the built-in
    /// default scene when left out.
    scene: Option<PathBuf>,
    /// The scene file's format, whatever its name ends in: toml, nff, sdl, obj or ply.
    #[arg(long)]
    format: Option<SceneFormat>,
    /// Overrides of the scene's render settings.
    #[command(flatten)]
    overrides: OverrideArgs,
    /// What the image shows: shaded, normals, depth, uv, object, material, item-buffer,
    /// tree-depth, rays or bvh-cost (switchable in the Tracing panel).
    #[arg(long, value_name = "NAME", default_value = "shaded", value_parser = |s: &str| s.parse::<DebugView>())]
    view: DebugView,
    /// Tracing threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Which tracer renders the shaded image: cpu or gpu (the debug views trace on the CPU).
    /// Default: the GPU when its adapter is real hardware, the CPU when it is a software
    /// rasterizer such as llvmpipe.
    #[arg(long)]
    device: Option<Device>,
    /// Where the eye rays find their first hits: rays (each searches the BVH) or raster (each
    /// starts from the item buffer, drawn on the GPU; the same image). The Tracing panel
    /// switches it.
    #[arg(long, default_value_t = FirstHit::Rays)]
    first_hit: FirstHit,
    /// Window size in logical pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_window_size, default_value = "1100x720")]
    window: Option<(u32, u32)>,
    /// Where "Save image" (Ctrl+S) writes; the camera snippet goes beside it as NAME.camera.toml.
    #[arg(long, value_name = "PATH", default_value = "raylab.png")]
    save: PathBuf,
    /// Before exiting (see --exit-when-done), save a screenshot of the window, as drawn, here.
    #[arg(long, value_name = "PATH")]
    screenshot: Option<PathBuf>,
    /// Exit once the script has run and refinement has reached its last pass (for tests).
    #[arg(long)]
    exit_when_done: bool,
    /// Print the UI's frame rate, the film's upload time, the time from each change to the
    /// first image (and the block size it started at) and to block size 1 on screen, and pauses.
    #[arg(long)]
    stats: bool,
    /// Scripted input, steps separated by `;` (`--help` lists them).
    #[arg(long, value_name = "STEPS", value_parser = Script::parse, long_help = script_steps::help())]
    script: Option<Script>,
    /// Most frames per second while refining.
    #[arg(long, default_value_t = 60.0)]
    max_fps: f32,
    /// An image to compare with (PNG, PPM, BMP, JPEG, OpenEXR or Radiance HDR): shown as the
    /// snapshot, left of the split view's divider, with the scene rendered at its size. X (or
    /// the script step `compare diff`) shows the heat map of the difference; a picked pixel
    /// shows both colours beside its ray tree.
    #[arg(long, value_name = "IMAGE")]
    compare: Option<PathBuf>,
}

/// `WxH` (or `N`), each side from 1 to [`MAX_WINDOW_SIDE`].
fn parse_window_size(text: &str) -> Result<(u32, u32), String> {
    let (width, height) = parse_size(text)?;
    check_window_size(width, height, MAX_WINDOW_SIDE, "raylab's largest window")?;
    Ok((width, height))
}

pub fn run(args: ViewArgs) -> Result<(), String> {
    let threads = super::thread_count(args.threads)?;
    if let Some(path) = &args.screenshot {
        if !args.exit_when_done {
            return Err("--screenshot is taken when the viewer exits: add --exit-when-done".into());
        }
        check_writable(path).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let mut overrides = SettingsOverrides::from(args.overrides);
    let compare = match &args.compare {
        Some(path) => {
            let image = SrgbImage::read(path)?;
            let size = (image.width, image.height);
            let given = (overrides.width, overrides.height);
            if given.0.is_some_and(|w| w != size.0) || given.1.is_some_and(|h| h != size.1) {
                return Err(format!(
                    "{} is {}×{}: the scene is rendered at the size of the image compared with, \
                     so leave out --size, --width and --height",
                    path.display(),
                    size.0,
                    size.1
                ));
            }
            (overrides.width, overrides.height) = (Some(size.0), Some(size.1));
            // As `raylab check` does: a tracer of one ray per pixel is compared with one
            // sample a pixel, unless --samples says otherwise.
            overrides.samples.get_or_insert(1);
            Some(Arc::new(image))
        }
        None => None,
    };
    // Checked before the window opens: each setting's range is its own, so overrides that are
    // right on the default settings are right on any scene's; the camera's as far as they can be
    // without the scene's camera.
    overrides.apply(&mut RenderSettings::default())?;
    overrides.check_camera()?;
    viewer::run(Options {
        scene: args.scene,
        format: args.format,
        overrides,
        debug_view: args.view,
        threads,
        device: args.device,
        first_hit: args.first_hit,
        window: args.window.unwrap_or((1100, 720)),
        save_path: args.save,
        screenshot: args.screenshot,
        exit_when_done: args.exit_when_done,
        stats: args.stats,
        script: args.script.unwrap_or_default(),
        max_fps: args.max_fps,
        compare,
    })
}
