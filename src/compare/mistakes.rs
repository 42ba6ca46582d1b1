//! The common mistakes of a ray tracer written for the lecture, each a change to how raylab
//! makes its image: a term of the shading model left out, a wrong index of refraction, eye rays
//! through pixel corners, the image upside down or a pixel off, the sRGB curve applied twice or
//! not at all, colours not clamped, every colour scaled. [`trace_with`] traces raylab's image
//! with some of them and [`Written`] writes it with the rest, pixel by pixel, so that
//! `raylab check` can find those an image shows by comparing it with each.

use rayon::prelude::*;
use serde::Serialize;

use crate::camera::PIXEL_CENTRE;
use crate::color::{linear_to_srgb, srgb_to_linear, srgb8};
use crate::film::Film;
use crate::render::Assembled;
use crate::scene::Scene;
use crate::srgb_image::SrgbImage;
use crate::stats::RayCounts;
use crate::whitted::Tracer;

/// A mistake `raylab check` recognises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, strum::EnumIter)]
#[serde(rename_all = "kebab-case")]
pub enum Mistake {
    /// No shadow rays: every light reaches every point that faces it.
    NoShadows,
    /// No specular (Phong) term.
    NoSpecular,
    /// No reflected rays.
    NoReflection,
    /// No transmitted rays.
    NoTransmission,
    /// Every index of refraction 1: refracted rays go straight on.
    IndexOfRefractionOne,
    /// Snell's ratio turned over: entering uses n₂/n₁ for n₁/n₂.
    IndexOfRefractionInverted,
    /// Eye rays through the pixels' bottom-left corners: the lecture's `dir_rc` with whole `r`
    /// and `c`, counted from the bottom-left corner of the image.
    PixelCorners,
    /// Eye rays through the pixels' top-left corners: whole `c`, and rows counted from the top.
    PixelTopLeftCorners,
    /// The rows written bottom first.
    FlippedVertically,
    /// The sRGB curve applied to values already encoded.
    GammaTwice,
    /// Linear values written as levels, with no sRGB curve.
    NoGamma,
    /// Values over 1 not clamped: their levels wrap around past 255.
    NoClamping,
    /// Every colour multiplied by one factor ([`Written::scale`], fitted to the image): a
    /// wrong exposure, or lights of another intensity.
    Scaled,
    /// The image one pixel to the left of where it belongs (its column 0 is raylab's column 1).
    ShiftedLeft,
    /// The image one pixel to the right.
    ShiftedRight,
    /// The image one pixel up.
    ShiftedUp,
    /// The image one pixel down.
    ShiftedDown,
}

