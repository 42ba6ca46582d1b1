//! The textures on the GPU: one record per scene texture (its kind and numbers), the background
//! image's record after them, and one buffer of texels that holds the sRGB decode table and then
//! every image's texels. The WGSL that reads them is `shaders/texture.wgsl`, the twin of
//! [`Texture::color`], with `shaders/noise.wgsl`, the twin of [`crate::noise`].

use super::record::gpu_record;
use bytemuck::Zeroable;
use glam::Vec2;

use crate::color::Color;
use crate::scene::Scene;
use crate::srgb_image::SrgbImage;
use crate::texture::{SRGB8_TO_LINEAR, Texture, TextureKind, Wrap};

/// Where [`GpuTexture::wrap`] keeps the wrap along v.
pub const WRAP_V_SHIFT: u32 = 8;

/// A material's [`super::materials::GpuMaterial::texture`] or the frame's background image when
/// there is none.
pub const NO_TEXTURE: u32 = u32::MAX;

gpu_record! {
    /// WGSL's `Texture`: a texture's kind ([`TextureKind`]) and the numbers that kind reads.
    pub struct GpuTexture {
        /// The first colour; Marble's colour.
        pub a: [f32; 3],
        pub kind: u32,
        /// The second colour.
        pub b: [f32; 3],
        /// Checker3d's cube side.
        pub size: f32,
        /// An image's scale; CheckerUv's squares across and up (`u_count`, `v_count`).
        pub scale: [f32; 2],
        /// An image's offset.
        pub offset: [f32; 2],
        /// Where an image's texels start in the texel buffer, one u32 each
        /// (`r | g << 8 | b << 16 | alpha << 24`).
        pub first: u32,
        pub width: u32,
        pub height: u32,
        /// The [`Wrap`] along u, and along v shifted left by [`WRAP_V_SHIFT`].
        pub wrap: u32,
    }
}

/// The textures of a scene as the GPU reads them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TextureRecords {
    /// The scene's textures in their order, then the background image's.
    pub textures: Vec<GpuTexture>,
    /// The bits of [`SRGB8_TO_LINEAR`]'s 256 floats, then every image's texels, row by row.
    pub texels: Vec<u32>,
}

impl TextureRecords {
    /// The records of `scene`'s textures and background image; the error says that the texels
    /// are too many for the WGSL's u32 indices.
    pub fn new(scene: &Scene) -> Result<TextureRecords, String> {
        let mut records = TextureRecords {
            textures: Vec::with_capacity(scene.textures.len() + 1),
            texels: SRGB8_TO_LINEAR.iter().map(|c| c.to_bits()).collect(),
        };
        for texture in &scene.textures {
            let record = records.record(texture);
            records.textures.push(record);
        }
        if let Some(image) = &scene.background_image {
            let record = records.image(image, [Wrap::Clamp; 2], Vec2::ONE, Vec2::ZERO);
            records.textures.push(record);
        }
        let count = records.texels.len();
        if u32::try_from(count).is_err() {
            return Err(format!(
                "the images have {count} texels; the GPU tracer indexes at most {}",
                u32::MAX
            ));
        }
        Ok(records)
    }

    /// The record of `texture`, its texels appended if it is an image.
    fn record(&mut self, texture: &Texture) -> GpuTexture {
        let colors = |kind: TextureKind, a: &Color, b: &Color| GpuTexture {
            a: a.to_array(),
            kind: kind as u32,
            b: b.to_array(),
            ..GpuTexture::zeroed()
        };
        match texture {
            Texture::Checker3d { a, b, size } => GpuTexture {
                size: *size,
                ..colors(TextureKind::Checker3d, a, b)
            },
            Texture::CheckerUv {
                a,
                b,
                u_count,
                v_count,
            } => GpuTexture {
                scale: [*u_count, *v_count],
                ..colors(TextureKind::CheckerUv, a, b)
            },
            Texture::Wood { a, b } => colors(TextureKind::Wood, a, b),
            Texture::Marble { color } => colors(TextureKind::Marble, color, &Color::ZERO),
            Texture::Image {
                image,
                wrap,
                scale,
                offset,
            } => self.image(image, *wrap, *scale, *offset),
        }
    }

    /// The record of `image` seen at `uv · scale + offset`, its texels appended.
    fn image(
        &mut self,
        image: &SrgbImage,
        wrap: [Wrap; 2],
        scale: Vec2,
        offset: Vec2,
    ) -> GpuTexture {
        let first = self.texels.len() as u32;
        let alpha = |i: usize| image.alpha.get(i).copied().unwrap_or(u8::MAX);
        self.texels
            .extend(image.pixels.iter().enumerate().map(|(i, &[r, g, b])| {
                u32::from(r) | u32::from(g) << 8 | u32::from(b) << 16 | u32::from(alpha(i)) << 24
            }));
        GpuTexture {
            kind: TextureKind::Image as u32,
            scale: scale.to_array(),
            offset: offset.to_array(),
            first,
            width: image.width,
            height: image.height,
            wrap: wrap[0] as u32 | (wrap[1] as u32) << WRAP_V_SHIFT,
            ..GpuTexture::zeroed()
        }
    }
}

/// The texture record of `scene`'s background image ([`NO_TEXTURE`]: it has none), the one
/// after the scene's textures.
pub fn background_record(scene: &Scene) -> u32 {
    match scene.background_image {
        Some(_) => scene.textures.len() as u32,
        None => NO_TEXTURE,
    }
}
