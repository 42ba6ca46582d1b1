//! Textures: colours that vary over a surface. Solid textures carved out of the object's space
//! (so they follow the object): a 3D checkerboard and Hill & Kelley's wood grain and marble;
//! checkerboards in texture coordinates; and images ([`SrgbImage`]s, any file raylab reads)
//! sampled with bilinear filtering. Images keep their 8-bit sRGB texels, three bytes each, and
//! turn them into linear colours as they are sampled.

use std::sync::{Arc, LazyLock};

use glam::{Vec2, Vec3};

use crate::color::{Color, srgb_to_linear};
use crate::noise::turbulence;
use crate::srgb_image::SrgbImage;

/// What happens to texture coordinates outside [0, 1], along one axis of an image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, strum::EnumIter)]
pub enum Wrap {
    Repeat,
    Clamp,
    /// Repeat, every other copy mirrored (glTF's MIRRORED_REPEAT).
    Mirror,
}

impl Wrap {
    /// Texel `i` of a row or column of `n` texels, wrapped into `0..n`.
    pub fn texel(self, i: i64, n: i64) -> i64 {
        match self {
            Wrap::Repeat => i.rem_euclid(n),
            Wrap::Clamp => i.clamp(0, n - 1),
            Wrap::Mirror => {
                let m = i.rem_euclid(2 * n);
                if m < n { m } else { 2 * n - 1 - m }
            }
        }
    }
}

/// A texture: a colour for each point of a surface.
#[derive(Clone, Debug, PartialEq, strum::EnumDiscriminants)]
#[strum_discriminants(
    name(TextureKind),
    doc = "The kinds of texture, one per variant of `Texture`.",
    derive(Hash, strum::EnumIter)
)]
pub enum Texture {
    /// Cubes of side `size` in object space, alternating `a` and `b`.
    Checker3d { a: Color, b: Color, size: f32 },
    /// `u_count × v_count` squares over the unit square of texture space.
    CheckerUv {
        a: Color,
        b: Color,
        u_count: f32,
        v_count: f32,
    },
    /// Hill & Kelley's wood grain: rings around the object's z axis, [`WOOD_RING_WIDTH`] apart,
    /// wobbling with the angle around the axis and with z; alternately `a` and `b`.
    Wood { a: Color, b: Color },
    /// Hill & Kelley's marble: veins across z, stirred by turbulence; `color` darkened in the
    /// veins (by [`marble_spline`]).
    Marble { color: Color },
    /// An image at texture coordinates `uv · scale + offset` (so repeated `scale` times over
    /// the unit square of texture space), wrapped along u and v by `wrap`.
    Image {
        image: Arc<SrgbImage>,
        wrap: [Wrap; 2],
        scale: Vec2,
        offset: Vec2,
    },
}

/// The book's wood: the two colours its rings alternate in, whatever the diffuse colour.
pub const WOOD_COLORS: (Color, Color) = (Color::new(0.6, 0.5, 0.2), Color::new(1.0, 0.62, 0.26));
/// How far apart the wood's rings are, in object units.
pub const WOOD_RING_WIDTH: f32 = 0.12;
/// How far the rings wobble, in rings; how many wobbles go round the axis; how fast they turn
/// with z (the book's `K`, `1/N` and `B`).
pub const WOOD_WOBBLE: (f32, f32, f32) = (0.6, 5.0, 1.8);
/// The frequency of the marble's turbulence, and how strongly it stirs the veins.
pub const MARBLE_TURBULENCE: (f32, f32) = (1.5, 5.0);

impl Texture {
    /// The colour at texture coordinates `uv`, or at `object_point` for solid textures.
    pub fn color(&self, uv: Vec2, object_point: Vec3) -> Color {
        match self {
            Texture::Checker3d { a, b, size } => {
                // The small bias keeps a surface lying on a cell boundary (a floor at y = 0)
                // from flickering between two cells with rounding noise.
                let cell = (object_point / *size + 1e-4).floor();
                let parity = (cell.x + cell.y + cell.z) as i64;
                if parity.rem_euclid(2) == 0 { *a } else { *b }
            }
            Texture::CheckerUv {
                a,
                b,
                u_count,
                v_count,
            } => {
                let parity = (uv.x * u_count).floor() as i64 + (uv.y * v_count).floor() as i64;
                if parity.rem_euclid(2) == 0 { *a } else { *b }
            }
            Texture::Wood { a, b } => {
                let (amplitude, wobbles, twist) = WOOD_WOBBLE;
                let angle = object_point.y.atan2(object_point.x);
                let radius = object_point.truncate().length() / WOOD_RING_WIDTH;
                let ring = radius + amplitude * (angle * wobbles + twist * object_point.z).sin();
                if (ring.floor() as i64).rem_euclid(2) == 0 {
                    *a
                } else {
                    *b
                }
            }
            Texture::Marble { color } => {
                let (frequency, strength) = MARBLE_TURBULENCE;
                let stir = strength * turbulence(frequency, object_point);
                let vein = (std::f32::consts::TAU * object_point.z + stir).sin();
                *color * marble_spline(vein)
            }
            Texture::Image {
                image,
                wrap,
                scale,
                offset,
            } => image.sample(uv * *scale + *offset, *wrap),
        }
    }

