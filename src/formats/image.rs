//! Writing the rendered image: PNG and PPM (8-bit sRGB) and OpenEXR and Radiance HDR (linear
//! floats), chosen by the file's extension ([`save_image`]); 8-bit images can be shown through
//! an exposure and tone curve ([`save_toned_image`]). A path can be checked before long
//! work ([`check_image_path`]). The file is written safely, as [`crate::output`] writes every
//! file: atomically, through a symbolic link, never over a read-only file.
//!
//! Every format is written a band of rows at a time from a function that gives each pixel's
//! colour ([`save_toned_pixels`]), so saving a film needs no copy of it: the memory it takes
//! is a band's, whatever the image's size.

use std::io::Write;
use std::path::{Path, PathBuf};

use exr::prelude::{
    Encoding, Image, Layer, LayerAttributes, SpecificChannels, Vec2, WritableImage,
};
use rayon::prelude::*;

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

/// About how many pixels a band of rows holds while it is encoded.
const BAND_PIXELS: usize = 1 << 18;
/// What an encoder keeps whatever the image's size (a compressor's window and tables).
const ENCODER_BYTES: u64 = 1 << 20;

impl OutputFormat {
    pub const EXTENSIONS: &'static str = "png, ppm, exr, hdr";

    /// Memory that saving an image `width` pixels wide takes, at most: a band of rows as
    /// linear colours and as the bytes the encoder is handed, and the encoder's own buffers
    /// (OpenEXR compresses blocks of 16 rows, with a few of them in flight).
    pub fn save_bytes(self, width: u32) -> u64 {
        let band = BAND_PIXELS.max(width as usize) as u64;
        let row = u64::from(width);
        ENCODER_BYTES
            + match self {
                OutputFormat::Png | OutputFormat::Ppm => band * (12 + 3) + row * 8,
                OutputFormat::Hdr => band * 12 + row * 8,
                OutputFormat::Exr => row * 16 * 12 * 8,
            }
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
    Encode(PathBuf, String),
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
    let expected = width as usize * height as usize;
    if pixels.len() != expected {
        check_image_path(path)?;
        return Err(OutputError::PixelCount {
            expected,
            got: pixels.len(),
        });
    }
    let pixel = |x: u32, y: u32| pixels[y as usize * width as usize + x as usize];
    save_toned_pixels(path, width, height, &pixel, tone)
}

/// The linear colour of an image's pixel `(x, y)`, row 0 at the top, asked for from any thread.
pub type PixelAt<'a> = &'a (dyn Fn(u32, u32) -> Color + Sync);

/// As [`save_toned_image`], the colours given by `pixel` a band of rows at a time, so that no
/// copy of the whole image is made.
pub fn save_toned_pixels(
    path: &Path,
    width: u32,
    height: u32,
    pixel: PixelAt,
    tone: Tone,
) -> Result<(), OutputError> {
    let format = check_image_path(path)?;
    let io = |e| OutputError::Io(path.into(), e);
    let encode = |e: String| OutputError::Encode(path.into(), e);
    let bands = Bands::new(width, height, pixel);
    write_atomically(path, io, |out| match format {
        OutputFormat::Png => write_png(out, &bands, tone).map_err(|e| encode(e.to_string())),
        OutputFormat::Ppm => write_ppm(out, &bands, tone).map_err(io),
        OutputFormat::Exr => write_exr(out, &bands).map_err(|e| encode(e.to_string())),
        OutputFormat::Hdr => write_hdr(out, &bands).map_err(io),
    })
}

/// An image's rows in bands of about [`BAND_PIXELS`] pixels, each computed on all threads.
struct Bands<'a> {
    width: u32,
    height: u32,
    rows: u32,
    pixel: PixelAt<'a>,
}

impl<'a> Bands<'a> {
    fn new(width: u32, height: u32, pixel: PixelAt<'a>) -> Self {
        let rows = (BAND_PIXELS / width.max(1) as usize).clamp(1, height.max(1) as usize);
        Bands {
            width,
            height,
            rows: rows as u32,
            pixel,
        }
    }

    /// Calls `write` with each band's colours, row by row, top to bottom.
    fn each<E>(&self, mut write: impl FnMut(&[Color]) -> Result<(), E>) -> Result<(), E> {
        let width = self.width.max(1);
        let mut band = Vec::new();
        for top in (0..self.height).step_by(self.rows as usize) {
            let bottom = (top + self.rows).min(self.height);
            (top * width..bottom * width)
                .into_par_iter()
                .map(|i| (self.pixel)(i % width, i / width))
                .collect_into_vec(&mut band);
            write(&band)?;
        }
        Ok(())
    }
}

/// PNG, 8-bit RGB, compressed as the `image` crate's fast setting does: fdeflate's fast DEFLATE
/// (`png::Compression::Fast`) after the adaptive filter, which picks each row's best of the five
/// PNG filters.
fn write_png(out: &mut impl Write, bands: &Bands, tone: Tone) -> Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(out, bands.width, bands.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_filter(png::Filter::Adaptive);
    let mut writer = encoder.write_header()?;
    let mut stream = writer.stream_writer()?;
    bands.each(|band| stream.write_all(&tone.to_srgb8(band)))?;
    stream.finish()?;
    writer.finish()
}

