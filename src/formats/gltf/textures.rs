//! A glTF material's base colour and emissive textures as raylab's image textures: the image
//! (PNG or JPEG, in a buffer view, a `data:` URI or a file beside the model, sRGB) with its
//! sampler's wrap along u and v. What raylab's image texture cannot say is moved into each primitive's mesh when it
//! is read ([`UvMap`]): the texture coordinate set and `KHR_texture_transform` become the
//! mesh's texture coordinates, and the base colour factor, which multiplies the texture,
//! becomes its vertex colours (raylab multiplies a texture by them).

use std::borrow::Cow;
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

use glam::{Mat2, Vec2};
use gltf::texture::WrappingMode;

use super::buffers::read_uri;
use crate::color::Color;
use crate::formats::SceneFiles;
use crate::srgb_image::SrgbImage;
use crate::texture::{Texture, Wrap};

/// How a primitive in a textured material reads its texture coordinates and colours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvMap {
    /// The texture coordinate set (`TEXCOORD_n`).
    pub set: u32,
    /// `KHR_texture_transform`: offset, rotation (radians) and scale, applied in glTF's texture
    /// space as `offset + rotate(scale · uv)`.
    pub offset: Vec2,
    pub rotation: f32,
    pub scale: Vec2,
    /// The base colour factor, multiplied into the vertex colours.
    pub tint: Color,
}

impl UvMap {
    /// The texture coordinates `uv` (glTF's, from the image's top left) map to.
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        self.offset + Mat2::from_angle(self.rotation) * (self.scale * uv)
    }
}

/// The textures of a file's materials, one per image and sampler in use: base colour and
/// emissive textures.
#[derive(Default)]
pub struct MaterialTextures {
    pub textures: Vec<Texture>,
    /// For each material: its base colour texture's index in `textures`.
    pub base: Vec<Option<u32>>,
    /// For each material: its emissive texture's index in `textures`.
    pub emissive: Vec<Option<u32>>,
    /// For each material with a texture: how its primitives read their texture coordinates
    /// and colours. The base colour texture's, else the emissive texture's: raylab's meshes
    /// hold one set of texture coordinates, which both textures read.
    pub maps: Vec<Option<UvMap>>,
}

/// The base colour and emissive textures of `document`'s materials, each image decoded once
/// however many materials use it. Images are in `buffers` (a buffer view) or beside the model
/// in `folder`.
pub fn material_textures(
    document: &gltf::Document,
    buffers: &[Cow<[u8]>],
    folder: &Path,
    files: SceneFiles,
) -> Result<MaterialTextures, String> {
    let mut result = MaterialTextures::default();
    let mut images: HashMap<usize, Arc<SrgbImage>> = HashMap::new();
    let mut records: HashMap<(usize, [Wrap; 2]), u32> = HashMap::new();
    // The texture record of `info`'s image and sampler, made the first time it is asked for.
    let mut record = |info: &gltf::texture::Info, result: &mut MaterialTextures| {
        let texture = info.texture();
        let image_index = texture.source().index();
        let sampler = texture.sampler();
        let wrap = [wrap(sampler.wrap_s()), wrap(sampler.wrap_t())];
        if let Some(&index) = records.get(&(image_index, wrap)) {
            return Ok(index);
        }
        let image = match images.get(&image_index) {
            Some(image) => Arc::clone(image),
            None => {
                let image = Arc::new(
                    decode_image(document, image_index, buffers, folder, files)
                        .map_err(|e| format!("image {image_index}: {e}"))?,
                );
                images.insert(image_index, Arc::clone(&image));
                image
            }
        };
        result.textures.push(Texture::Image {
            image,
            wrap,
            scale: Vec2::ONE,
            offset: Vec2::ZERO,
        });
        let index = result.textures.len() as u32 - 1;
        records.insert((image_index, wrap), index);
        Ok::<u32, String>(index)
    };
    for material in document.materials() {
        let pbr = material.pbr_metallic_roughness();
        let base = pbr.base_color_texture();
        let emissive = material.emissive_texture();
        let base_index = base
            .as_ref()
            .map(|info| record(info, &mut result))
            .transpose()?;
        let emissive_index = (emissive.as_ref())
            .map(|info| record(info, &mut result))
            .transpose()?;
        // The base colour factor multiplies the base colour texture only: with none, it stays
        // the material's colour.
        let [r, g, b, _] = pbr.base_color_factor();
        let map = match (&base, &emissive) {
            (Some(info), _) => Some(uv_map(info, Color::new(r, g, b))),
            (None, Some(info)) => Some(uv_map(info, Color::ONE)),
            (None, None) => None,
        };
        result.base.push(base_index);
        result.emissive.push(emissive_index);
        result.maps.push(map);
    }
    Ok(result)
}