    /// The alpha (the share of the surface that is there, 1 all of it) at texture coordinates
    /// `uv`: an image's alpha channel, sampled as its colours are; 1 for every other texture.
    pub fn alpha(&self, uv: Vec2) -> f32 {
        match self {
            Texture::Image {
                image,
                wrap,
                scale,
                offset,
            } => image.sample_alpha(uv * *scale + *offset, *wrap),
            _ => 1.0,
        }
    }
}

/// The book's marble profile: how bright the stone is at `x = sin(…)` in [−1, 1]: dark veins
/// (0.15) around x = −0.75, pale stone (0.95) around 0, a second shade (0.26) around 0.7.
pub fn marble_spline(x: f32) -> f32 {
    if x < -0.4 {
        0.15 + 2.857 * (x + 0.75).powi(2)
    } else if x < 0.4 {
        0.95 - 2.8125 * x * x
    } else {
        0.26 + 2.666 * (x - 0.7).powi(2)
    }
}

impl SrgbImage {
    /// Bilinear sample at `uv` of the value `texel` gives for each texel (by its index), blended
    /// by `lerp`; `v = 0` is the bottom of the image, and the texels are wrapped into the image
    /// along x by `wrap[0]` and along y by `wrap[1]`. Texel coordinates are held within ±2^40
    /// (far past where single precision tells texels apart), so that a model's absurd texture
    /// coordinates (infinite, not a number) wrap or clamp like any others.
    fn bilinear<T>(
        &self,
        uv: Vec2,
        wrap: [Wrap; 2],
        texel: impl Fn(usize) -> T,
        lerp: impl Fn(T, T, f32) -> T,
    ) -> T {
        const REACH: f32 = (1u64 << 40) as f32;
        // Not a number reads as the image's corner.
        let held = |t: f32| {
            if t.is_nan() {
                0.0
            } else {
                t.clamp(-REACH, REACH)
            }
        };
        let (w, h) = (self.width as i64, self.height as i64);
        let at = |x: i64, y: i64| {
            let (x, y) = (wrap[0].texel(x, w), wrap[1].texel(y, h));
            texel((y * w + x) as usize)
        };
        let x = held(uv.x * self.width as f32 - 0.5);
        let y = held((1.0 - uv.y) * self.height as f32 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let top = lerp(at(x0, y0), at(x0 + 1, y0), fx);
        let bottom = lerp(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx);
        lerp(top, bottom, fy)
    }

    /// Bilinear sample of the linear colours at `uv` (`v = 0` is the bottom of the image),
    /// wrapped along x by `wrap[0]` and along y by `wrap[1]`. Texel coordinates are held within
    /// ±2^40, so that a model's absurd texture coordinates (infinite, not a number) wrap or clamp
    /// like any others.
    pub fn sample(&self, uv: Vec2, wrap: [Wrap; 2]) -> Color {
        let linear = &*SRGB8_TO_LINEAR;
        let texel = |i: usize| Color::from_array(self.pixels[i].map(|c| linear[c as usize]));
        self.bilinear(uv, wrap, texel, Color::lerp)
    }

    /// Bilinear sample of the alpha at `uv` (in [0, 1]; 1 where the image has no alpha), as
    /// [`Self::sample`] samples the colours.
    pub fn sample_alpha(&self, uv: Vec2, wrap: [Wrap; 2]) -> f32 {
        if self.alpha.is_empty() {
            return 1.0;
        }
        let texel = |i: usize| f32::from(self.alpha[i]) / 255.0;
        self.bilinear(uv, wrap, texel, |a: f32, b, s| a * (1.0 - s) + b * s)
    }
}

/// [`srgb_to_linear`] of each 8-bit value `c / 255`: how texels decode.
pub static SRGB8_TO_LINEAR: LazyLock<[f32; 256]> =
    LazyLock::new(|| std::array::from_fn(|c| srgb_to_linear(c as f32 / 255.0)));

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn absurd_texture_coordinates_sample_within_the_images_colours() {
        let image = two_by_two();
        let texels = image.to_linear();
        let lowest = texels.iter().copied().reduce(Color::min).unwrap();
        let highest = texels.iter().copied().reduce(Color::max).unwrap();
        for uv in [
            Vec2::new(f32::MAX, -f32::MAX),
            Vec2::new(-1e30, 1e30),
            Vec2::new(f32::INFINITY, f32::NEG_INFINITY),
            Vec2::splat(f32::NAN),
        ] {
            for wrap in [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror] {
                let c = image.sample(uv, [wrap; 2]);
                let within = c.cmpge(lowest - 1e-6).all() && c.cmple(highest + 1e-6).all();
                assert!(within, "{uv} {wrap:?}: {c}");
            }
        }
    }

