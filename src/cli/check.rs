//! `raylab check`: renders the reference of a scene at an image's size and says why the image
//! differs from it: the common mistakes that account for it, and for the worst pixels of the
//! largest regions that differ, raylab's ray tree there. The exit status is `diff`'s.

use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use raylab::compare::check::{check, memory_bytes};
use raylab::compare::difference::DEFAULT_TOLERANCE;
use raylab::compare::traces::Traces;
use raylab::formats::SceneFormat;
use raylab::formats::nff::NffLighting;
use raylab::memory;
use raylab::render::assemble;
use raylab::settings::SettingsOverrides;
use raylab::srgb_image::SrgbImage;

use super::Verdict;
use super::overrides::OverrideArgs;

#[derive(Args, Debug)]
pub struct CheckArgs {
    /// The scene the image is of: a .toml, .nff, SDL (.dat, .sdl), .obj, .ply, .gltf or .glb file, or `spd:NAME[:SIZE]`.
    scene: String,
    /// The image to check: PNG, PPM, BMP, JPEG, OpenEXR or Radiance HDR. raylab renders the
    /// scene at its size.
    image: PathBuf,
    /// How many 8-bit levels a channel may be off before its pixel counts as different.
    #[arg(long, value_name = "LEVELS", default_value_t = DEFAULT_TOLERANCE)]
    tolerance: u8,
    /// Print the findings as JSON instead of text.
    #[arg(long)]
    json: bool,
    /// The scene file's format, whatever its name ends in: toml, nff, sdl, obj or ply.
    #[arg(long)]
    format: Option<SceneFormat>,
    /// Overrides of the scene's render settings (the size is the image's).
    #[command(flatten)]
    overrides: OverrideArgs,
    /// Brightness of NFF and SPD scenes' lights (see `raylab render --help`).
    #[arg(long, default_value_t = NffLighting::default())]
    nff_lights: NffLighting,
}

pub fn run(args: CheckArgs) -> Result<Verdict, String> {
    let (size, decoder) = SrgbImage::probe(&args.image)?;
    let mut scene = super::load_scene(Some(&args.scene), args.nff_lights, args.format)?;
    let overrides = SettingsOverrides::from(args.overrides);
    if overrides.width.is_some_and(|w| w != size.0) || overrides.height.is_some_and(|h| h != size.1)
    {
        return Err(format!(
            "{} is {}×{}: raylab renders the scene at the image's size, so leave out --size, \
             --width and --height",
            args.image.display(),
            size.0,
            size.1
        ));
    }
    overrides.apply(&mut scene.settings)?;
    scene.camera = overrides.apply_camera(scene.camera.spec)?;
    (scene.settings.width, scene.settings.height) = size;
    scene.settings.validate()?;
    let pixels = u64::from(size.0) * u64::from(size.1);
    memory::check(
        &format!("checking a {}×{} image", size.0, size.1),
        pixels * 3 + decoder + memory_bytes(&scene.settings),
    )?;
    let image = SrgbImage::read(&args.image)?;
    let assembled = assemble(scene)?;
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] check: {msg}")
            .expect("the template is valid"),
    );
    bar.enable_steady_tick(Duration::from_millis(100));
    bar.set_message("tracing raylab's image");
    let traces = Traces::new(assembled, 0);
    let report = check(&traces, &image, args.tolerance, &mut |step| {
        bar.set_message(step.to_string());
    });
    bar.finish_and_clear();
    let report = report?;
    super::print_out(|out| {
        if args.json {
            let json = serde_json::to_string_pretty(&report)
                .map_err(|e| std::io::Error::other(e.to_string()))?;
            writeln!(out, "{json}")
        } else {
            let image = args.image.display().to_string();
            write!(out, "{}", report.to_text(&image, &args.scene))
        }
    })?;
    Ok(Verdict::from_difference(&report.difference))
}
