//! Parts of an image rendered apart (tiles, crops): OpenEXR files that hold the linear film
//! values of a rectangle of the image, so that merging them gives exactly what one render of
//! the whole image writes, in any output format.
//!
//! A part is an ordinary OpenEXR image whose data window is its rectangle and whose display
//! window is the whole image (as renderers write crops; any EXR viewer shows it in place), with
//! one header attribute of raylab's own, `raylabPart`, a text of lines: `scene = ` the scene's
//! content hash ([`scene_hash`]), `tile = K/N` and `frame = F` when it is one, then `settings =`
//! and, on the lines after it, the settings that shape the pixels. (One attribute, not four:
//! the OpenEXR writer orders several as a hash map does, differently in each run, and a part
//! rendered again should be the same file.) The metadata
//! lives inside the file rather than in a sidecar: a part cannot lose it or be paired with
//! another part's, and it is written atomically with the pixels.

use std::collections::{BTreeMap, HashMap};
use std::fmt::{self, Write as _};
use std::hash::Hasher;
use std::io::{BufRead, BufReader, Cursor, Read, Seek};
use std::path::{Path, PathBuf};

use exr::compression::Compression;
use exr::meta::attribute::{AttributeValue, IntegerBounds, Text};
use exr::prelude::{
    Encoding, Image, ImageAttributes, Layer, LayerAttributes, SpecificChannels, Vec2, WritableImage,
};

use crate::color::Color;
use crate::limits::check_image_size;
use crate::memory;
use crate::output::write_atomically;
use crate::scene::Scene;
use crate::srgb_image::{MAX_EXR_TILE_SIDE, read_exr_rgb, small_exr_blocks};
use crate::tiles::Rect;

/// What a part says about itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PartInfo {
    /// The whole image's size.
    pub width: u32,
    pub height: u32,
    /// The pixels the part holds.
    pub rect: Rect,
    /// The scene's content hash ([`scene_hash`]).
    pub scene: String,
    /// The settings that shape the pixels, as text, one `name = value` a line.
    pub settings: String,
    /// Tile `K` of `N`, when the part is one.
    pub tile: Option<(u32, u32)>,
    /// The frame of a sequence it belongs to, when it does.
    pub frame: Option<u32>,
}

/// A part read back: what it says and its pixels (linear RGB, row by row over its rectangle).
#[derive(Clone, Debug)]
pub struct Part {
    pub info: PartInfo,
    pub pixels: Vec<Color>,
}

/// Why a part could not be written or read.
#[derive(Debug)]
pub struct PartError {
    pub path: PathBuf,
    pub message: String,
}

impl fmt::Display for PartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for PartError {}

/// The header attribute that makes an OpenEXR file a part.
const ATTRIBUTE: &str = "raylabPart";

/// A hash of everything in `scene` that shapes its pixels (its settings, camera, lights, fog,
/// materials, textures, background and geometry; not the names or warnings, which may hold
/// the path the file was read from), as 16 hex digits. The same on every machine for the same
/// scene file read by the same raylab: FNV-1a over the values as `{:?}` prints them (floats
/// exactly, in their shortest round-tripping form).
pub fn scene_hash(scene: &Scene) -> String {
    /// Feeds formatted text into a hasher without keeping it.
    struct HashWriter(fnv::FnvHasher);
    impl fmt::Write for HashWriter {
        fn write_str(&mut self, s: &str) -> fmt::Result {
            self.0.write(s.as_bytes());
            Ok(())
        }
    }
    let mut h = HashWriter(fnv::FnvHasher::default());
    let _ = write!(
        h,
        "{:?}{:?}{:?}{:?}{:?}{:?}{:?}{:?}",
        scene.settings,
        scene.camera,
        scene.lights,
        scene.atmosphere,
        scene.materials,
        scene.textures,
        scene.background_image,
        scene.geometry
    );
    format!("{:016x}", h.0.finish())
}