    fn two_by_two() -> SrgbImage {
        SrgbImage::new(
            2,
            2,
            vec![[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 255]],
        )
    }

    #[test]
    fn texel_centres_sample_exactly() {
        let img = two_by_two();
        // Top-left texel centre is (0.25, 0.75) in uv (v up).
        assert_eq!(
            img.sample(Vec2::new(0.25, 0.75), [Wrap::Clamp; 2]),
            Color::X
        );
        assert_eq!(
            img.sample(Vec2::new(0.75, 0.25), [Wrap::Clamp; 2]),
            Color::ONE
        );
    }

    #[test]
    fn bilinear_blends_between_texels() {
        let img = two_by_two();
        let mid = img.sample(Vec2::new(0.5, 0.75), [Wrap::Clamp; 2]);
        assert!((mid - Color::new(0.5, 0.5, 0.0)).length() < 1e-6, "{mid}");
    }

    #[test]
    fn alpha_is_sampled_as_the_colours_are_and_is_one_without_an_alpha_channel() {
        let mut img = two_by_two();
        let texture = |image: &SrgbImage| Texture::Image {
            image: Arc::new(image.clone()),
            wrap: [Wrap::Clamp; 2],
            scale: Vec2::ONE,
            offset: Vec2::ZERO,
        };
        assert_eq!(texture(&img).alpha(Vec2::splat(0.3)), 1.0);
        img.alpha = vec![0, 255, 51, 255];
        let t = texture(&img);
        assert_eq!(t.alpha(Vec2::new(0.25, 0.75)), 0.0);
        assert_eq!(t.alpha(Vec2::new(0.75, 0.75)), 1.0);
        assert_eq!(t.alpha(Vec2::new(0.25, 0.25)), 0.2);
        assert!((t.alpha(Vec2::new(0.5, 0.75)) - 0.5).abs() < 1e-6);
        let wood = Texture::Wood {
            a: Color::ZERO,
            b: Color::ONE,
        };
        assert_eq!(wood.alpha(Vec2::ZERO), 1.0);
    }

    #[test]
    fn repeat_and_clamp_differ_outside_the_unit_square() {
        let img = two_by_two();
        let uv = Vec2::new(1.25, 0.75);
        assert_eq!(img.sample(uv, [Wrap::Repeat; 2]), Color::X);
        assert_eq!(img.sample(uv, [Wrap::Clamp; 2]), Color::Y);
    }

    #[test]
    fn mirror_reflects_every_other_copy_and_each_axis_wraps_on_its_own() {
        for n in [1, 2, 5] {
            let wrapped: Vec<i64> = (-2 * n..3 * n).map(|i| Wrap::Mirror.texel(i, n)).collect();
            // …, n−1 … 0 | 0 … n−1 | n−1 … 0 | 0 …: each copy mirrors its neighbours.
            for (k, &t) in wrapped.iter().enumerate() {
                let i = k as i64 - 2 * n;
                let copy = i.div_euclid(n);
                let within = i.rem_euclid(n);
                let expected = if copy % 2 == 0 {
                    within
                } else {
                    n - 1 - within
                };
                assert_eq!(t, expected, "texel {i} of {n}");
            }
        }
        let img = two_by_two();
        let uv = Vec2::new(1.25, 0.75);
        assert_eq!(img.sample(uv, [Wrap::Mirror, Wrap::Clamp]), Color::Y);
        assert_eq!(img.sample(uv, [Wrap::Repeat, Wrap::Clamp]), Color::X);
    }

