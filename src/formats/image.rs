//! Writing the rendered image: PNG and PPM (8-bit sRGB) and OpenEXR and Radiance HDR (linear
//! floats), chosen by the file's extension ([`save_image`]); 8-bit images can be shown through
//! an exposure and tone curve ([`save_toned_image`]). A path can be checked before long
//! work ([`check_image_path`]). The file is written safely, as [`crate::output`] writes every
//! file: atomically, through a symbolic link, never over a read-only file.

use std::path::{Path, PathBuf};

use image::codecs::pnm::{PnmEncoder, PnmSubtype, SampleEncoding};
use image::{DynamicImage, ImageFormat, Rgb32FImage, RgbImage};

use crate::color::Color;
use crate::output::{check_writable, write_atomically};
use crate::tone::Tone;

/// The image formats raylab writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    Png,
    Ppm,
    Exr,
    Hdr,
}

impl OutputFormat {
    pub const EXTENSIONS: &'static str = "png, ppm, exr, hdr";

    /// Memory that saving an image of `pixels` pixels takes, at most: the linear pixels handed
    /// to [`save_image`], the encoder's input and what the encoder keeps while it writes.
    pub fn save_bytes(self, pixels: u64) -> u64 {
        let per_pixel = match self {
            OutputFormat::Png | OutputFormat::Ppm => 12 + 3 + 3,
            OutputFormat::Exr | OutputFormat::Hdr => 12 + 12 + 12,
        };
        pixels * per_pixel
    }

    /// The format a file name's extension asks for.
    pub fn from_path(path: &Path) -> Option<OutputFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(OutputFormat::Png),
            "ppm" => Some(OutputFormat::Ppm),
            "exr" => Some(OutputFormat::Exr),
            "hdr" => Some(OutputFormat::Hdr),
            _ => None,
        }
    }
}

/// Why an image could not be written.
#[derive(Debug)]
pub enum OutputError {
    UnknownFormat(PathBuf),
    Io(PathBuf, std::io::Error),
    Encode(PathBuf, image::ImageError),
    /// The pixel buffer does not hold `width × height` pixels.
    PixelCount {
        expected: usize,
        got: usize,
    },
}

impl std::fmt::Display for OutputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OutputError::UnknownFormat(p) => write!(
                f,
                "{}: unknown image format (use one of: {})",
                p.display(),
                OutputFormat::EXTENSIONS
            ),
            OutputError::Io(p, e) => write!(f, "{}: {e}", p.display()),
            OutputError::Encode(p, e) => write!(f, "{}: {e}", p.display()),
            OutputError::PixelCount { expected, got } => {
                write!(f, "image needs {expected} pixels, got {got}")
            }
        }
    }
}

impl std::error::Error for OutputError {}

/// Checks, before the long work that makes it, that an image can be saved at `path`: its
/// extension names a format raylab writes, and [`check_writable`] passes.
pub fn check_image_path(path: &Path) -> Result<OutputFormat, OutputError> {
    let format =
        OutputFormat::from_path(path).ok_or_else(|| OutputError::UnknownFormat(path.into()))?;
    check_writable(path).map_err(|e| OutputError::Io(path.into(), e))?;
    Ok(format)
}

/// Writes `pixels` (linear RGB, row 0 at the top) to `path` in the format its extension names.
pub fn save_image(
    path: &Path,
    width: u32,
    height: u32,
    pixels: &[Color],
) -> Result<(), OutputError> {
    save_toned_image(path, width, height, pixels, Tone::default())
}

