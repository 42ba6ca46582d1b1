//! Tone mapping: how the linear colours of the film become the 8-bit sRGB of the screen and of
//! PNG and PPM files. An exposure in stops scales the linear values (each stop doubles them), a
//! [`ToneCurve`] brings them into [0, 1], and the one sRGB encoder ([`srgb8`]) makes bytes. The
//! default (exposure 0, [`ToneCurve::Clamp`]) is the plain encoding, bit for bit. The viewer
//! uploads its image through the same [`Tone`], so what it saves is what it shows.

use crate::color::{Color, SrgbEncoder, srgb8};
use rayon::prelude::*;
use strum::VariantNames;

/// Largest linear value a curve looks at: beyond it every curve is white anyway, and the filmic
/// curve's squares stay finite.
pub const CURVE_INPUT_MAX: f32 = 1e6;

/// How linear values (after exposure) are brought into [0, 1]. The command line and the viewer
/// name it in lower case: `clamp`, `reinhard`, `filmic`.
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase", parse_err_ty = String, parse_err_fn = unknown_curve)]
pub enum ToneCurve {
    /// Values above 1 become white: the image as traced.
    #[default]
    Clamp,
    /// Reinhard's `x / (1 + x)`: highlights are compressed smoothly and never quite reach white.
    Reinhard,
    /// Narkowicz's fit of the ACES filmic curve: a toe that deepens the shadows and a shoulder
    /// that rolls highlights off into white (from about x = 10).
    Filmic,
}

impl ToneCurve {
    /// The curve at linear value `x`, in [0, 1] (negative values and NaN give 0).
    pub fn apply(self, x: f32) -> f32 {
        // NaN counts as 0, as in `srgb8`.
        let x = if x.is_nan() {
            0.0
        } else {
            x.clamp(0.0, CURVE_INPUT_MAX)
        };
        match self {
            ToneCurve::Clamp => x.min(1.0),
            ToneCurve::Reinhard => x / (1.0 + x),
            ToneCurve::Filmic => {
                ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).min(1.0)
            }
        }
    }
}

/// Why `s` is no tone curve's name.
fn unknown_curve(s: &str) -> String {
    format!(
        "unknown tone curve `{s}` (use one of: {})",
        ToneCurve::VARIANTS.join(", ")
    )
}

/// Exposure and tone curve: the whole way from linear colour to display bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tone {
    /// Stops: each one doubles the linear values before the curve.
    pub exposure: f32,
    pub curve: ToneCurve,
}

impl Tone {
    /// Exposures the viewer and the command line take, in stops.
    pub const EXPOSURE_RANGE: std::ops::RangeInclusive<f32> = -16.0..=16.0;

    /// Checks the exposure; the error says what is wrong.
    pub fn new(exposure: f32, curve: ToneCurve) -> Result<Tone, String> {
        if !Tone::EXPOSURE_RANGE.contains(&exposure) {
            return Err(format!(
                "exposure must be from {} to {} stops, got {exposure}",
                Tone::EXPOSURE_RANGE.start(),
                Tone::EXPOSURE_RANGE.end()
            ));
        }
        Ok(Tone { exposure, curve })
    }

    /// What the linear values are multiplied by: 2 to the power of the exposure (exactly 1 at
    /// exposure 0).
    pub fn scale(self) -> f32 {
        self.exposure.exp2()
    }

    /// One linear channel as the byte shown.
    pub fn srgb8(self, v: f32) -> u8 {
        srgb8(self.curve.apply(v * self.scale()))
    }

    /// A linear colour as the display's sRGB bytes (red, green, blue).
    pub fn map(self, c: Color) -> [u8; 3] {
        let scale = self.scale();
        c.to_array().map(|v| srgb8(self.curve.apply(v * scale)))
    }