/// Writes the part `info` describes, with its `pixels` (row by row over `info.rect`),
/// atomically: a task run again replaces its part whole.
pub fn write_part(path: &Path, info: &PartInfo, pixels: &[Color]) -> Result<(), PartError> {
    let error = |message: String| PartError {
        path: path.into(),
        message,
    };
    let rect = info.rect;
    if pixels.len() as u64 != rect.pixels() {
        return Err(error(format!(
            "the part needs {} pixels, got {}",
            rect.pixels(),
            pixels.len()
        )));
    }
    let mut text = format!("scene = {}\n", info.scene);
    if let Some((k, n)) = info.tile {
        text += &format!("tile = {k}/{n}\n");
    }
    if let Some(frame) = info.frame {
        text += &format!("frame = {frame}\n");
    }
    text += &format!("settings =\n{}", info.settings);
    let text = Text::new_or_none(&text)
        .ok_or_else(|| error(format!("cannot store {text:?} in an OpenEXR header")))?;
    let other = HashMap::from([(Text::from(ATTRIBUTE), AttributeValue::Text(text))]);
    let width = rect.width() as usize;
    let channels = SpecificChannels::rgb(|at: Vec2<usize>| {
        let c = pixels[at.y() * width + at.x()];
        (c.x, c.y, c.z)
    });
    // In the layer's attributes, where the reader puts attributes it does not know.
    let attributes = LayerAttributes {
        layer_position: Vec2(rect.x0 as i32, rect.y0 as i32),
        other,
        ..LayerAttributes::default()
    };
    let layer = Layer::new(
        (width, rect.height() as usize),
        attributes,
        Encoding::FAST_LOSSLESS,
        channels,
    );
    let mut image = Image::from_layer(layer);
    image.attributes.display_window =
        IntegerBounds::new((0, 0), (info.width as usize, info.height as usize));
    write_atomically(
        path,
        |e| error(e.to_string()),
        |out| {
            image
                .write()
                .to_buffered(out)
                .map_err(|e| error(e.to_string()))
        },
    )
}

/// What the part at `path` says about itself, reading only its header.
pub fn read_part_info(path: &Path) -> Result<PartInfo, PartError> {
    let error = |message: String| PartError {
        path: path.into(),
        message,
    };
    let (file, _) = crate::memory::open_file(path).map_err(error)?;
    read_header(BufReader::new(file)).map_err(error)
}

/// Reads the part at `path`: what it says and its pixels.
pub fn read_part(path: &Path) -> Result<Part, PartError> {
    let (file, _) = crate::memory::open_file(path).map_err(|message| PartError {
        path: path.into(),
        message,
    })?;
    read_part_from(BufReader::new(file), path)
}

/// Reads the part held in `bytes` as [`read_part`] reads a file; `origin` names it in errors.
pub fn read_part_bytes(bytes: &[u8], origin: &Path) -> Result<Part, PartError> {
    read_part_from(Cursor::new(bytes), origin)
}

/// Reads a part from `reader`: first its header, which must describe a part of an image that
/// raylab renders and fit in memory, and only then its pixels.
fn read_part_from(mut reader: impl BufRead + Seek, origin: &Path) -> Result<Part, PartError> {
    let error = |message: String| PartError {
        path: origin.into(),
        message,
    };
    let info = read_header(&mut reader).map_err(error)?;
    let rect = info.rect;
    memory::check(
        &format!(
            "reading the {}×{} pixels of a part",
            rect.width(),
            rect.height()
        ),
        rect.pixels() * std::mem::size_of::<Color>() as u64,
    )
    .map_err(error)?;
    reader.rewind().map_err(|e| error(e.to_string()))?;
    let (_, pixels) = read_exr_rgb(reader, |c| c).map_err(error)?;
    Ok(Part { info, pixels })
}

