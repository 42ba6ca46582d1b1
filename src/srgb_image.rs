//! An image as 8-bit sRGB pixels ([`SrgbImage`]), the form textures are sampled from and images
//! are compared in. It decodes any image file raylab reads (PNG, PPM, BMP, JPEG, OpenEXR,
//! Radiance HDR): 8- and 16-bit images keep their values, scaled to 8 bits; the linear floats
//! of OpenEXR and Radiance HDR go through the sRGB curve, clamped to [0, 1] as raylab's own
//! 8-bit images are. An 8- or 16-bit image's alpha channel is kept, in 8 bits, where it is not
//! opaque everywhere (a texture's cut-outs: [`crate::material::Material::alpha_cutoff`]);
//! comparisons read the colours alone. An image's sides are held to
//! [`crate::limits::MAX_IMAGE_SIDE`] and its size checked against the memory available before
//! its pixels are decoded. An OpenEXR file's header is checked before its blocks
//! ([`small_exr_blocks`]), and its pixels are read by [`read_exr_rgb`], which holds no more
//! memory than the file holds pixels (an OpenEXR image is its data window: the pixels it has).

use std::io::{BufRead, BufReader, Cursor, Read, Seek};
use std::path::Path;

use exr::compression::Compression;
use exr::meta::attribute::LevelMode;
use exr::meta::{BlockDescription, MetaData};
use exr::prelude::{ReadChannels, ReadLayers, ReadSpecificChannel, Vec2, read};
use image::{DynamicImage, ImageDecoder, ImageReader};

use crate::color::{Color, srgb_to_linear, srgb8};
use crate::limits::check_image_size;

/// An image of 8-bit sRGB pixels, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct SrgbImage {
    pub width: u32,
    pub height: u32,
    /// `width × height` pixels, row by row.
    pub pixels: Vec<[u8; 3]>,
    /// The pixels' alpha (coverage, 255 opaque), row by row; empty where the image is opaque
    /// everywhere.
    pub alpha: Vec<u8>,
}

impl SrgbImage {
    /// The opaque image of `width × height` pixels, row by row.
    pub fn new(width: u32, height: u32, pixels: Vec<[u8; 3]>) -> SrgbImage {
        SrgbImage {
            width,
            height,
            pixels,
            alpha: Vec::new(),
        }
    }

    /// Decodes an image file's bytes, its format told by its first bytes. An image with no
    /// pixels, sides over [`crate::limits::MAX_IMAGE_SIDE`], or one that would not fit in
    /// memory ([`crate::memory::check`]) is refused before it is decoded.
    pub fn decode(bytes: &[u8]) -> Result<SrgbImage, String> {
        SrgbImage::decode_from(Cursor::new(bytes))
    }

    /// [`Self::decode`] of the image `reader` reads, which is read as far as it is needed: a
    /// file's bytes are not held beside its pixels.
    pub fn decode_from(mut reader: impl BufRead + Seek) -> Result<SrgbImage, String> {
        if is_exr(&mut reader)? {
            check_exr_header(&mut reader)?;
            reader.rewind().map_err(|e| e.to_string())?;
            let ((width, height), pixels) = read_exr_rgb(reader, |c| c.to_array().map(srgb8))?;
            return Ok(SrgbImage::new(width, height, pixels));
        }
        decode_with(guessed(reader)?)
    }

    /// The size of the image in the file at `path` and the memory decoding it takes at most
    /// beyond its 3 bytes a pixel (the decoder's own buffer), read from its header alone.
    pub fn probe(path: &Path) -> Result<((u32, u32), u64), String> {
        let named = |e: String| format!("{}: {e}", path.display());
        let (file, _) = crate::memory::open_file(path).map_err(named)?;
        let mut reader = BufReader::new(file);
        if is_exr(&mut reader).map_err(named)? {
            let size = check_exr_header(&mut reader).map_err(named)?;
            return Ok((size, 0));
        }
        let decoder = guessed(reader)
            .and_then(|reader| reader.into_decoder().map_err(|e| e.to_string()))
            .map_err(named)?;
        let (width, height) = decoder.dimensions();
        check_image_size(width, height).map_err(named)?;
        Ok(((width, height), decoder.total_bytes()))
    }

