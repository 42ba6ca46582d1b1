//! What an image shows that points to where its mistake is when no common mistake accounts for
//! it: an image of one colour (all black: no light reached the eye), edges that do not line up
//! with raylab's (the camera), or edges that do with every colour scaled (the exposure or the
//! lights).

use serde::Serialize;

use super::difference::pixel_difference;
use crate::srgb_image::SrgbImage;

/// Neighbours that differ by more than this many levels in a channel make an edge.
const EDGE_LEVELS: u8 = 24;

/// At least this share of your image's edge pixels are raylab's edge pixels too where the edges
/// line up; fewer, and the objects are elsewhere in the frame.
const EDGES_TOGETHER: f64 = 0.8;

/// How far from 1 the fitted scale of the colours must be to be worth a word.
const SCALED: f32 = 0.05;

/// One thing the image shows.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Evidence {
    /// `one-colour`, `edges-apart` or `scaled`.
    pub kind: &'static str,
    /// What it shows and where to look, in a sentence.
    pub says: String,
}

/// What `image` shows, against raylab's image `raylab` of the same size, whose colours scale to
/// it by `scale` (fitted by least squares).
pub fn evidence(raylab: &SrgbImage, image: &SrgbImage, scale: f32) -> Vec<Evidence> {
    if let Some(color) = one_colour(image) {
        let says = if color == [0; 3] {
            "your image is all black: no light reached any pixel. Do the eye rays hit anything \
             (the camera, each pixel's ray), and do the lights reach the surfaces?"
                .to_string()
        } else {
            format!(
                "every pixel of your image is ({}, {}, {}): each eye ray sees the same thing, as \
                 when every ray misses and sees the background; look at the camera and at how \
                 each pixel's ray is made",
                color[0], color[1], color[2]
            )
        };
        return vec![Evidence {
            kind: "one-colour",
            says,
        }];
    }
    let Some(share) = edges_together(raylab, image) else {
        return Vec::new();
    };
    if share < EDGES_TOGETHER {
        return vec![Evidence {
            kind: "edges-apart",
            says: format!(
                "only {:.0} % of the edges in your image are where raylab's are: the objects \
                 are not where raylab sees them. Look at the camera: the eye, the \
                 look-at point, the up vector, the view angle θ and the image's aspect",
                100.0 * share
            ),
        }];
    }
    if (scale - 1.0).abs() > SCALED {
        return vec![Evidence {
            kind: "scaled",
            says: format!(
                "the edges line up with raylab's ({:.0} %), but your colours are raylab's × \
                 {scale:.2} overall: look at the exposure and the lights' intensity",
                100.0 * share
            ),
        }];
    }
    Vec::new()
}

/// The one colour of every pixel of `image`, if it has one.
fn one_colour(image: &SrgbImage) -> Option<[u8; 3]> {
    let first = *image.pixels.first()?;
    image.pixels.iter().all(|&p| p == first).then_some(first)
}

/// Whether pixel `(x, y)` of `image` is on an edge: it differs from its right or lower
/// neighbour by more than [`EDGE_LEVELS`].
fn is_edge(image: &SrgbImage, x: u32, y: u32) -> bool {
    let here = image.at(x, y);
    (x + 1 < image.width && pixel_difference(here, image.at(x + 1, y)) > EDGE_LEVELS)
        || (y + 1 < image.height && pixel_difference(here, image.at(x, y + 1)) > EDGE_LEVELS)
}

/// The share of `image`'s edge pixels that are edge pixels of `raylab` too; `None` when either
/// image has no edges.
fn edges_together(raylab: &SrgbImage, image: &SrgbImage) -> Option<f64> {
    let (width, height) = (image.width, image.height);
    let (mut edges, mut together, mut raylab_edges) = (0u64, 0u64, 0u64);
    for y in 0..height {
        for x in 0..width {
            raylab_edges += u64::from(is_edge(raylab, x, y));
            if !is_edge(image, x, y) {
                continue;
            }
            edges += 1;
            together += u64::from(is_edge(raylab, x, y));
        }
    }
    (edges > 0 && raylab_edges > 0).then(|| together as f64 / edges as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `size × size` image, white where `inside(x, y)`, else black.
    fn shape(size: u32, inside: impl Fn(u32, u32) -> bool) -> SrgbImage {
        let pixels = (0..size * size)
            .map(|i| {
                if inside(i % size, i / size) {
                    [255; 3]
                } else {
                    [0; 3]
                }
            })
            .collect();
        SrgbImage::new(size, size, pixels)
    }

    #[test]
    fn an_image_of_one_colour_is_called_out() {
        let raylab = shape(20, |x, _| x < 10);
        let black = shape(20, |_, _| false);
        let said = evidence(&raylab, &black, 1.0);
        assert_eq!(said[0].kind, "one-colour");
        assert!(said[0].says.contains("all black"), "{said:?}");
        let grey = SrgbImage {
            pixels: vec![[40, 50, 60]; 400],
            ..black
        };
        assert!(
            evidence(&raylab, &grey, 1.0)[0]
                .says
                .contains("(40, 50, 60)")
        );
    }

    #[test]
    fn edges_elsewhere_point_to_the_camera_and_edges_in_place_to_the_exposure() {
        let raylab = shape(40, |x, y| (10..20).contains(&x) && (10..20).contains(&y));
        let moved = shape(40, |x, y| (25..35).contains(&x) && (22..32).contains(&y));
        let said = evidence(&raylab, &moved, 1.0);
        assert_eq!(said[0].kind, "edges-apart", "{said:?}");
        assert!(said[0].says.contains("camera"), "{said:?}");
        let said = evidence(&raylab, &raylab, 0.6);
        assert_eq!(said[0].kind, "scaled", "{said:?}");
        assert!(said[0].says.contains("× 0.60"), "{said:?}");
        assert!(evidence(&raylab, &raylab, 1.0).is_empty());
    }
}
