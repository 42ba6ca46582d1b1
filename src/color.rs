//! Colour: linear RGB ([`Color`], what the tracer adds and multiplies) and the sRGB transfer
//! function between it and the 8-bit sRGB of textures, image files and the screen. Every 8-bit
//! sRGB value raylab writes (PNG and PPM files, legends, the viewer's texture and swatches)
//! comes from the one encoder, [`srgb8`].

use glam::Vec3;

/// Linear RGB.
pub type Color = Vec3;

/// The sRGB transfer function, inverted.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// The sRGB transfer function, for writing 8-bit images.
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.0031308 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// One linear channel as an 8-bit sRGB value (clamped to [0, 1] first; NaN gives 0).
pub fn srgb8(v: f32) -> u8 {
    (linear_to_srgb(v) * 255.0).round() as u8
}

/// The 8-bit sRGB bytes of linear colours, three per colour (red, green, blue).
pub fn to_srgb8(pixels: &[Color]) -> Vec<u8> {
    pixels
        .iter()
        .flat_map(|c| c.to_array().map(srgb8))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trip() {
        for i in 0..=20 {
            let c = i as f32 / 20.0;
            assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-5);
        }
    }

    #[test]
    fn the_encoder_clamps_and_rounds() {
        assert_eq!(to_srgb8(&[Color::new(-1.0, 0.5, 2.0)]), [0, 188, 255]);
        assert_eq!(srgb8(f32::NAN), 0);
        assert_eq!(srgb8(srgb_to_linear(128.0 / 255.0)), 128);
    }
}
