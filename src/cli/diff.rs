//! `raylab diff`: how an image differs from a reference, as a course grades a student's ray
//! tracer: the figures, FLIP (NVIDIA's perceptual difference), and a heat map of where. The
//! exit status is `cmp`'s: 0 within the tolerance, 1 different, 2 trouble.
//!
//! Memory stays in proportion: the two images as 8-bit pixels (3 bytes a pixel each), the
//! decoder's buffer while one is read, and tiles of FLIP's work and bands of the heat map, whose
//! sizes do not grow with the image; all of it checked against the memory available before
//! either image is read ([`memory_needed`]).

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use raylab::compare::difference::{
    DEFAULT_TOLERANCE, Difference, HeatMap, check_sizes, difference,
};
use raylab::formats::image::{OutputFormat, check_image_path, save_toned_pixels};
use raylab::memory;
use raylab::srgb_image::SrgbImage;
use raylab::tone::Tone;
use rayon::prelude::*;

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
    let (reference, image) = read_pair(&args.reference, &args.image)?;
    let figures = difference(&reference, &image, args.tolerance)?;
    let flip = flip(&reference, &image);
    let legend = match &args.output {
        Some(output) => {
            let map = HeatMap::new(&reference, &image, &figures);
            let (width, height) = (figures.width, figures.height);
            save_toned_pixels(
                output,
                width,
                height,
                &|x, y| map.color(x, y),
                Tone::default(),
            )
            .map_err(|e| e.to_string())?;
            let legend = map.legend();
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

/// Reads a reference and an image to compare with it, once their headers say they are the same
/// size and the memory comparing them takes ([`memory_needed`]) is there.
pub fn read_pair(reference: &Path, image: &Path) -> Result<(SrgbImage, SrgbImage), String> {
    let (size, reference_decoder) = SrgbImage::probe(reference)?;
    let (image_size, image_decoder) = SrgbImage::probe(image)?;
    check_sizes(size, image_size)?;
    let decoder = reference_decoder.max(image_decoder);
    memory::check(
        &format!("comparing two {}×{} images", size.0, size.1),
        memory_needed(size, decoder),
    )?;
    Ok((SrgbImage::read(reference)?, SrgbImage::read(image)?))
}

/// The memory `raylab diff` takes for two images of `size`, the larger decoder's buffer being
/// `decoder` bytes: both images' pixels (3 bytes each), the decoder's buffer and the copy its
/// pixels are taken into (3 bytes a pixel) while the second is read, FLIP's tiles on every
/// thread and a band of the heat map.
pub fn memory_needed(size: (u32, u32), decoder: u64) -> u64 {
    let pixels = u64::from(size.0) * u64::from(size.1);
    let flip_tiles = rayon::current_num_threads() as u64 * FLIP_TILE_BYTES;
    3 * pixels * 3 + decoder + flip_tiles + OutputFormat::Png.save_bytes(size.0)
}

/// FLIP's filters reach at most this many pixels from a pixel at its default 67 pixels per
/// degree (its spatial filter's radius is 10, its feature filter's 9): a tile of the images
/// with this margin gives its inner pixels the values the whole images give them.
const FLIP_MARGIN: u32 = 16;

/// The side of the tiles FLIP is computed in, margins left out.
const FLIP_TILE: u32 = 384;

/// The memory FLIP takes for one tile with its margins: both tiles' pixels as bytes and as its
/// images of floats (colours, their filtered twins and feature maps, measured at about 150
/// bytes a pixel).
const FLIP_TILE_BYTES: u64 = ((FLIP_TILE + 2 * FLIP_MARGIN) as u64).pow(2) * 160;

/// The mean FLIP error of `image` against `reference`, from 0 (the same to the eye) to 1, at
/// FLIP's default viewing distance (67 pixels per degree: a 0.7 m wide 4K screen seen from
/// 0.7 m), computed in tiles ([`FLIP_TILE`]) on all threads.
pub fn flip(reference: &SrgbImage, image: &SrgbImage) -> f32 {
    flip_in_tiles(reference, image, FLIP_TILE)
}

/// [`flip`] in tiles of `tile` pixels a side, each with a margin of [`FLIP_MARGIN`].
fn flip_in_tiles(reference: &SrgbImage, image: &SrgbImage, tile: u32) -> f32 {
    let (width, height) = (reference.width, reference.height);
    let corners: Vec<(u32, u32)> = (0..height)
        .step_by(tile as usize)
        .flat_map(|y| (0..width).step_by(tile as usize).map(move |x| (x, y)))
        .collect();
    let sum: f64 = corners
        .into_par_iter()
        .map(|(x0, y0)| {
            let (x1, y1) = ((x0 + tile).min(width), (y0 + tile).min(height));
            let (left, top) = (
                x0.saturating_sub(FLIP_MARGIN),
                y0.saturating_sub(FLIP_MARGIN),
            );
            let right = (x1 + FLIP_MARGIN).min(width);
            let bottom = (y1 + FLIP_MARGIN).min(height);
            let crop = |image: &SrgbImage| {
                let bytes: Vec<u8> = (top..bottom)
                    .flat_map(|y| (left..right).flat_map(move |x| image.at(x, y)))
                    .collect();
                nv_flip::FlipImageRgb8::with_data(right - left, bottom - top, &bytes)
            };
            let map = nv_flip::flip(
                crop(reference),
                crop(image),
                nv_flip::DEFAULT_PIXELS_PER_DEGREE,
            )
            .to_vec();
            let at = |x: u32, y: u32| map[((y - top) * (right - left) + x - left) as usize];
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| f64::from(at(x, y))))
                .sum::<f64>()
        })
        .sum();
    (sum / (f64::from(width) * f64::from(height))) as f32
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

#[cfg(test)]
mod tests {
    use super::*;

    /// An image of sharp-edged blocks and a gradient: edges and colours for FLIP's filters.
    fn pattern(width: u32, height: u32, seed: u32) -> SrgbImage {
        let pixels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| {
                let block = ((x / 7) * 31 + (y / 5) * 17 + seed * 13) % 251;
                [
                    block as u8,
                    ((x * 255) / width) as u8,
                    ((x ^ y) % 200) as u8,
                ]
            })
            .collect();
        SrgbImage::new(width, height, pixels)
    }

    #[test]
    fn flip_in_tiles_is_flip_of_the_whole_images() {
        let (reference, image) = (pattern(150, 97, 0), pattern(150, 97, 1));
        let whole = flip_in_tiles(&reference, &image, 1000);
        assert!(whole > 0.05, "the images differ: {whole}");
        for tile in [16, 40, 64] {
            let tiled = flip_in_tiles(&reference, &image, tile);
            assert!(
                (tiled - whole).abs() < 1e-5,
                "tiles of {tile}: {tiled} against {whole}"
            );
        }
        assert_eq!(flip_in_tiles(&reference, &reference, 40), 0.0);
    }
}
