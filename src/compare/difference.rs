//! The figures of how an image differs from its reference ([`Difference`]), in 8-bit levels,
//! and the heat map of where ([`HeatMap`]).

use rayon::prelude::*;
use serde::Serialize;

use crate::color::Color;
use crate::inspect::{Legend, heat, heat_bar};
use crate::srgb_image::SrgbImage;

/// The tolerance a course's grader allows by default: a pixel differs when one of its channels
/// is more than this many 8-bit levels off.
pub const DEFAULT_TOLERANCE: u8 = 2;

/// How an image differs from its reference. Levels are 8-bit sRGB values (0 to 255).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Difference {
    pub width: u32,
    pub height: u32,
    /// The mean of |image − reference| over every channel of every pixel.
    pub mean_absolute: f64,
    /// The root of the mean squared difference over every channel of every pixel.
    pub rmse: f64,
    /// Peak signal-to-noise ratio in decibels, 20·log10(255 / RMSE); infinite for equal images.
    pub psnr: f64,
    /// The largest difference of any channel, and the first pixel (in reading order) that has it.
    pub largest: u8,
    pub largest_at: (u32, u32),
    pub tolerance: u8,
    /// The pixels with a channel more than `tolerance` levels off.
    pub over_tolerance: u64,
}

impl Difference {
    /// Whether every pixel is within the tolerance.
    pub fn within_tolerance(&self) -> bool {
        self.over_tolerance == 0
    }

    /// The share of the pixels over the tolerance, in [0, 1].
    pub fn over_tolerance_share(&self) -> f64 {
        self.over_tolerance as f64 / (f64::from(self.width) * f64::from(self.height))
    }
}

/// Checks that two images have the same size; the error gives both.
pub fn check_same_size(reference: &SrgbImage, image: &SrgbImage) -> Result<(), String> {
    check_sizes(
        (reference.width, reference.height),
        (image.width, image.height),
    )
}

/// Checks that images of the sizes `reference` and `image` (width, height) can be compared.
pub fn check_sizes(reference: (u32, u32), image: (u32, u32)) -> Result<(), String> {
    if reference == image {
        Ok(())
    } else {
        Err(format!(
            "the images differ in size: the reference is {}×{}, the image {}×{}",
            reference.0, reference.1, image.0, image.1
        ))
    }
}

/// The largest difference of a channel between two pixels, in levels.
pub fn pixel_difference(a: [u8; 3], b: [u8; 3]) -> u8 {
    (0..3).map(|c| a[c].abs_diff(b[c])).max().unwrap_or(0)
}

/// The figures of `image` against `reference`, a pixel over `tolerance` levels off counted as
/// different. The images must be the same size ([`check_same_size`]).
pub fn difference(
    reference: &SrgbImage,
    image: &SrgbImage,
    tolerance: u8,
) -> Result<Difference, String> {
    check_same_size(reference, image)?;
    Ok(difference_from(|x, y| reference.at(x, y), image, tolerance))
}

/// The sums of a part of the image that make up its [`Difference`].
#[derive(Clone, Copy, Default)]
struct Sums {
    sum: u64,
    squares: u64,
    /// The largest difference and its pixel's index (the first of them in reading order).
    largest: (u8, u64),
    over_tolerance: u64,
}

impl Sums {
    fn add(self, other: Sums) -> Sums {
        let first_largest = |a: (u8, u64), b: (u8, u64)| {
            if b.0 > a.0 || (b.0 == a.0 && b.1 < a.1) {
                b
            } else {
                a
            }
        };
        Sums {
            sum: self.sum + other.sum,
            squares: self.squares + other.squares,
            largest: first_largest(self.largest, other.largest),
            over_tolerance: self.over_tolerance + other.over_tolerance,
        }
    }
}

/// [`difference`] of `image` against the reference whose pixel `(x, y)` is `reference(x, y)`,
/// made pixel by pixel as it is measured (on all threads, a row each).
pub fn difference_from(
    reference: impl Fn(u32, u32) -> [u8; 3] + Sync,
    image: &SrgbImage,
    tolerance: u8,
) -> Difference {
    let (width, height) = (image.width, image.height);
    let sums = (0..height)
        .into_par_iter()
        .map(|y| {
            let mut row = Sums {
                largest: (0, u64::from(y) * u64::from(width)),
                ..Sums::default()
            };
            for x in 0..width {
                let (a, b) = (reference(x, y), image.at(x, y));
                for c in 0..3 {
                    let d = u64::from(a[c].abs_diff(b[c]));
                    row.sum += d;
                    row.squares += d * d;
                }
                let d = pixel_difference(a, b);
                if d > row.largest.0 {
                    row.largest = (d, u64::from(y) * u64::from(width) + u64::from(x));
                }
                row.over_tolerance += u64::from(d > tolerance);
            }
            row
        })
        .reduce(Sums::default, Sums::add);
    let channels = f64::from(width) * f64::from(height) * 3.0;
    let rmse = (sums.squares as f64 / channels).sqrt();
    let (largest, index) = sums.largest;
    Difference {
        width,
        height,
        mean_absolute: sums.sum as f64 / channels,
        rmse,
        psnr: 20.0 * (255.0 / rmse).log10(),
        largest,
        largest_at: (
            (index % u64::from(width)) as u32,
            (index / u64::from(width)) as u32,
        ),
        tolerance,
        over_tolerance: sums.over_tolerance,
    }
}