/// As [`save_image`], with 8-bit formats (PNG, PPM) shown through `tone`; OpenEXR and Radiance
/// HDR keep the linear values as they are.
pub fn save_toned_image(
    path: &Path,
    width: u32,
    height: u32,
    pixels: &[Color],
    tone: Tone,
) -> Result<(), OutputError> {
    let format = check_image_path(path)?;
    let expected = width as usize * height as usize;
    if pixels.len() != expected {
        return Err(OutputError::PixelCount {
            expected,
            got: pixels.len(),
        });
    }
    let io = |e| OutputError::Io(path.into(), e);
    let encode = |e| OutputError::Encode(path.into(), e);
    write_atomically(path, io, |out| {
        match format {
            OutputFormat::Png | OutputFormat::Ppm => {
                let srgb = RgbImage::from_raw(width, height, tone.to_srgb8(pixels)).ok_or(
                    OutputError::PixelCount {
                        expected,
                        got: pixels.len(),
                    },
                )?;
                if format == OutputFormat::Png {
                    srgb.write_to(out, ImageFormat::Png).map_err(encode)?;
                } else {
                    let encoder = PnmEncoder::new(out)
                        .with_subtype(PnmSubtype::Pixmap(SampleEncoding::Binary));
                    srgb.write_with_encoder(encoder).map_err(encode)?;
                }
            }
            OutputFormat::Exr | OutputFormat::Hdr => {
                let floats: Vec<f32> = pixels.iter().flat_map(|c| c.to_array()).collect();
                let linear = Rgb32FImage::from_raw(width, height, floats).ok_or(
                    OutputError::PixelCount {
                        expected,
                        got: pixels.len(),
                    },
                )?;
                let image_format = if format == OutputFormat::Exr {
                    ImageFormat::OpenExr
                } else {
                    ImageFormat::Hdr
                };
                DynamicImage::ImageRgb32F(linear)
                    .write_to(out, image_format)
                    .map_err(encode)?;
            }
        }
        Ok(())
    })
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::linear_to_srgb;

    fn gradient(w: u32, h: u32) -> Vec<Color> {
        (0..w * h)
            .map(|i| Color::new((i % w) as f32 / w as f32, (i / w) as f32 / h as f32, 0.5))
            .collect()
    }

    #[test]
    fn every_format_round_trips() {
        let dir = tempfile::tempdir().unwrap();
        let pixels = gradient(7, 5);
        for ext in ["png", "ppm", "exr", "hdr"] {
            let path = dir.path().join(format!("out.{ext}"));
            save_image(&path, 7, 5, &pixels).unwrap();
            let back = image::open(&path).unwrap().to_rgb32f();
            assert_eq!((back.width(), back.height()), (7, 5), "{ext}");
            let back: Vec<f32> = back.into_raw();
            let linear = matches!(ext, "exr" | "hdr");
            for (i, c) in pixels.iter().enumerate() {
                for ch in 0..3 {
                    let expected = if linear { c[ch] } else { linear_to_srgb(c[ch]) };
                    let got = back[i * 3 + ch];
                    assert!(
                        (got - expected).abs() < 0.02,
                        "{ext} pixel {i}: {got} vs {expected}"
                    );
                }
            }
        }
        let leftovers = std::fs::read_dir(dir.path())
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .ends_with(".tmp")
            })
            .count();
        assert_eq!(leftovers, 0, "no temporary files left behind");
    }

    #[test]
    fn ppm_is_binary_p6() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.ppm");
        save_image(&path, 2, 1, &[Color::ONE, Color::ZERO]).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(b"P6"));
        assert!(bytes.ends_with(&[255, 255, 255, 0, 0, 0]));
    }

    #[test]
    fn unknown_extensions_and_missing_folders_are_errors() {
        let err = save_image(Path::new("out.gif"), 1, 1, &[Color::ONE]).unwrap_err();
        assert!(err.to_string().contains("unknown image format"), "{err}");
        let err = save_image(Path::new("/no/such/dir/out.png"), 1, 1, &[Color::ONE]).unwrap_err();
        assert!(matches!(err, OutputError::Io(..)), "{err}");
    }

    #[test]
    fn a_failed_write_keeps_the_old_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("keep.png");
        std::fs::write(&path, b"old").unwrap();
        // Too few pixels cannot be encoded; the old file must survive.
        let err = save_image(&path, 4, 4, &[Color::ONE]).unwrap_err();
        assert!(matches!(
            err,
            OutputError::PixelCount {
                expected: 16,
                got: 1
            }
        ));
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
    }

    #[test]
    fn image_paths_are_checked_before_any_work() {
        let dir = tempfile::tempdir().unwrap();
        let err = check_image_path(&dir.path().join("x.gif")).unwrap_err();
        assert!(matches!(err, OutputError::UnknownFormat(_)), "{err}");
        let err = check_image_path(&dir.path().join("no/x.png")).unwrap_err();
        assert!(err.to_string().contains("does not exist"), "{err}");
        assert_eq!(
            check_image_path(&dir.path().join("x.EXR")).unwrap(),
            OutputFormat::Exr
        );
    }
}
