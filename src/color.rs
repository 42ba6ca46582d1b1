//! Colour: linear RGB ([`Color`], what the tracer adds and multiplies) and the sRGB transfer
//! function between it and the 8-bit sRGB of textures, image files and the screen. Every 8-bit
//! sRGB value raylab writes (PNG and PPM files, legends, the viewer's texture and swatches)
//! comes from the one encoder, [`srgb8`], directly or through its exact table
//! ([`SrgbEncoder`]) for whole images.

use std::sync::LazyLock;

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

/// Bucket of a linear value in [0, 1): its bit pattern without the lowest bits. Each bucket is
/// 1/128 of an octave wide, narrower than the gap between two byte thresholds, so it holds at
/// most one of them.
pub const BUCKET_SHIFT: u32 = 16;

/// [`srgb8`] by table, for whole images: for each bucket of linear values, the byte of its
/// lowest value and the value (if any) from which the byte is one more. It gives exactly
/// [`srgb8`]'s byte for every value, without a `powf`.
pub struct SrgbEncoder {
    buckets: Vec<(u8, f32)>,
}

impl SrgbEncoder {
    /// The table, made on first use (a third of a millisecond) and shared.
    pub fn shared() -> &'static SrgbEncoder {
        static SHARED: LazyLock<SrgbEncoder> = LazyLock::new(SrgbEncoder::new);
        &SHARED
    }

    fn new() -> SrgbEncoder {
        let buckets = (0..1f32.to_bits() >> BUCKET_SHIFT)
            .map(|k| {
                let (lo, hi) = (k << BUCKET_SHIFT, ((k + 1) << BUCKET_SHIFT) - 1);
                let base = srgb8(f32::from_bits(lo));
                if srgb8(f32::from_bits(hi)) == base {
                    return (base, f32::INFINITY);
                }
                // Bit patterns of non-negative floats are ordered like the floats.
                let (mut lo, mut hi) = (lo, hi);
                while lo < hi {
                    let mid = lo + (hi - lo) / 2;
                    if srgb8(f32::from_bits(mid)) > base {
                        hi = mid;
                    } else {
                        lo = mid + 1;
                    }
                }
                (base, f32::from_bits(lo))
            })
            .collect();
        SrgbEncoder { buckets }
    }

    /// The table: for each bucket of linear values in [0, 1) (the bits of a value shifted right
    /// by [`BUCKET_SHIFT`]), the byte of its lowest value and the value (infinity: none) from
    /// which the byte is one more.
    pub fn buckets(&self) -> &[(u8, f32)] {
        &self.buckets
    }

    /// [`srgb8`] of `v`.
    #[inline]
    pub fn encode(&self, v: f32) -> u8 {
        if v.is_nan() || v <= 0.0 {
            // Zero, negative or NaN, as `srgb8` clamps them.
            return 0;
        }
        if v >= 1.0 {
            return 255;
        }
        let (base, step) = self.buckets[(v.to_bits() >> BUCKET_SHIFT) as usize];
        base + u8::from(v >= step)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_encodes_exactly_like_srgb8() {
        let encoder = SrgbEncoder::shared();
        let steps: Vec<f32> = encoder
            .buckets
            .iter()
            .map(|b| b.1)
            .filter(|s| s.is_finite())
            .collect();
        assert_eq!(steps.len(), 255, "every byte boundary is in the table once");
        // Away from the steps both give the bucket's byte; around each step, every float for
        // thousands of ulps either side is compared, so a `powf` that wobbled there (it is
        // within an ulp) would show.
        for step in steps {
            let bits = step.to_bits();
            for b in bits - 4096..bits + 4096 {
                let v = f32::from_bits(b);
                assert_eq!(encoder.encode(v), srgb8(v), "{v}");
            }
        }
        let mut v = 1e-7f32;
        while v < 1.5 {
            assert_eq!(encoder.encode(v), srgb8(v), "{v}");
            v *= 1.0007;
        }
        for v in [
            -1.0,
            0.0,
            f32::NAN,
            f32::INFINITY,
            1.0,
            f32::MIN_POSITIVE,
            1e-30,
        ] {
            assert_eq!(encoder.encode(v), srgb8(v), "{v}");
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