    /// The sRGB bytes of linear colours, three per colour.
    pub fn to_srgb8(self, pixels: &[Color]) -> Vec<u8> {
        // On all threads, in pieces, through the sRGB table: [`Self::map`]'s bytes without its
        // three `powf` a pixel, which add up to milliseconds for an image.
        const PIECE: usize = 4096;
        let (encoder, scale) = (SrgbEncoder::shared(), self.scale());
        let mut bytes = vec![0; pixels.len() * 3];
        let pieces = bytes
            .par_chunks_mut(3 * PIECE)
            .zip(pixels.par_chunks(PIECE));
        pieces.for_each(|(bytes, pixels)| {
            for (byte, &v) in bytes.iter_mut().zip(pixels.iter().flat_map(|c| c.as_ref())) {
                *byte = encoder.encode(self.curve.apply(v * scale));
            }
        });
        bytes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::color::to_srgb8;
    use strum::IntoEnumIterator;

    /// Linear values from 0 to 64, finely spaced at the dark end.
    fn sweep() -> impl Iterator<Item = f32> {
        std::iter::once(0.0).chain((0..4000).map(|i| 1e-6 * 1.005f32.powi(i)))
    }

    #[test]
    fn clamp_at_exposure_zero_is_the_plain_encoding_bit_for_bit() {
        let pixels: Vec<Color> = sweep()
            .chain([-1.0, f32::NAN, f32::INFINITY, 1.0, 250.0])
            .map(|v| Color::new(v, v * 0.5, v * 3.0))
            .collect();
        assert_eq!(Tone::default().to_srgb8(&pixels), to_srgb8(&pixels));
        assert_eq!(Tone::default().scale(), 1.0);
    }

    #[test]
    fn a_whole_image_gets_each_pixels_own_bytes() {
        // `to_srgb8` goes through the sRGB table, `map` through `powf`.
        let pixels: Vec<Color> = sweep()
            .chain([-1.0, f32::NAN, f32::INFINITY, 250.0])
            .map(|v| Color::new(v, v * 0.5, v * 3.0))
            .collect();
        for curve in ToneCurve::iter() {
            for exposure in [-2.0, 0.0, 0.5, 1.0, 3.0] {
                let tone = Tone::new(exposure, curve).unwrap();
                let one_by_one: Vec<u8> = pixels.iter().flat_map(|&c| tone.map(c)).collect();
                assert_eq!(tone.to_srgb8(&pixels), one_by_one, "{tone:?}");
            }
        }
    }

    #[test]
    fn one_stop_doubles_the_linear_values_before_the_curve() {
        for curve in ToneCurve::iter() {
            let one = Tone::new(1.0, curve).unwrap();
            let zero = Tone::new(0.0, curve).unwrap();
            assert_eq!(one.scale(), 2.0);
            for v in sweep() {
                assert_eq!(one.srgb8(v), zero.srgb8(2.0 * v), "{curve} at {v}");
            }
        }
        let dark = Tone::new(-2.0, ToneCurve::Clamp).unwrap();
        assert_eq!(dark.srgb8(1.0), srgb8(0.25));
    }

    #[test]
    fn curves_start_at_zero_rise_and_stay_in_the_unit_range() {
        for curve in ToneCurve::iter() {
            assert_eq!(curve.apply(0.0), 0.0, "{curve}");
            assert_eq!(curve.apply(-3.0), 0.0, "{curve}");
            let mut last = 0.0;
            for v in sweep().chain([1e5, 1e7, f32::MAX, f32::INFINITY]) {
                let y = curve.apply(v);
                assert!((0.0..=1.0).contains(&y), "{curve}({v}) = {y}");
                assert!(y >= last, "{curve} falls at {v}: {y} < {last}");
                last = y;
            }
        }
        // The curves do differ: Reinhard keeps highlights below white, filmic reaches it.
        assert!(ToneCurve::Reinhard.apply(8.0) < 0.9);
        assert_eq!(ToneCurve::Filmic.apply(20.0), 1.0);
        // Filmic's toe darkens the shadows, its shoulder lifts the middle.
        assert!(ToneCurve::Filmic.apply(0.05) < 0.05);
        assert!(ToneCurve::Filmic.apply(0.5) > 0.55);
    }

    #[test]
    fn curves_read_and_print_their_names() {
        for curve in ToneCurve::iter() {
            assert_eq!(curve.to_string().parse::<ToneCurve>(), Ok(curve));
        }
        assert_eq!(ToneCurve::VARIANTS, ["clamp", "reinhard", "filmic"]);
        assert_eq!(
            "aces".parse::<ToneCurve>(),
            Err("unknown tone curve `aces` (use one of: clamp, reinhard, filmic)".to_string())
        );
    }

    #[test]
    fn exposures_out_of_range_are_refused() {
        for bad in [f32::NAN, f32::INFINITY, 17.0, -100.0] {
            let err = Tone::new(bad, ToneCurve::Clamp).unwrap_err();
            assert!(err.contains("exposure"), "{err}");
        }
        assert!(Tone::new(-16.0, ToneCurve::Filmic).is_ok());
    }
}