impl Mistake {
    /// What the mistake is, as `raylab check` says it.
    pub fn describe(self) -> &'static str {
        match self {
            Mistake::NoShadows => "shadows are missing (no shadow rays)",
            Mistake::NoSpecular => "the specular (Phong) term is missing",
            Mistake::NoReflection => "reflections are missing (no reflected rays)",
            Mistake::NoTransmission => "transmission is missing (no transmitted rays)",
            Mistake::IndexOfRefractionOne => {
                "a wrong index of refraction: 1.0 (light is not bent) instead of the scene's"
            }
            Mistake::IndexOfRefractionInverted => {
                "a wrong index of refraction: Snell's ratio turned over (n2/n1 for n1/n2)"
            }
            Mistake::PixelCorners => {
                "a camera offset: eye rays through pixel corners (whole r and c, from the \
                 bottom-left) instead of pixel centres"
            }
            Mistake::PixelTopLeftCorners => {
                "a camera offset: eye rays through the pixels' top-left corners instead of \
                 their centres"
            }
            Mistake::FlippedVertically => "the image is flipped vertically (row 0 at the bottom)",
            Mistake::GammaTwice => "gamma applied twice (the sRGB curve on encoded values)",
            Mistake::NoGamma => "gamma not applied (linear values written as levels)",
            Mistake::NoClamping => "colours over 1 are not clamped (their levels wrap around)",
            Mistake::Scaled => {
                "every colour is scaled by one factor: look at the exposure or the lights' \
                 intensity"
            }
            Mistake::ShiftedLeft => "the image is shifted one pixel to the left",
            Mistake::ShiftedRight => "the image is shifted one pixel to the right",
            Mistake::ShiftedUp => "the image is shifted one pixel up",
            Mistake::ShiftedDown => "the image is shifted one pixel down",
        }
    }

    /// Whether raylab's ray tree at a pixel can account for what the mistake changes there (a
    /// term of the shading left out or changed); the others change the whole image alike.
    pub fn is_local(self) -> bool {
        matches!(
            self,
            Mistake::NoShadows
                | Mistake::NoSpecular
                | Mistake::NoReflection
                | Mistake::NoTransmission
                | Mistake::IndexOfRefractionOne
                | Mistake::IndexOfRefractionInverted
        )
    }

    /// Whether the mistake changes the scene or where the eye rays go, so that the image must
    /// be traced again; the others change only how it is written.
    pub fn retraces(self) -> bool {
        self.is_local() || matches!(self, Mistake::PixelCorners | Mistake::PixelTopLeftCorners)
    }

    /// Whether the two cannot be made at once (two indices of refraction, two sample
    /// positions, two curves, two shifts).
    pub fn excludes(self, other: Mistake) -> bool {
        use Mistake::*;
        let group = |m: Mistake| match m {
            IndexOfRefractionOne | IndexOfRefractionInverted => 1,
            PixelCorners | PixelTopLeftCorners => 2,
            GammaTwice | NoGamma => 3,
            ShiftedLeft | ShiftedRight | ShiftedUp | ShiftedDown => 4,
            _ => 0,
        };
        self != other && group(self) != 0 && group(self) == group(other)
    }

    /// Whether the mistake can change `scene`'s image at all.
    pub fn applies_to(self, scene: &Scene) -> bool {
        let materials = &scene.materials;
        match self {
            Mistake::NoShadows => !scene.lights.is_empty() && scene.settings.shadows,
            Mistake::NoSpecular => materials.iter().any(|m| m.specular > 0.0),
            Mistake::NoReflection => {
                scene.settings.reflections && materials.iter().any(|m| m.reflectivity > 0.0)
            }
            Mistake::NoTransmission
            | Mistake::IndexOfRefractionOne
            | Mistake::IndexOfRefractionInverted => {
                scene.settings.transmission
                    && materials
                        .iter()
                        .any(|m| m.transparency > 0.0 && m.ior != 1.0)
            }
            _ => true,
        }
    }
}

/// `scene` with the scene's mistakes among `mistakes` made.
fn scene_with(scene: &Scene, mistakes: &[Mistake]) -> Scene {
    let mut scene = scene.clone();
    for mistake in mistakes {
        let settings = &mut scene.settings;
        match mistake {
            Mistake::NoShadows => settings.shadows = false,
            Mistake::NoReflection => settings.reflections = false,
            Mistake::NoTransmission => settings.transmission = false,
            Mistake::NoSpecular => scene.materials.iter_mut().for_each(|m| m.specular = 0.0),
            Mistake::IndexOfRefractionOne => {
                scene.materials.iter_mut().for_each(|m| m.ior = 1.0);
            }
            Mistake::IndexOfRefractionInverted => {
                scene.materials.iter_mut().for_each(|m| m.ior = 1.0 / m.ior);
            }
            _ => {}
        }
    }
    scene
}

/// Where in its pixel each eye ray goes with `mistakes` made (x right, y down, in pixels).
fn sample_offset(mistakes: &[Mistake]) -> (f32, f32) {
    if mistakes.contains(&Mistake::PixelCorners) {
        (0.0, 1.0)
    } else if mistakes.contains(&Mistake::PixelTopLeftCorners) {
        (0.0, 0.0)
    } else {
        PIXEL_CENTRE
    }
}

