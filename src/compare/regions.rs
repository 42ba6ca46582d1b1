//! The regions where two images differ: each a set of connected pixels (touching at a side or a
//! corner) over the tolerance, with its size, its bounds and its worst pixel.

use serde::Serialize;

use super::difference::{check_same_size, pixel_difference};
use crate::srgb_image::SrgbImage;

/// Connected pixels over the tolerance.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Region {
    /// How many pixels it has.
    pub pixels: u64,
    /// The smallest rectangle around it: left and top column and row, then right and bottom,
    /// inclusive.
    pub bounds: [u32; 4],
    /// Its pixel with the largest channel difference (the first in reading order), and that
    /// difference in levels.
    pub worst: (u32, u32),
    pub worst_levels: u8,
}

/// The regions where `image` differs from `reference` by more than `tolerance` levels, largest
/// first (then in reading order of their first pixel).
pub fn regions(
    reference: &SrgbImage,
    image: &SrgbImage,
    tolerance: u8,
) -> Result<Vec<Region>, String> {
    check_same_size(reference, image)?;
    let (width, height) = (reference.width as usize, reference.height as usize);
    let over: Vec<u8> = reference
        .pixels
        .iter()
        .zip(&image.pixels)
        .map(|(a, b)| pixel_difference(*a, *b))
        .collect();
    let mut seen = vec![false; over.len()];
    // Pixel indices; an image has fewer than 2³² pixels (its sides are at most 16384).
    let mut found = Vec::new();
    let mut stack = Vec::new();
    for start in 0..over.len() {
        if seen[start] || over[start] <= tolerance {
            continue;
        }
        seen[start] = true;
        stack.push(start as u32);
        let mut region = Region {
            pixels: 0,
            bounds: [u32::MAX, u32::MAX, 0, 0],
            worst: (0, 0),
            worst_levels: 0,
        };
        while let Some(i) = stack.pop() {
            let i = i as usize;
            let (x, y) = (i % width, i / width);
            add_pixel(&mut region, (x as u32, y as u32), over[i]);
            for (dx, dy) in NEIGHBOURS {
                let (nx, ny) = (x as isize + dx, y as isize + dy);
                if nx < 0 || ny < 0 || nx >= width as isize || ny >= height as isize {
                    continue;
                }
                let j = ny as usize * width + nx as usize;
                if !seen[j] && over[j] > tolerance {
                    seen[j] = true;
                    stack.push(j as u32);
                }
            }
        }
        found.push((start, region));
    }
    found.sort_by_key(|(start, region)| (std::cmp::Reverse(region.pixels), *start));
    Ok(found.into_iter().map(|(_, region)| region).collect())
}

/// The eight pixels that touch one at a side or a corner.
const NEIGHBOURS: [(isize, isize); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// Adds pixel `at`, `levels` off, to `region`. The pixels come in no particular order, so the
/// worst is the first in reading order among equals.
fn add_pixel(region: &mut Region, at: (u32, u32), levels: u8) {
    let [x0, y0, x1, y1] = &mut region.bounds;
    (*x0, *y0) = ((*x0).min(at.0), (*y0).min(at.1));
    (*x1, *y1) = ((*x1).max(at.0), (*y1).max(at.1));
    let earlier = (at.1, at.0) < (region.worst.1, region.worst.0);
    let worse = levels > region.worst_levels || (levels == region.worst_levels && earlier);
    if region.pixels == 0 || worse {
        region.worst = at;
        region.worst_levels = levels;
    }
    region.pixels += 1;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An image whose pixels are `levels` grey, from rows of text: '.' 0, digits 1 to 9 × 10.
    fn image(rows: &[&str]) -> SrgbImage {
        let pixels = rows
            .iter()
            .flat_map(|row| row.chars())
            .map(|c| [c.to_digit(10).map_or(0, |d| d as u8 * 10); 3])
            .collect();
        SrgbImage::new(rows[0].len() as u32, rows.len() as u32, pixels)
    }

    #[test]
    fn pixels_touching_at_a_corner_are_one_region_and_the_largest_comes_first() {
        let reference = image(&["......", "......", "......", "......"]);
        let mine = image(&["1.....", ".2..5.", "....55", "9....."]);
        let found = regions(&reference, &mine, 2).unwrap();
        assert_eq!(found.len(), 3, "{found:?}");
        assert_eq!(found[0].pixels, 3);
        assert_eq!(found[0].bounds, [4, 1, 5, 2]);
        assert_eq!((found[0].worst, found[0].worst_levels), ((4, 1), 50));
        assert_eq!(found[1].pixels, 2, "(0, 0) and (1, 1) touch at a corner");
        assert_eq!((found[1].worst, found[1].worst_levels), ((1, 1), 20));
        assert_eq!((found[2].worst, found[2].pixels), ((0, 3), 1));
    }

    #[test]
    fn pixels_within_the_tolerance_make_no_region() {
        let reference = image(&["...", "..."]);
        let mine = image(&["1.1", ".1."]);
        assert!(regions(&reference, &mine, 10).unwrap().is_empty());
        assert_eq!(regions(&reference, &mine, 9).unwrap().len(), 1);
    }
}
