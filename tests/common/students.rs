//! A student's images with the mistakes `raylab check` names, each made here its own way (the
//! scene changed, the lecture's camera taken literally, the levels written wrongly), not with
//! `check`'s code: what the tests of `check` and `grade` hand in.

use raylab::bvh::Bvh;
use raylab::color::{Color, srgb8};
use raylab::progressive::render_image;
use raylab::scene::Scene;
use raylab::stats::RayCounts;
use raylab::whitted::Tracer;

/// An image with one mistake: its name (a file stem), its levels row by row, and what `check`
/// says of it.
pub struct Mistaken {
    pub name: &'static str,
    pub pixels: Vec<[u8; 3]>,
    pub says: &'static str,
}

/// The scene's image as the renderer makes it (linear colours, row by row).
pub fn rendered(scene: &Scene) -> Vec<Color> {
    let bvh = Bvh::build(&scene.geometry);
    render_image(&Tracer::new(scene, &bvh)).0
}

pub fn levels(colors: &[Color]) -> Vec<[u8; 3]> {
    colors.iter().map(|c| c.to_array().map(srgb8)).collect()
}

/// The lecture's tracer taken literally: the eye ray of pixel (x, y) is `dir_rc` at whole
/// `c = x` and `r` = the row counted from the bottom, a corner of the pixel, not its centre.
/// With `from_top`, the rows are counted from the top: the ray goes through the pixel's
/// top-left corner.
fn rendered_through_corners(scene: &Scene, from_top: bool) -> Vec<Color> {
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(scene, &bvh);
    let (width, height) = (scene.settings.width, scene.settings.height);
    let mut counts = RayCounts::default();
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let r = (height - y - u32::from(!from_top)) as f32;
            let ray = scene.camera.ray(r, x as f32, height, width);
            tracer.trace_eye(&ray, &mut counts)
        })
        .collect()
}

/// `pixels`, rows of `width`, with the rows in the other order.
pub fn flipped(pixels: &[[u8; 3]], width: u32) -> Vec<[u8; 3]> {
    pixels
        .chunks(width as usize)
        .rev()
        .flatten()
        .copied()
        .collect()
}

/// `pixels`, rows of `width`, moved by `(dx, dy)` pixels (right and down), the edge repeated
/// where the image moved away from it.
fn shifted(pixels: &[[u8; 3]], width: u32, (dx, dy): (i32, i32)) -> Vec<[u8; 3]> {
    let height = pixels.len() as i32 / width as i32;
    let width = width as i32;
    (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let (sx, sy) = ((x - dx).clamp(0, width - 1), (y - dy).clamp(0, height - 1));
            pixels[(sy * width + sx) as usize]
        })
        .collect()
}

/// `scene` (a clone) changed by `change`.
fn changed(scene: &Scene, change: impl FnOnce(&mut Scene)) -> Scene {
    let mut scene = scene.clone();
    change(&mut scene);
    scene
}

/// `scene`'s image with each mistake `check` knows, named as the likely cause: a term of the
/// shading left out, a wrong index of refraction (1, or Snell's ratio turned over), eye rays
/// through pixel corners (bottom-left or top-left), the image flipped or shifted a pixel each
/// way, the sRGB curve twice or not at all, no clamping, the colours scaled. The scene needs
/// shadows, specular highlights, mirrors and glass of index 1.5.
pub fn mistaken(scene: &Scene) -> Vec<Mistaken> {
    let width = scene.settings.width;
    let colors = rendered(scene);
    let reference = levels(&colors);
    // Gamma applied again, as 1/2.2, to levels already encoded with the sRGB curve.
    let gamma_twice = reference
        .iter()
        .map(|p| p.map(|l| (255.0 * (f32::from(l) / 255.0).powf(1.0 / 2.2)).round() as u8))
        .collect();
    // Linear values written as levels.
    let no_gamma = colors
        .iter()
        .map(|c| {
            c.to_array()
                .map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)
        })
        .collect();
    // The sRGB curve past 1, the level cast to a byte as C does: it wraps around.
    let wrapped = |v: f32| {
        let encoded = if v <= 0.0031308 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        ((encoded.max(0.0) * 255.0).round() as i64).rem_euclid(256) as u8
    };
    let no_clamping = colors.iter().map(|c| c.to_array().map(wrapped)).collect();
    // Glass of index 1.5 given the index `ior`.
    let glass = |ior: f32| {
        move |s: &mut Scene| {
            for m in &mut s.materials {
                if m.ior == 1.5 {
                    m.ior = ior;
                }
            }
        }
    };
    let no_specular = |s: &mut Scene| s.materials.iter_mut().for_each(|m| m.specular = 0.0);
    let image = |change: &dyn Fn(&mut Scene)| levels(&rendered(&changed(scene, change)));
    let one = |name, pixels, says| Mistaken { name, pixels, says };
    vec![
        one(
            "no-shadows",
            image(&|s| s.settings.shadows = false),
            "likely cause: shadows are missing",
        ),
        one(
            "no-specular",
            image(&no_specular),
            "likely cause: the specular (Phong) term is missing",
        ),
        one(
            "no-reflection",
            image(&|s| s.settings.reflections = false),
            "likely cause: reflections are missing",
        ),
        one(
            "no-transmission",
            image(&|s| s.settings.transmission = false),
            "likely cause: transmission is missing",
        ),
        one(
            "ior-1",
            image(&glass(1.0)),
            "likely cause: a wrong index of refraction: 1.0",
        ),
        one(
            "ior-inverted",
            image(&glass(1.0 / 1.5)),
            "likely cause: a wrong index of refraction: Snell's ratio turned over",
        ),
        one(
            "corners",
            levels(&rendered_through_corners(scene, false)),
            "likely cause: a camera offset: eye rays through pixel corners",
        ),
        one(
            "top-left-corners",
            levels(&rendered_through_corners(scene, true)),
            "likely cause: a camera offset: eye rays through the pixels' top-left corners",
        ),
        one(
            "flipped",
            flipped(&reference, width),
            "likely cause: the image is flipped vertically",
        ),
        one(
            "gamma-twice",
            gamma_twice,
            "likely cause: gamma applied twice",
        ),
        one("no-gamma", no_gamma, "likely cause: gamma not applied"),
        one(
            "no-clamping",
            no_clamping,
            "likely cause: colours over 1 are not clamped",
        ),
        one(
            "darker",
            levels(&colors.iter().map(|c| *c * 0.8).collect::<Vec<_>>()),
            "likely cause: every colour is scaled by one factor",
        ),
        one(
            "shifted-right",
            shifted(&reference, width, (1, 0)),
            "likely cause: the image is shifted one pixel to the right",
        ),
        one(
            "shifted-left",
            shifted(&reference, width, (-1, 0)),
            "likely cause: the image is shifted one pixel to the left",
        ),
        one(
            "shifted-up",
            shifted(&reference, width, (0, -1)),
            "likely cause: the image is shifted one pixel up",
        ),
        one(
            "shifted-down",
            shifted(&reference, width, (0, 1)),
            "likely cause: the image is shifted one pixel down",
        ),
    ]
}