/// raylab's image of `assembled`'s scene, traced with the mistakes among `mistakes` that
/// [`Mistake::retraces`]. Without them it is the renderer's image; eye rays through pixel
/// corners are traced one per pixel.
pub fn trace_with(assembled: &Assembled, mistakes: &[Mistake]) -> Film {
    let scene = scene_with(&assembled.scene, mistakes);
    let tracer = Tracer::new(&scene, &assembled.bvh).with_caustics(assembled.caustics.as_deref());
    let offset = sample_offset(mistakes);
    if offset == PIXEL_CENTRE {
        return crate::progressive::render_film(&tracer).0;
    }
    let (width, height) = (scene.settings.width, scene.settings.height);
    let film = Film::new(width, height);
    (0..height).into_par_iter().for_each(|y| {
        let mut counts = RayCounts::default();
        for x in 0..width {
            let ray = tracer.scene.camera.eye_ray((x, y), offset, (width, height));
            film.set(x, y, tracer.trace_eye(&ray, &mut counts));
        }
    });
    film
}

/// raylab's traced image as written with the mistakes among `mistakes` that do not
/// [`Mistake::retraces`], pixel by pixel: no written copy of the image is made.
pub struct Written<'a> {
    pub colors: &'a Film,
    pub mistakes: &'a [Mistake],
    /// The factor [`Mistake::Scaled`] multiplies colours by.
    pub scale: f32,
}

impl Written<'_> {
    /// The levels of pixel `(x, y)` (row 0 at the top).
    pub fn at(&self, x: u32, y: u32) -> [u8; 3] {
        let has = |m: Mistake| self.mistakes.contains(&m);
        let (width, height) = (self.colors.width(), self.colors.height());
        let (mut sx, mut sy) = (x, y);
        if has(Mistake::FlippedVertically) {
            sy = height - 1 - sy;
        }
        // Shifted left, the image shows at x what belongs at x + 1; at the edge, the edge.
        let step = |v: u32, by: i32, size: u32| (v as i32 + by).clamp(0, size as i32 - 1) as u32;
        if has(Mistake::ShiftedLeft) {
            sx = step(sx, 1, width);
        } else if has(Mistake::ShiftedRight) {
            sx = step(sx, -1, width);
        }
        if has(Mistake::ShiftedUp) {
            sy = step(sy, 1, height);
        } else if has(Mistake::ShiftedDown) {
            sy = step(sy, -1, height);
        }
        let mut color = self.colors.get(sx, sy);
        if has(Mistake::Scaled) {
            color *= self.scale;
        }
        color.to_array().map(|v| self.level(v))
    }

    /// The level a linear channel value `v` is written as.
    fn level(&self, v: f32) -> u8 {
        let has = |m: Mistake| self.mistakes.contains(&m);
        let encoded = if has(Mistake::NoGamma) {
            v
        } else if has(Mistake::GammaTwice) {
            linear_to_srgb(linear_to_srgb(v))
        } else if has(Mistake::NoClamping) && v > 1.0 {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        } else {
            return srgb8(v);
        };
        let level = (encoded.max(0.0) * 255.0).round();
        if has(Mistake::NoClamping) {
            (level as u32 % 256) as u8
        } else {
            level.min(255.0) as u8
        }
    }

    /// The whole written image.
    pub fn image(&self) -> SrgbImage {
        let (width, height) = (self.colors.width(), self.colors.height());
        let pixels = (0..height)
            .into_par_iter()
            .flat_map_iter(|y| (0..width).map(move |x| self.at(x, y)))
            .collect();
        SrgbImage::new(width, height, pixels)
    }
}