    /// Reads and decodes the image file at `path` (a regular file), as it is read: its bytes are
    /// not held beside its pixels. The error names the file.
    pub fn read(path: &Path) -> Result<SrgbImage, String> {
        let named = |e: String| format!("{}: {e}", path.display());
        let (file, _) = crate::memory::open_file(path).map_err(named)?;
        SrgbImage::decode_from(BufReader::new(file)).map_err(named)
    }

    /// The image of `width × height` linear colours, row by row, encoded as raylab writes
    /// 8-bit files.
    pub fn from_linear(width: u32, height: u32, colors: &[Color]) -> SrgbImage {
        let pixels = colors.iter().map(|c| c.to_array().map(srgb8)).collect();
        SrgbImage::new(width, height, pixels)
    }

    /// The linear colours of the pixels, row by row: [`Self::from_linear`] of them gives the
    /// same image back, byte for byte.
    pub fn to_linear(&self) -> Vec<Color> {
        self.pixels.iter().map(|p| linear(*p)).collect()
    }

    /// The linear colour of the pixel at column `x`, row `y`.
    pub fn linear_at(&self, x: u32, y: u32) -> Color {
        linear(self.at(x, y))
    }

    /// The pixel at column `x`, row `y` (row 0 at the top).
    pub fn at(&self, x: u32, y: u32) -> [u8; 3] {
        self.pixels[(y as usize) * self.width as usize + x as usize]
    }
}

/// The linear colour of a pixel's levels.
fn linear(levels: [u8; 3]) -> Color {
    Color::from(levels.map(|v| srgb_to_linear(f32::from(v) / 255.0)))
}

/// A reader of the image `reader` holds, its format told by its first bytes; the error says
/// which formats raylab reads.
fn guessed<R: BufRead + Seek>(reader: R) -> Result<ImageReader<R>, String> {
    let reader = ImageReader::new(reader)
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    match reader.format() {
        Some(_) => Ok(reader),
        None => {
            Err("not an image raylab reads (PNG, PPM, BMP, JPEG, OpenEXR or Radiance HDR)".into())
        }
    }
}

/// The first bytes of every OpenEXR file.
const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// Whether `reader` holds an OpenEXR file, told from its first bytes without consuming them.
fn is_exr(reader: &mut impl BufRead) -> Result<bool, String> {
    let start = reader.fill_buf().map_err(|e| e.to_string())?;
    Ok(start.starts_with(&EXR_MAGIC))
}

/// Decodes an image of any format but OpenEXR with the `image` crate: its size checked first.
fn decode_with(reader: ImageReader<impl BufRead + Seek>) -> Result<SrgbImage, String> {
    let decoder = reader.into_decoder().map_err(|e| e.to_string())?;
    let (width, height) = decoder.dimensions();
    check_image_size(width, height)?;
    let pixels = u64::from(width) * u64::from(height);
    let decoded = decoder.total_bytes();
    let bytes_per_pixel = if decoder.color_type().has_alpha() {
        4
    } else {
        3
    };
    crate::memory::check(
        &format!("the {width}×{height} image"),
        decoded + pixels * bytes_per_pixel,
    )?;
    let image = DynamicImage::from_decoder(decoder).map_err(|e| e.to_string())?;
    let alpha = alpha_channel(&image);
    let pixels = match image {
        DynamicImage::ImageRgb32F(_) | DynamicImage::ImageRgba32F(_) => image
            .into_rgb32f()
            .pixels()
            .map(|p| p.0.map(srgb8))
            .collect(),
        // The decoder's buffer is dropped pixel by pixel as ours fills.
        _ => image
            .into_rgb8()
            .into_raw()
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]])
            .collect(),
    };
    Ok(SrgbImage {
        width,
        height,
        pixels,
        alpha,
    })
}

/// The 8-bit alpha of a decoded image's pixels, row by row: empty where it has no alpha channel
/// or is opaque everywhere.
fn alpha_channel(image: &DynamicImage) -> Vec<u8> {
    let eight_bits = |a: u16| ((u32::from(a) + 128) / 257) as u8;
    let alpha: Vec<u8> = match image {
        DynamicImage::ImageLumaA8(b) => b.pixels().map(|p| p.0[1]).collect(),
        DynamicImage::ImageRgba8(b) => b.pixels().map(|p| p.0[3]).collect(),
        DynamicImage::ImageLumaA16(b) => b.pixels().map(|p| eight_bits(p.0[1])).collect(),
        DynamicImage::ImageRgba16(b) => b.pixels().map(|p| eight_bits(p.0[3])).collect(),
        _ => Vec::new(),
    };
    if alpha.iter().all(|&a| a == u8::MAX) {
        Vec::new()
    } else {
        alpha
    }
}