/// Binary PPM (P6).
fn write_ppm(out: &mut impl Write, bands: &Bands, tone: Tone) -> std::io::Result<()> {
    write!(out, "P6\n{} {}\n255\n", bands.width, bands.height)?;
    bands.each(|band| out.write_all(&tone.to_srgb8(band)))
}

/// OpenEXR, losslessly compressed; the encoder asks for the pixels block by block.
fn write_exr(
    out: &mut (impl Write + std::io::Seek),
    bands: &Bands,
) -> Result<(), exr::error::Error> {
    let pixel = bands.pixel;
    let channels = SpecificChannels::rgb(|at: Vec2<usize>| {
        let c = pixel(at.x() as u32, at.y() as u32);
        (c.x, c.y, c.z)
    });
    let size = (bands.width as usize, bands.height as usize);
    let layer = Layer::new(
        size,
        LayerAttributes::default(),
        Encoding::FAST_LOSSLESS,
        channels,
    );
    Image::from_layer(layer).write().to_buffered(out)
}

/// Radiance HDR: RGBE pixels, each scanline run-length encoded channel by channel (runs are not
/// looked for: every byte goes out as part of a literal run), or flat where the format has no
/// run-length encoding (scanlines under 8 or over 32,767 pixels wide).
fn write_hdr(out: &mut impl Write, bands: &Bands) -> std::io::Result<()> {
    let width = bands.width as usize;
    write!(
        out,
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {} +X {}\n",
        bands.height, bands.width
    )?;
    let encoded = (8..=32_767).contains(&width);
    let mut channels = vec![0u8; 4 * width];
    bands.each(|band| {
        for row in band.chunks(width) {
            if !encoded {
                for &c in row {
                    out.write_all(&rgbe(c))?;
                }
                continue;
            }
            for (x, &c) in row.iter().enumerate() {
                for (channel, byte) in rgbe(c).into_iter().enumerate() {
                    channels[channel * width + x] = byte;
                }
            }
            out.write_all(&[2, 2, (width >> 8) as u8, width as u8])?;
            for channel in channels.chunks(width) {
                for literal in channel.chunks(128) {
                    out.write_all(&[literal.len() as u8])?;
                    out.write_all(literal)?;
                }
            }
        }
        Ok(())
    })
}

/// A linear colour as Radiance's shared-exponent bytes: three mantissas and the exponent of the
/// brightest channel, offset by 128 (black for anything under 10⁻³²).
fn rgbe(c: Color) -> [u8; 4] {
    let c = c.max(Color::ZERO);
    let brightest = c.max_element();
    if !brightest.is_finite() || brightest < 1e-32 {
        return [0; 4];
    }
    // brightest = m · 2^e with m in [0.5, 1).
    let e = brightest.log2().floor() as i32 + 1;
    let scale = 256.0 / 2f32.powi(e);
    let m = (c * scale).to_array().map(|v| (v as u32).min(255) as u8);
    [m[0], m[1], m[2], (e + 128).clamp(0, 255) as u8]
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
    fn images_taller_than_a_band_are_written_band_by_band_exactly() {
        let dir = tempfile::tempdir().unwrap();
        // Wide enough for run-length encoded HDR scanlines, tall enough for several bands;
        // and narrow, for flat HDR scanlines.
        for (w, h) in [(1000, 700), (5, 3)] {
            let pixels = gradient(w, h);
            assert!(w < 8 || Bands::new(w, h, &|_, _| Color::ZERO).rows < h);
            for ext in ["png", "ppm", "exr", "hdr"] {
                let path = dir.path().join(format!("big.{ext}"));
                save_image(&path, w, h, &pixels).unwrap();
                let back = image::open(&path).unwrap().to_rgb32f();
                assert_eq!((back.width(), back.height()), (w, h), "{ext}");
                for (i, (c, got)) in pixels.iter().zip(back.pixels()).enumerate() {
                    for ch in 0..3 {
                        let (got, want) = (got[ch], c[ch]);
                        let close = match ext {
                            "exr" => got == want,
                            // Eight bits of mantissa for the brightest channel.
                            "hdr" => (got - want).abs() <= c.max_element() / 128.0,
                            _ => (got * 255.0).round() == (linear_to_srgb(want) * 255.0).round(),
                        };
                        assert!(close, "{ext} {w}×{h} pixel {i}: {got} vs {want}");
                    }
                }
            }
        }
    }

    #[test]
    fn rgbe_keeps_the_brightest_channels_exponent() {
        assert_eq!(rgbe(Color::ZERO), [0; 4]);
        assert_eq!(rgbe(Color::new(1.0, 0.5, 0.0)), [128, 64, 0, 129]);
        assert_eq!(rgbe(Color::new(0.75, 0.0, 3.0)), [48, 0, 192, 130]);
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