/// The factor that scales raylab's colours `traced` closest to `image` (least squares over the
/// linear values of the channels neither image clips at black or white).
pub fn fitted_scale(traced: &Film, image: &SrgbImage) -> f32 {
    let (mut both, mut ours) = (0.0f64, 0.0f64);
    for y in 0..image.height {
        for x in 0..image.width {
            let raylab = traced.get(x, y).to_array();
            for (c, level) in image.at(x, y).into_iter().enumerate() {
                let r = raylab[c];
                if (0.01..0.99).contains(&r) && (1..255).contains(&level) {
                    let yours = srgb_to_linear(f32::from(level) / 255.0);
                    both += f64::from(r) * f64::from(yours);
                    ours += f64::from(r) * f64::from(r);
                }
            }
        }
    }
    if ours > 0.0 {
        (both / ours) as f32
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::color::Color;

    /// The image of `width × height` linear `colors` written with `mistakes`.
    fn write_with(width: u32, height: u32, colors: &[Color], mistakes: &[Mistake]) -> SrgbImage {
        let film = Film::new(width, height);
        for (i, &c) in colors.iter().enumerate() {
            film.set(i as u32 % width, i as u32 / width, c);
        }
        let written = Written {
            colors: &film,
            mistakes,
            scale: 0.5,
        };
        written.image()
    }

    #[test]
    fn without_mistakes_the_image_is_written_as_raylab_writes_it() {
        let colors = [Color::new(0.2, 0.5, 2.0), Color::new(-1.0, 1.0, 0.001)];
        let image = write_with(1, 2, &colors, &[]);
        assert_eq!(image, SrgbImage::from_linear(1, 2, &colors));
    }

    #[test]
    fn the_curves_and_the_flip_are_those_of_the_mistakes() {
        let colors = [Color::new(0.5, 0.0, 0.0), Color::new(1.5, 0.25, 1.0)];
        let flipped = write_with(1, 2, &colors, &[Mistake::FlippedVertically]);
        assert_eq!(flipped.pixels[0], [255, srgb8(0.25), 255], "row 1 first");
        let linear = write_with(1, 2, &colors, &[Mistake::NoGamma]);
        assert_eq!(linear.pixels[0], [128, 0, 0]);
        let twice = write_with(1, 2, &colors, &[Mistake::GammaTwice]);
        assert_eq!(twice.pixels[0][0], srgb8(linear_to_srgb(0.5)));
        // 1.5 encodes past 1: 1.055·1.5^(1/2.4) − 0.055 = 1.1942, 305 levels, wraps to 49.
        let wrapped = write_with(1, 2, &colors, &[Mistake::NoClamping]);
        assert_eq!(wrapped.pixels[1][0], 49);
    }

    #[test]
    fn shifts_and_scaling_move_and_darken_the_image() {
        let colors = [Color::splat(0.1), Color::splat(0.2), Color::splat(0.4)];
        let levels = |image: SrgbImage| image.pixels.iter().map(|p| p[0]).collect::<Vec<_>>();
        let [a, b, c] = colors.map(|c| srgb8(c.x));
        let left = write_with(3, 1, &colors, &[Mistake::ShiftedLeft]);
        assert_eq!(levels(left), [b, c, c]);
        let right = write_with(3, 1, &colors, &[Mistake::ShiftedRight]);
        assert_eq!(levels(right), [a, a, b]);
        let scaled = write_with(3, 1, &colors, &[Mistake::Scaled]);
        assert_eq!(levels(scaled), [0.05, 0.1, 0.2].map(srgb8));
        let down = write_with(1, 3, &colors, &[Mistake::ShiftedDown]);
        assert_eq!(levels(down), [a, a, b]);
    }

    #[test]
    fn the_scale_fitted_is_the_one_made() {
        let film = Film::new(16, 1);
        let mut pixels = Vec::new();
        for x in 0..16 {
            let c = Color::splat(0.05 * (x + 1) as f32);
            film.set(x, 0, c);
            pixels.push((c * 0.8).to_array().map(srgb8));
        }
        let image = SrgbImage::new(16, 1, pixels);
        assert!((fitted_scale(&film, &image) - 0.8).abs() < 0.01);
    }

    #[test]
    fn mistakes_of_one_kind_exclude_each_other() {
        assert!(Mistake::GammaTwice.excludes(Mistake::NoGamma));
        assert!(Mistake::PixelCorners.excludes(Mistake::PixelTopLeftCorners));
        assert!(!Mistake::NoShadows.excludes(Mistake::NoSpecular));
        assert!(!Mistake::NoGamma.excludes(Mistake::NoGamma));
        assert!(Mistake::ShiftedLeft.excludes(Mistake::ShiftedUp));
    }
}
