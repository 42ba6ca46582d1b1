//! `raylab inspect`: the ray tree of one pixel, as text or JSON, and as the lecture's figure
//! ([`super::figure`]).

use std::io::Write;

use clap::Args;

use raylab::backend::Backend;
use raylab::formats::SceneFormat;
use raylab::formats::nff::NffLighting;
use raylab::inspect::{DebugView, trace_ray_tree};
use raylab::render::{FirstHit, assemble};
use raylab::settings::SettingsOverrides;

use super::figure::FigureArgs;
use super::overrides::OverrideArgs;

#[derive(Args, Debug)]
pub struct InspectArgs {
    /// Scene: a .toml, .nff, SDL (.dat, .sdl), .obj, .ply, .gltf or .glb file, or `spd:NAME[:SIZE]`; the built-in default scene when left
    /// out.
    scene: Option<String>,
    /// The scene file's format, whatever its name ends in: toml, nff, sdl, obj or ply.
    #[arg(long)]
    format: Option<SceneFormat>,
    /// The pixel, `X,Y`: X from the left, Y from the top of the image, from 0.
    #[arg(long, value_parser = parse_pixel)]
    pixel: (u32, u32),
    /// Print the tree as JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Overrides of the scene's render settings.
    #[command(flatten)]
    overrides: OverrideArgs,
    /// Brightness of NFF and SPD scenes' lights (see `raylab render --help`).
    #[arg(long, default_value_t = NffLighting::default())]
    nff_lights: NffLighting,
    /// Where the eye ray finds its first hit: rays, or raster (from the item buffer, drawn on
    /// the GPU; the tree says whether the hit came from it).
    #[arg(long, default_value_t = FirstHit::Rays)]
    first_hit: FirstHit,
    /// The ray-tree figure.
    #[command(flatten)]
    figure: FigureArgs,
}

/// `X,Y` as two integers.
fn parse_pixel(text: &str) -> Result<(u32, u32), String> {
    let usage = || format!("expected X,Y (two whole numbers, e.g. 320,240), got `{text}`");
    let (x, y) = text.split_once(',').ok_or_else(usage)?;
    let number = |s: &str| s.trim().parse::<u32>().map_err(|_| usage());
    Ok((number(x)?, number(y)?))
}

pub fn run(mut args: InspectArgs) -> Result<(), String> {
    args.figure.check()?;
    let observer_look_at = match args.figure.draw {
        Some(_) => args.overrides.take_look_at(),
        None => None,
    };
    let mut scene = super::load_scene(args.scene.as_deref(), args.nff_lights, args.format)?;
    let overrides = SettingsOverrides::from(args.overrides);
    overrides.apply(&mut scene.settings)?;
    scene.camera = overrides.apply_camera(scene.camera.spec)?;
    let (width, height) = (scene.settings.width, scene.settings.height);
    let (x, y) = args.pixel;
    if x >= width || y >= height {
        return Err(format!(
            "pixel ({x}, {y}) is outside the {width}×{height} image (x < {width}, y < {height})"
        ));
    }
    let assembled = assemble(scene)?;
    let mut backend = Backend::new(super::thread_pool(None)?);
    backend.set_first_hit(args.first_hit);
    let items = backend
        .item_buffer(&assembled, ((0, 0), (width, height)))
        .map_err(|e| super::explain(e, DebugView::Shaded, args.first_hit))?;
    let tracer = assembled.tracer().with_item_buffer(items.as_ref());
    let tree = trace_ray_tree(&tracer, x, y);
    let text = if args.json {
        let json = serde_json::to_string_pretty(&tree)
            .map_err(|e| format!("cannot write the tree as JSON: {e}"))?;
        json + "\n"
    } else {
        tree.to_text()
    };
    super::print_out(|out| out.write_all(text.as_bytes()))?;
    args.figure
        .write(&tree, &assembled, observer_look_at, &mut backend)
}
