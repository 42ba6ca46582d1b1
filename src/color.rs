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

/// Where [`srgb8`] steps up: entry `k` is the least linear value whose byte is `k + 1`, so a
/// value's byte is the number of entries at or below it. The viewer's shader encodes with this
/// table, exactly as [`srgb8`] does, without its own `pow`.
pub fn srgb8_steps() -> [f32; 255] {
    std::array::from_fn(|k| {
        let byte = k as u8 + 1;
        // Bit patterns of non-negative floats are ordered like the floats, and srgb8 rises.
        let (mut lo, mut hi) = (0u32, 1f32.to_bits());
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if srgb8(f32::from_bits(mid)) >= byte {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        f32::from_bits(lo)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counting_the_steps_below_a_value_gives_its_byte() {
        let steps = srgb8_steps();
        let by_steps = |v: f32| steps.iter().filter(|&&s| s <= v).count() as u8;
        let mut v = 1e-7f32;
        while v < 1.5 {
            assert_eq!(by_steps(v), srgb8(v), "{v}");
            v *= 1.0007;
        }
        for (k, &step) in steps.iter().enumerate() {
            let below = f32::from_bits(step.to_bits() - 1);
            assert_eq!(srgb8(step), k as u8 + 1);
            assert_eq!(srgb8(below), k as u8, "the step is the least such value");
        }
        for v in [-1.0, 0.0, f32::INFINITY, 1.0] {
            assert_eq!(by_steps(v), srgb8(v), "{v}");
        }
    }

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