/// Reads a part's header from `reader`: what the part says about itself.
fn read_header(reader: impl Read) -> Result<PartInfo, String> {
    let meta = exr::meta::MetaData::read_from_buffered(reader, false)
        .map_err(|e| format!("not a readable OpenEXR file: {e}"))?;
    let [header] = meta.headers.as_slice() else {
        return Err("a raylab part has one layer".into());
    };
    let position = header.own_attributes.layer_position;
    let size = header.layer_size;
    let info = part_info(
        &header.shared_attributes,
        &header.own_attributes,
        (position.x(), position.y()),
        (size.x(), size.y()),
    )?;
    // Stored much as `write_part` stores parts (tiles of 64 × 64), so that the OpenEXR reader's
    // buffers for a block stay small: a tile size or a channel list in a header could ask for
    // any size.
    if header.deep || !small_exr_blocks(header.blocks) {
        return Err(format!(
            "a raylab part is a flat image of one resolution, in scan lines or in tiles of at \
             most {MAX_EXR_TILE_SIDE} pixels a side; this one is not"
        ));
    }
    // Nor is any other decompressor run on a part: OpenEXR's others are lossy or seldom used,
    // and its B44 one overflows on a crafted block (fuzz/regressions/part/crash-2df55c…).
    if !matches!(
        header.compression,
        Compression::RLE | Compression::Uncompressed
    ) {
        return Err(format!(
            "a raylab part is stored with rle compression or none; this one has {}",
            header.compression
        ));
    }
    let channels: Vec<String> = header
        .channels
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    let full = header
        .channels
        .list
        .iter()
        .all(|c| c.sampling == Vec2(1, 1));
    if channels != ["B", "G", "R"] || !full {
        return Err(format!(
            "a raylab part has the channels B, G and R, each at every pixel; this one has {}",
            channels.join(", ")
        ));
    }
    Ok(info)
}

