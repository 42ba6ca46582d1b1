//! `raylab diff`: how an image differs from a reference, as a course grades a student's ray
//! tracer: the figures, FLIP (NVIDIA's perceptual difference), and a heat map of where. The
//! exit status is `cmp`'s: 0 within the tolerance, 1 different, 2 trouble.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use raylab::compare::difference::{DEFAULT_TOLERANCE, Difference, difference, heat_map};
use raylab::formats::image::{check_image_path, save_image};
use raylab::srgb_image::SrgbImage;

use super::Verdict;

#[derive(Args, Debug)]
pub struct DiffArgs {
    /// The reference image: PNG, PPM, BMP, JPEG, OpenEXR or Radiance HDR (floats are compared
    /// through the sRGB curve, clamped, as raylab writes 8-bit files).
    reference: PathBuf,
    /// The image to compare with it, of the same size, in any of those formats.
    image: PathBuf,
    /// Also write a heat map of the difference to this file (and its legend beside it, as
    /// NAME.legend.png).
    #[arg(short, long, value_name = "DIFF.png")]
    output: Option<PathBuf>,
    /// How many 8-bit levels a channel may be off before its pixel counts as different.
    #[arg(long, value_name = "LEVELS", default_value_t = DEFAULT_TOLERANCE)]
    tolerance: u8,
    /// Print the figures as JSON instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(args: DiffArgs) -> Result<Verdict, String> {
    if let Some(output) = &args.output {
        check_image_path(output).map_err(|e| e.to_string())?;
        check_image_path(&super::legend_path(output)).map_err(|e| e.to_string())?;
    }
    let reference = SrgbImage::read(&args.reference)?;
    let image = SrgbImage::read(&args.image)?;
    let figures = difference(&reference, &image, args.tolerance)?;
    let flip = flip(&reference, &image);
    let legend = match &args.output {
        Some(output) => {
            let (pixels, legend) = heat_map(&reference, &image, &figures);
            save_image(output, figures.width, figures.height, &pixels)
                .map_err(|e| e.to_string())?;
            let path = super::save_legend(&legend, output)?;
            Some((legend, path))
        }
        None => None,
    };
    super::print_out(|out| {
        if args.json {
            let json = to_json(&args, &figures, flip);
            writeln!(out, "{json:#}")
        } else {
            write!(out, "{}", to_text(&args, &figures, flip))?;
            if let Some((legend, path)) = &legend {
                writeln!(out, "{} → {}", legend.to_text(), path.display())?;
            }
            Ok(())
        }
    })?;
    Ok(Verdict::from_difference(&figures))
}

/// The mean FLIP error of `image` against `reference`, from 0 (the same to the eye) to 1, at
/// FLIP's default viewing distance (67 pixels per degree: a 0.7 m wide 4K screen seen from
/// 0.7 m).
pub fn flip(reference: &SrgbImage, image: &SrgbImage) -> f32 {
    let flip_image = |image: &SrgbImage| {
        let bytes: Vec<u8> = image.pixels.iter().flatten().copied().collect();
        nv_flip::FlipImageRgb8::with_data(image.width, image.height, &bytes)
    };
    let map = nv_flip::flip(
        flip_image(reference),
        flip_image(image),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    nv_flip::FlipPool::from_image(&map).mean()
}

fn name(path: &Path) -> String {
    path.display().to_string()
}

fn to_text(args: &DiffArgs, d: &Difference, flip: f32) -> String {
    let (x, y) = d.largest_at;
    let psnr = if d.psnr.is_finite() {
        format!("{:.2} dB", d.psnr)
    } else {
        "infinite (the images are equal)".to_string()
    };
    let verdict = if d.within_tolerance() {
        "within tolerance"
    } else {
        "different"
    };
    format!(
        "{} against {}: {}×{} pixels\n\
         mean absolute difference: {:.4} levels\n\
         RMSE: {:.4} levels\n\
         PSNR: {psnr}\n\
         largest difference: {} levels at pixel ({x}, {y})\n\
         over the tolerance of {} levels: {} pixels ({:.2} %)\n\
         FLIP: {flip:.4}\n\
         {verdict}\n",
        name(&args.image),
        name(&args.reference),
        d.width,
        d.height,
        d.mean_absolute,
        d.rmse,
        d.largest,
        d.tolerance,
        d.over_tolerance,
        100.0 * d.over_tolerance_share(),
    )
}

fn to_json(args: &DiffArgs, d: &Difference, flip: f32) -> serde_json::Value {
    serde_json::json!({
        "reference": name(&args.reference),
        "image": name(&args.image),
        "width": d.width,
        "height": d.height,
        "mean_absolute": d.mean_absolute,
        "rmse": d.rmse,
        "psnr": d.psnr.is_finite().then_some(d.psnr),
        "largest": { "levels": d.largest, "x": d.largest_at.0, "y": d.largest_at.1 },
        "tolerance": d.tolerance,
        "over_tolerance": d.over_tolerance,
        "flip": flip,
        "within_tolerance": d.within_tolerance(),
        "heat_map": args.output.as_deref().map(name),
    })
}