/// Reads the R, G and B channels of an OpenEXR file's first valid layer: its size (its data
/// window's) and its pixels, row by row, each linear colour made a `T` by `pixel` as it
/// arrives. A row is allocated when its first pixel arrives, so that a file claiming many
/// pixels it does not hold costs no more than it holds; a row it leaves out is an error. Check
/// the header first ([`small_exr_blocks`]).
pub fn read_exr_rgb<T: Copy + Default + 'static>(
    reader: impl BufRead + Seek,
    pixel: fn(Color) -> T,
) -> Result<((u32, u32), Vec<T>), String> {
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .specific_channels()
        .required("R")
        .required("G")
        .required("B")
        .collect_pixels(
            |size: Vec2<usize>, _| (size.x(), vec![Vec::new(); size.y()]),
            move |(width, rows): &mut (usize, Vec<Vec<T>>),
                  at: Vec2<usize>,
                  (r, g, b): (f32, f32, f32)| {
                let row = &mut rows[at.y()];
                if row.is_empty() {
                    *row = vec![T::default(); *width];
                }
                row[at.x()] = pixel(Color::new(r, g, b));
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(reader)
        .map_err(|e| format!("not a readable OpenEXR file with R, G and B: {e}"))?;
    let size = image.layer_data.size;
    let (width, height) = (size.x() as u32, size.y() as u32);
    check_image_size(width, height)?;
    let (_, rows) = image.layer_data.channel_data.pixels;
    let mut colors = Vec::with_capacity(size.area());
    for row in rows {
        if row.len() != size.x() {
            return Err("its pixels do not fill its data window".into());
        }
        colors.extend(row);
    }
    Ok(((width, height), colors))
}

/// The largest OpenEXR tile side raylab reads: a tile size in a header could ask the reader for
/// buffers of any size.
pub const MAX_EXR_TILE_SIDE: usize = 256;

/// Whether an OpenEXR layer's blocks are small: scan lines, or tiles of one resolution at most
/// [`MAX_EXR_TILE_SIDE`] pixels a side.
pub fn small_exr_blocks(blocks: BlockDescription) -> bool {
    match blocks {
        BlockDescription::ScanLines => true,
        BlockDescription::Tiles(tiles) => {
            tiles.level_mode == LevelMode::Singular
                && tiles.tile_size.x() <= MAX_EXR_TILE_SIDE
                && tiles.tile_size.y() <= MAX_EXR_TILE_SIDE
        }
    }
}

/// Refuses an OpenEXR file with a layer larger than raylab reads or than fits in memory, whose
/// blocks are not small ([`small_exr_blocks`]), with deep data, or with B44 compression (lossy,
/// seldom used, and its decompressor overflows on a crafted block:
/// fuzz/regressions/part/crash-2df55c…). Returns the first layer's size.
fn check_exr_header(reader: impl Read) -> Result<(u32, u32), String> {
    let meta = MetaData::read_from_buffered(reader, false)
        .map_err(|e| format!("not a readable OpenEXR file: {e}"))?;
    for header in &meta.headers {
        let size = header.layer_size;
        let (width, height) = (size.x() as u32, size.y() as u32);
        check_image_size(width, height)?;
        let pixels = size.area() as u64;
        crate::memory::check(&format!("the {width}×{height} image"), pixels * 3)?;
        if header.deep || !small_exr_blocks(header.blocks) {
            return Err(format!(
                "raylab reads flat OpenEXR images of one resolution, in scan lines or in tiles \
                 of at most {MAX_EXR_TILE_SIDE} pixels a side; this one is not"
            ));
        }
        if matches!(header.compression, Compression::B44 | Compression::B44A) {
            return Err(format!(
                "raylab does not read OpenEXR's {} compression",
                header.compression
            ));
        }
    }
    let first = meta
        .headers
        .first()
        .ok_or("an OpenEXR file with no layer")?;
    Ok((first.layer_size.x() as u32, first.layer_size.y() as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn encoded(image: impl Into<DynamicImage>, format: image::ImageFormat) -> Vec<u8> {
        let mut bytes = Vec::new();
        image
            .into()
            .write_to(&mut Cursor::new(&mut bytes), format)
            .unwrap();
        bytes
    }

    #[test]
    fn every_level_goes_to_linear_and_back_unchanged() {
        let levels = (0..=255u8).map(|v| [v, 255 - v, v / 2]).collect::<Vec<_>>();
        let image = SrgbImage::new(16, 16, levels);
        let back = SrgbImage::from_linear(16, 16, &image.to_linear());
        assert_eq!(back, image);
    }

    #[test]
    fn eight_bit_files_keep_their_values() {
        let rgb = image::RgbImage::from_pixel(3, 2, image::Rgb([200, 100, 50]));
        for format in [
            image::ImageFormat::Png,
            image::ImageFormat::Bmp,
            image::ImageFormat::Pnm,
        ] {
            let img = SrgbImage::decode(&encoded(rgb.clone(), format)).unwrap();
            assert_eq!((img.width, img.height), (3, 2), "{format:?}");
            assert_eq!(img.pixels, vec![[200, 100, 50]; 6], "{format:?}");
        }
    }

    #[test]
    fn an_alpha_channel_is_kept_in_eight_bits_unless_the_image_is_opaque() {
        let rgba =
            image::RgbaImage::from_fn(2, 1, |x, _| image::Rgba([10, 20, 30, [0, 200][x as usize]]));
        let img = SrgbImage::decode(&encoded(rgba, image::ImageFormat::Png)).unwrap();
        assert_eq!(img.pixels, vec![[10, 20, 30]; 2]);
        assert_eq!(img.alpha, vec![0, 200]);
        let grey =
            image::ImageBuffer::<image::LumaA<u16>, _>::from_pixel(1, 1, image::LumaA([0, 32896]));
        let img = SrgbImage::decode(&encoded(grey, image::ImageFormat::Png)).unwrap();
        assert_eq!(img.alpha, vec![128]);
        let opaque = image::RgbaImage::from_pixel(2, 2, image::Rgba([1, 2, 3, 255]));
        let img = SrgbImage::decode(&encoded(opaque, image::ImageFormat::Png)).unwrap();
        assert!(img.alpha.is_empty());
    }

    #[test]
    fn a_plain_ppm_with_a_small_maximum_is_scaled_to_eight_bits() {
        let img = SrgbImage::decode(b"P3\n2 1\n15\n15 0 5  0 15 0\n").unwrap();
        assert_eq!(img.pixels, vec![[255, 0, 85], [0, 255, 0]]);
    }

    #[test]
    fn sixteen_bit_files_are_scaled_to_eight_bits() {
        let rgb = image::ImageBuffer::<image::Rgb<u16>, _>::from_pixel(
            1,
            1,
            image::Rgb([65535, 0, 32896]),
        );
        let img = SrgbImage::decode(&encoded(rgb, image::ImageFormat::Png)).unwrap();
        assert_eq!(img.pixels, vec![[255, 0, 128]]);
    }

    #[test]
    fn float_files_go_through_the_srgb_curve_clamped() {
        // Linear 0.214 is sRGB 128; 2 is past white; a negative value is below black (the
        // Radiance format stores none, and writes 0).
        let rgb = image::Rgb32FImage::from_fn(3, 1, |x, _| {
            image::Rgb([[0.214, 0.214, 0.214], [2.0, 2.0, 2.0], [-1.0, 0.0, 0.0]][x as usize])
        });
        for format in [image::ImageFormat::OpenExr, image::ImageFormat::Hdr] {
            let img = SrgbImage::decode(&encoded(rgb.clone(), format)).unwrap();
            let [grey, white, black] = [0, 1, 2].map(|x| img.at(x, 0));
            assert!(
                grey.iter().all(|c| c.abs_diff(128) <= 1),
                "{format:?}: {grey:?}"
            );
            assert_eq!((white, black), ([255; 3], [0; 3]), "{format:?}");
        }
    }

    #[test]
    fn what_is_no_image_is_refused_with_the_formats_read() {
        let err = SrgbImage::decode(b"hello, world").unwrap_err();
        assert!(err.contains("PNG, PPM"), "{err}");
        let err = SrgbImage::decode(b"P6\n0 0\n255\n").unwrap_err();
        assert!(!err.is_empty());
    }

    #[test]
    fn from_linear_encodes_as_raylab_writes() {
        let img = SrgbImage::from_linear(2, 1, &[Color::new(0.5, 0.0, 1.0), Color::ONE]);
        assert_eq!(img.pixels, vec![[srgb8(0.5), 0, 255], [255; 3]]);
        assert_eq!(img.at(1, 0), [255; 3]);
    }
}