/// The part's description from its header: the image's and the layer's attributes, and where
/// its pixels lie.
fn part_info(
    attributes: &ImageAttributes,
    layer: &LayerAttributes,
    position: (i32, i32),
    size: (usize, usize),
) -> Result<PartInfo, String> {
    let Some(AttributeValue::Text(text)) = layer.other.get(&Text::from(ATTRIBUTE)) else {
        return Err(format!("not a raylab part (no {ATTRIBUTE} in its header)"));
    };
    let text = text.to_string();
    let bad = || format!("{ATTRIBUTE} is not what raylab writes: {text:?}");
    let (head, settings) = text.split_once("settings =\n").ok_or_else(bad)?;
    let mut fields = BTreeMap::new();
    for line in head.lines() {
        let (name, value) = line.split_once(" = ").ok_or_else(bad)?;
        fields.insert(name, value);
    }
    let scene = fields.get("scene").ok_or_else(bad)?.to_string();
    let display = attributes.display_window;
    let (Ok(width), Ok(height)) = (
        u32::try_from(display.size.x()),
        u32::try_from(display.size.y()),
    ) else {
        return Err("its display window is larger than any image".into());
    };
    // Before anything is made of the sizes, so that no part asks for more than a render would.
    check_image_size(width, height).map_err(|e| format!("its display window: {e}"))?;
    let to_u32 = |v: i64| u32::try_from(v).ok();
    let rect = (|| {
        if display.position != Vec2(0, 0) {
            return None;
        }
        let x0 = to_u32(position.0.into())?;
        let y0 = to_u32(position.1.into())?;
        let rect = Rect {
            x0,
            y0,
            x1: x0.checked_add(to_u32(size.0 as i64)?)?,
            y1: y0.checked_add(to_u32(size.1 as i64)?)?,
        };
        rect.is_inside(&Rect::image(width, height)).then_some(rect)
    })()
    .ok_or("its data window does not lie inside a display window at (0, 0)")?;
    let tile = match fields.get("tile") {
        None => None,
        Some(t) => Some(
            t.split_once('/')
                .and_then(|(k, n)| Some((k.parse().ok()?, n.parse().ok()?)))
                .ok_or_else(bad)?,
        ),
    };
    let frame = match fields.get("frame") {
        None => None,
        Some(f) => Some(f.parse().map_err(|_| bad())?),
    };
    Ok(PartInfo {
        width,
        height,
        rect,
        scene,
        settings: settings.to_string(),
        tile,
        frame,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_part_reads_back_bit_for_bit() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("part.exr");
        let info = PartInfo {
            width: 9,
            height: 7,
            rect: Rect {
                x0: 2,
                y0: 3,
                x1: 6,
                y1: 5,
            },
            scene: "0123456789abcdef".into(),
            settings: "samples = 4\nview = shaded".into(),
            tile: Some((1, 3)),
            frame: Some(12),
        };
        // Values no 16-bit float or 8-bit encoding keeps.
        let pixels: Vec<Color> = (0..8)
            .map(|i| Color::new(0.1 + i as f32 * 1e-7, 1234.567, -0.0))
            .collect();
        write_part(&path, &info, &pixels).unwrap();
        assert_eq!(read_part_info(&path).unwrap(), info);
        let part = read_part(&path).unwrap();
        assert_eq!(part.info, info);
        let bits = |p: &[Color]| -> Vec<[u32; 3]> {
            p.iter().map(|c| c.to_array().map(f32::to_bits)).collect()
        };
        assert_eq!(bits(&part.pixels), bits(&pixels));
    }

    /// A part of a 4 × 3 image: its whole, as a file in `dir`.
    fn small_part(dir: &Path) -> PathBuf {
        let path = dir.join("small.exr");
        let info = PartInfo {
            width: 4,
            height: 3,
            rect: Rect::image(4, 3),
            scene: "0123456789abcdef".into(),
            settings: "samples = 1".into(),
            tile: Some((0, 1)),
            frame: None,
        };
        write_part(&path, &info, &[Color::ONE; 12]).unwrap();
        path
    }

    /// `bytes` of an OpenEXR file with its box attribute `name` (`dataWindow`,
    /// `displayWindow`) set to `[x_min, y_min, x_max, y_max]`, as a crafted file would have it.
    fn with_box(bytes: &[u8], name: &str, bounds: [i32; 4]) -> Vec<u8> {
        let key = format!("{name}\0box2i\0");
        let at = bytes
            .windows(key.len())
            .position(|w| w == key.as_bytes())
            .unwrap_or_else(|| panic!("no {name} in the header"));
        let mut bytes = bytes.to_vec();
        let values = at + key.len() + 4; // after the attribute's size, 16
        for (i, v) in bounds.iter().enumerate() {
            bytes[values + 4 * i..values + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
        }
        bytes
    }

    #[test]
    fn a_part_of_an_image_larger_than_raylab_renders_is_refused_before_its_pixels() {
        let dir = tempfile::tempdir().unwrap();
        let bytes = std::fs::read(small_part(dir.path())).unwrap();
        let huge = [0, 0, 999_999, 999_999];
        let whole = with_box(&with_box(&bytes, "displayWindow", huge), "dataWindow", huge);
        let corner = with_box(&bytes, "displayWindow", huge);
        for (name, bytes) in [("whole.exr", whole), ("corner.exr", corner)] {
            let path = dir.path().join(name);
            std::fs::write(&path, bytes).unwrap();
            let expected = "image sides must be at most 16384, got 1000000×1000000";
            let err = read_part_info(&path).unwrap_err().to_string();
            assert!(err.contains(expected), "{err}");
            let err = read_part(&path).unwrap_err().to_string();
            assert!(err.contains(expected), "{err}");
        }
    }

    #[test]
    fn a_part_with_other_channels_is_refused_before_its_pixels() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rgba.exr");
        let text = "scene = 0123456789abcdef\nsettings =\nsamples = 1";
        let attribute = AttributeValue::Text(Text::from(text));
        let attributes = LayerAttributes {
            other: HashMap::from([(Text::from(ATTRIBUTE), attribute)]),
            ..LayerAttributes::default()
        };
        let channels = SpecificChannels::rgba(|_| (1.0f32, 1.0f32, 1.0f32, 1.0f32));
        let layer = Layer::new((4, 3), attributes, Encoding::FAST_LOSSLESS, channels);
        Image::from_layer(layer).write().to_file(&path).unwrap();
        let err = read_part(&path).unwrap_err().to_string();
        assert!(err.contains("has the channels B, G and R"), "{err}");
        assert!(err.ends_with("this one has A, B, G, R"), "{err}");
    }

    #[test]
    fn an_image_that_is_not_a_part_is_an_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plain.exr");
        crate::formats::image::save_image(&path, 2, 2, &[Color::ONE; 4]).unwrap();
        let err = read_part(&path).unwrap_err().to_string();
        assert!(err.contains("not a raylab part"), "{err}");
        std::fs::write(&path, b"garbage").unwrap();
        let err = read_part_info(&path).unwrap_err().to_string();
        assert!(err.contains("not a readable OpenEXR file"), "{err}");
    }
}