/// The heat map of where an image differs from its reference: each pixel's largest channel
/// difference on the heat ramp, from 0 to the largest difference in the image (at least one
/// level past the tolerance, so equal images stay dark). Its colours are made pixel by pixel
/// ([`HeatMap::color`]), so that writing it takes no image-sized buffer.
pub struct HeatMap<'a> {
    reference: &'a SrgbImage,
    image: &'a SrgbImage,
    tolerance: u8,
    /// The difference shown brightest.
    top: u8,
}

impl<'a> HeatMap<'a> {
    /// The heat map of `image` against `reference`, whose figures are `difference`. The images
    /// must be the same size.
    pub fn new(reference: &'a SrgbImage, image: &'a SrgbImage, difference: &Difference) -> Self {
        HeatMap {
            reference,
            image,
            tolerance: difference.tolerance,
            top: difference
                .largest
                .max(difference.tolerance.saturating_add(1)),
        }
    }

    /// The linear colour of pixel `(x, y)`.
    pub fn color(&self, x: u32, y: u32) -> Color {
        let d = pixel_difference(self.reference.at(x, y), self.image.at(x, y));
        heat(f32::from(d) / f32::from(self.top))
    }

    /// The legend: the ramp from 0 to the top, the tolerance marked.
    pub fn legend(&self) -> Legend {
        let tolerance = f32::from(self.tolerance) / f32::from(self.top);
        Legend {
            label: "largest channel difference, 8-bit levels".into(),
            ticks: vec![
                (0.0, "0".into()),
                (
                    tolerance.min(1.0),
                    format!("{} (tolerance)", self.tolerance),
                ),
                (1.0, self.top.to_string()),
            ],
            colors: heat_bar(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, pixels: &[[u8; 3]]) -> SrgbImage {
        SrgbImage::new(width, pixels.len() as u32 / width, pixels.to_vec())
    }

    #[test]
    fn the_figures_are_the_hand_computed_ones() {
        let reference = image(2, &[[10, 20, 30], [100, 100, 100]]);
        let student = image(2, &[[13, 20, 30], [100, 90, 100]]);
        let d = difference(&reference, &student, 2).unwrap();
        // Channel differences 3, 0, 0 and 0, 10, 0.
        assert!((d.mean_absolute - 13.0 / 6.0).abs() < 1e-12, "{d:?}");
        assert!((d.rmse - (109.0f64 / 6.0).sqrt()).abs() < 1e-12, "{d:?}");
        assert!((d.psnr - 35.5386).abs() < 1e-3, "{d:?}");
        assert_eq!((d.largest, d.largest_at), (10, (1, 0)));
        assert_eq!(d.over_tolerance, 2);
        let d = difference(&reference, &student, 3).unwrap();
        assert_eq!(d.over_tolerance, 1);
        assert!(!d.within_tolerance());
        assert_eq!(
            difference(&reference, &student, 10).unwrap().over_tolerance,
            0
        );
    }

    #[test]
    fn equal_images_differ_by_nothing() {
        let a = image(1, &[[1, 2, 3], [4, 5, 6]]);
        let d = difference(&a, &a, 0).unwrap();
        assert_eq!((d.mean_absolute, d.rmse, d.largest), (0.0, 0.0, 0));
        assert_eq!(d.psnr, f64::INFINITY);
        assert!(d.within_tolerance());
    }

    #[test]
    fn images_of_different_sizes_are_refused() {
        let err = difference(&image(2, &[[0; 3]; 4]), &image(1, &[[0; 3]; 4]), 2).unwrap_err();
        assert!(err.contains("2×2") && err.contains("1×4"), "{err}");
    }

    #[test]
    fn the_heat_map_is_darkest_where_equal_and_brightest_at_the_largest() {
        let reference = image(3, &[[0; 3], [0; 3], [0; 3]]);
        let student = image(3, &[[0; 3], [0, 4, 0], [0, 0, 8]]);
        let d = difference(&reference, &student, 2).unwrap();
        let map = HeatMap::new(&reference, &student, &d);
        let pixels: Vec<Color> = (0..3).map(|x| map.color(x, 0)).collect();
        assert_eq!(pixels, vec![heat(0.0), heat(0.5), heat(1.0)]);
        assert_eq!(map.legend().ticks.last().unwrap().1, "8");
    }
}
