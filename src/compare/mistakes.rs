//! The common mistakes of a ray tracer written for the lecture, each a change to how raylab
//! makes its image: a term of the shading model left out, a wrong index of refraction, eye rays
//! through pixel corners, the image upside down, the sRGB curve applied twice or not at all,
//! colours not clamped. [`trace_with`] and [`write_with`] make raylab's image with some of them,
//! so that `raylab check` can find those an image shows by comparing it with each.

use rayon::prelude::*;
use serde::Serialize;

use crate::camera::PIXEL_CENTRE;
use crate::color::{Color, linear_to_srgb, srgb8};
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
        }
    }

    /// Whether the mistake changes the scene or where the eye rays go, so that the image must
    /// be traced again; the others change only how it is written.
    pub fn retraces(self) -> bool {
        !matches!(
            self,
            Mistake::FlippedVertically
                | Mistake::GammaTwice
                | Mistake::NoGamma
                | Mistake::NoClamping
        )
    }

    /// Whether the two cannot be made at once (two indices of refraction, two sample
    /// positions, two curves).
    pub fn excludes(self, other: Mistake) -> bool {
        use Mistake::*;
        let group = |m: Mistake| match m {
            IndexOfRefractionOne | IndexOfRefractionInverted => 1,
            PixelCorners | PixelTopLeftCorners => 2,
            GammaTwice | NoGamma => 3,
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

/// raylab's image of `assembled`'s scene as linear colours, row by row, traced with the
/// mistakes among `mistakes` that [`Mistake::retraces`]. Without them it is the renderer's
/// image; eye rays through pixel corners are traced one per pixel.
pub fn trace_with(assembled: &Assembled, mistakes: &[Mistake]) -> Vec<Color> {
    let scene = scene_with(&assembled.scene, mistakes);
    let tracer = Tracer::new(&scene, &assembled.bvh).with_caustics(assembled.caustics.as_deref());
    let offset = sample_offset(mistakes);
    if offset == PIXEL_CENTRE {
        return crate::progressive::render_image(&tracer).0;
    }
    let (width, height) = (scene.settings.width, scene.settings.height);
    (0..height)
        .into_par_iter()
        .flat_map_iter(|y| {
            let mut counts = RayCounts::default();
            let tracer = &tracer;
            (0..width)
                .map(move |x| {
                    let ray = tracer.scene.camera.eye_ray((x, y), offset, (width, height));
                    tracer.trace_eye(&ray, &mut counts)
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The image of `width × height` linear `colors` as written with the mistakes among `mistakes`
/// that do not [`Mistake::retraces`].
pub fn write_with(width: u32, height: u32, colors: &[Color], mistakes: &[Mistake]) -> SrgbImage {
    let has = |m: Mistake| mistakes.contains(&m);
    let level = |v: f32| -> u8 {
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
    };
    let mut pixels: Vec<[u8; 3]> = colors.iter().map(|c| c.to_array().map(level)).collect();
    if has(Mistake::FlippedVertically) {
        let rows: Vec<&[[u8; 3]]> = pixels.chunks(width as usize).rev().collect();
        pixels = rows.concat();
    }
    SrgbImage {
        width,
        height,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn mistakes_of_one_kind_exclude_each_other() {
        assert!(Mistake::GammaTwice.excludes(Mistake::NoGamma));
        assert!(Mistake::PixelCorners.excludes(Mistake::PixelTopLeftCorners));
        assert!(!Mistake::NoShadows.excludes(Mistake::NoSpecular));
        assert!(!Mistake::NoGamma.excludes(Mistake::NoGamma));
    }
}