/// How a primitive reads the texture `info` names: its coordinate set and
/// `KHR_texture_transform`, with `tint` for its vertex colours.
fn uv_map(info: &gltf::texture::Info, tint: Color) -> UvMap {
    let transform = info.texture_transform();
    let finite = |v: [f32; 2], default: Vec2| {
        let v = Vec2::from(v);
        if v.is_finite() { v } else { default }
    };
    UvMap {
        set: transform
            .as_ref()
            .and_then(|t| t.tex_coord())
            .unwrap_or(info.tex_coord()),
        offset: transform
            .as_ref()
            .map_or(Vec2::ZERO, |t| finite(t.offset(), Vec2::ZERO)),
        rotation: transform
            .as_ref()
            .map_or(0.0, |t| t.rotation())
            .clamp(-1e6, 1e6),
        scale: transform
            .as_ref()
            .map_or(Vec2::ONE, |t| finite(t.scale(), Vec2::ONE)),
        tint: tint.clamp(Color::ZERO, Color::ONE),
    }
}

/// raylab's wrap for a glTF sampler's.
fn wrap(mode: WrappingMode) -> Wrap {
    match mode {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
    }
}

/// The pixels of image `index`: from its buffer view (whose range is checked) or its URI.
fn decode_image(
    document: &gltf::Document,
    index: usize,
    buffers: &[Cow<[u8]>],
    folder: &Path,
    files: SceneFiles,
) -> Result<SrgbImage, String> {
    let json = &document.as_json().images[index];
    let bytes: Cow<[u8]> = match (&json.buffer_view, &json.uri) {
        (Some(view), _) => {
            let view = &document.as_json().buffer_views[view.value()];
            let buffer = buffers
                .get(view.buffer.value())
                .ok_or("its buffer view's buffer is missing")?;
            let start = view.byte_offset.map_or(0, |o| o.0 as usize);
            let end = start.checked_add(view.byte_length.0 as usize);
            Cow::Borrowed(
                end.and_then(|end| buffer.get(start..end))
                    .ok_or("its buffer view reaches past its buffer")?,
            )
        }
        (None, Some(uri)) => read_uri(uri, folder, files)?,
        (None, None) => return Err("it has neither a buffer view nor a URI".to_string()),
    };
    SrgbImage::decode(&bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_texture_transform_scales_then_rotates_counter_clockwise_then_offsets() {
        let map = UvMap {
            set: 0,
            offset: Vec2::new(0.5, 0.25),
            rotation: std::f32::consts::FRAC_PI_2,
            scale: Vec2::new(2.0, 3.0),
            tint: Color::ONE,
        };
        // (1, 0) → scaled (2, 0) → turned (0, 2) → offset (0.5, 2.25).
        assert!(map.apply(Vec2::X).abs_diff_eq(Vec2::new(0.5, 2.25), 1e-6));
        // (0, 1) → (0, 3) → (−3, 0) → (−2.5, 0.25).
        assert!(map.apply(Vec2::Y).abs_diff_eq(Vec2::new(-2.5, 0.25), 1e-6));
    }
}