    #[test]
    fn checkerboards_alternate() {
        let t = Texture::Checker3d {
            a: Color::ZERO,
            b: Color::ONE,
            size: 1.0,
        };
        assert_eq!(t.color(Vec2::ZERO, Vec3::new(0.5, 0.5, 0.5)), Color::ZERO);
        assert_eq!(t.color(Vec2::ZERO, Vec3::new(1.5, 0.5, 0.5)), Color::ONE);
        assert_eq!(t.color(Vec2::ZERO, Vec3::new(-0.5, 0.5, 0.5)), Color::ONE);
        let t = Texture::CheckerUv {
            a: Color::ZERO,
            b: Color::ONE,
            u_count: 4.0,
            v_count: 4.0,
        };
        assert_eq!(t.color(Vec2::new(0.1, 0.1), Vec3::ZERO), Color::ZERO);
        assert_eq!(t.color(Vec2::new(0.3, 0.1), Vec3::ZERO), Color::ONE);
    }

    #[test]
    fn texels_decode_to_the_linear_value_of_their_srgb_byte() {
        let img = SrgbImage::new(1, 1, vec![[0, 128, 255]]);
        let c = img.sample(Vec2::splat(0.5), [Wrap::Clamp; 2]);
        assert_eq!(c, Color::new(0.0, srgb_to_linear(128.0 / 255.0), 1.0));
        assert!((c.y - 0.2158605).abs() < 1e-6, "{c}");
    }

    #[test]
    fn wood_rings_alternate_outwards_from_the_z_axis() {
        let t = Texture::Wood {
            a: Color::ZERO,
            b: Color::ONE,
        };
        // Along a line where the wobble is zero (angle 0, z 0), ring k spans radii
        // [k, k + 1)·WOOD_RING_WIDTH.
        for k in 0..8 {
            let r = (k as f32 + 0.5) * WOOD_RING_WIDTH;
            let expected = if k % 2 == 0 { Color::ZERO } else { Color::ONE };
            assert_eq!(
                t.color(Vec2::ZERO, Vec3::new(r, 0.0, 0.0)),
                expected,
                "ring {k}"
            );
        }
        // The rings are round: the same radius elsewhere on the circle lies in a ring within
        // the wobble's reach.
        let p = Vec3::new(0.0, 3.5 * WOOD_RING_WIDTH, 0.0);
        assert!([Color::ZERO, Color::ONE].contains(&t.color(Vec2::ZERO, p)));
    }

    #[test]
    fn marble_darkens_its_colour_between_vein_and_stone() {
        let color = Color::new(0.9, 0.8, 0.7);
        let t = Texture::Marble { color };
        let mut brightness = Vec::new();
        for n in 0..400 {
            let p = Vec3::new(n as f32 * 0.031, 0.2, n as f32 * 0.013);
            let c = t.color(Vec2::ZERO, p);
            let k = c.x / color.x;
            assert!((0.149..=0.951).contains(&k), "{k}");
            assert!(
                (c - color * k).length() < 1e-5,
                "{c} is not a shade of {color}"
            );
            brightness.push(k);
        }
        let spread = brightness.iter().fold(0.0f32, |m, &k| m.max(k))
            - brightness.iter().fold(1.0f32, |m, &k| m.min(k));
        assert!(spread > 0.5, "veins and stone differ by only {spread}");
    }

    #[test]
    fn the_marble_profile_is_continuous() {
        for x in [-0.4f32, 0.4] {
            let (below, above) = (marble_spline(x - 1e-4), marble_spline(x + 1e-4));
            assert!((below - above).abs() < 1e-3, "{below} {above} at {x}");
        }
        assert_eq!(marble_spline(0.0), 0.95);
    }

    #[test]
    fn image_coordinates_are_scaled_then_offset() {
        let t = Texture::Image {
            image: Arc::new(two_by_two()),
            wrap: [Wrap::Clamp; 2],
            scale: Vec2::splat(0.5),
            offset: Vec2::new(0.5, 0.0),
        };
        // (0.5, 0.5) → (0.75, 0.25): the bottom-right texel.
        assert_eq!(t.color(Vec2::splat(0.5), Vec3::ZERO), Color::ONE);
    }
}
