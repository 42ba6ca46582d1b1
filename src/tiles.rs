//! Splitting an image into rectangles rendered apart (on other machines, by a scheduler's array
//! of tasks) and checking that a set of them covers the image exactly once, for merging.
//!
//! [`split`] cuts a `width × height` image into `n` tiles as a grid of `rows × columns` cells,
//! `rows · columns = n`, choosing among the factor pairs of `n` the one whose cells are nearest
//! to square (a prime `n` gives bands of rows or columns). Cell borders lie at
//! `⌊i · width / columns⌋`, so sizes that `n` does not divide give cells that differ by one pixel
//! at most. Tiles are numbered row by row from 0.

use std::fmt;

/// A rectangle of pixels, half-open as pbrt's `--pixelbounds`: columns `x0..x1`, rows `y0..y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Rect {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl Rect {
    /// The whole `width × height` image.
    pub fn image(width: u32, height: u32) -> Rect {
        Rect {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }

    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }

    pub fn pixels(&self) -> u64 {
        u64::from(self.width()) * u64::from(self.height())
    }

    /// Whether the rectangle lies inside `outer`.
    pub fn is_inside(&self, outer: &Rect) -> bool {
        self.x0 >= outer.x0 && self.y0 >= outer.y0 && self.x1 <= outer.x1 && self.y1 <= outer.y1
    }

    /// Whether the two rectangles share a pixel.
    pub fn overlaps(&self, other: &Rect) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    /// The rectangle grown by `margin` pixels on every side, clipped to `bounds`.
    pub fn grown(&self, margin: u32, bounds: &Rect) -> Rect {
        Rect {
            x0: self.x0.saturating_sub(margin).max(bounds.x0),
            y0: self.y0.saturating_sub(margin).max(bounds.y0),
            x1: self.x1.saturating_add(margin).min(bounds.x1),
            y1: self.y1.saturating_add(margin).min(bounds.y1),
        }
    }
}

impl fmt::Display for Rect {
    /// As `--crop` takes it: `X0,Y0,X1,Y1`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{},{},{}", self.x0, self.y0, self.x1, self.y1)
    }
}

/// The `rows × columns` grid [`split`] uses for `n` tiles of a `width × height` image: of the
/// factor pairs of `n` with no empty cell, the one whose cells are nearest to square. `None`
/// when `n` is 0 or every grid of `n` cells has an empty one (more rows than pixels, say).
pub fn grid(width: u32, height: u32, n: u32) -> Option<(u32, u32)> {
    // How far a cell of the grid is from square: |log(cell width / cell height)|.
    let squareness = |(rows, columns): (u32, u32)| {
        let aspect =
            (f64::from(width) * f64::from(rows)) / (f64::from(height) * f64::from(columns));
        aspect.ln().abs()
    };
    (1..=n)
        .filter(|rows| n.is_multiple_of(*rows))
        .map(|rows| (rows, n / rows))
        .filter(|&(rows, columns)| rows <= height && columns <= width)
        .min_by(|a, b| squareness(*a).total_cmp(&squareness(*b)))
}

/// Why an image cannot be split as asked.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SplitError {
    NoTiles,
    TileOutOfRange { k: u32, n: u32 },
    TooManyTiles { n: u32, width: u32, height: u32 },
}

impl fmt::Display for SplitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SplitError::NoTiles => write!(f, "the number of tiles must be at least 1"),
            SplitError::TileOutOfRange { k, n } => {
                write!(
                    f,
                    "tile {k} of {n} does not exist: tiles are numbered 0 to {}",
                    n - 1
                )
            }
            SplitError::TooManyTiles { n, width, height } => write!(
                f,
                "a {width}×{height} image cannot be split into {n} tiles without an empty one"
            ),
        }
    }
}

impl std::error::Error for SplitError {}

/// Tile `k` of the `n` tiles [`split`] cuts a `width × height` image into.
pub fn tile(width: u32, height: u32, k: u32, n: u32) -> Result<Rect, SplitError> {
    if n == 0 {
        return Err(SplitError::NoTiles);
    }
    if k >= n {
        return Err(SplitError::TileOutOfRange { k, n });
    }
    let (rows, columns) =
        grid(width, height, n).ok_or(SplitError::TooManyTiles { n, width, height })?;
    // The border before cell `i` of `cells` along `size` pixels.
    let border =
        |i: u32, cells: u32, size: u32| (u64::from(i) * u64::from(size) / u64::from(cells)) as u32;
    let (row, column) = (k / columns, k % columns);
    Ok(Rect {
        x0: border(column, columns, width),
        y0: border(row, rows, height),
        x1: border(column + 1, columns, width),
        y1: border(row + 1, rows, height),
    })
}

/// All `n` tiles of a `width × height` image, in order.
pub fn split(width: u32, height: u32, n: u32) -> Result<Vec<Rect>, SplitError> {
    (0..n.max(1)).map(|k| tile(width, height, k, n)).collect()
}

/// What is wrong with a set of rectangles that should cover an image exactly once.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CoverError {
    /// Rectangle `index` reaches outside the image.
    Outside { index: usize },
    /// Rectangles `first` and `second` share pixels.
    Overlap { first: usize, second: usize },
    /// No rectangle covers pixel (x, y) (the first such pixel, row by row).
    Gap { x: u32, y: u32 },
}

/// Checks that `rects` cover `image` exactly once: each inside it, no two sharing a pixel, and
/// together as many pixels as it has.
pub fn check_cover(image: &Rect, rects: &[Rect]) -> Result<(), CoverError> {
    if let Some(index) = rects.iter().position(|r| !r.is_inside(image)) {
        return Err(CoverError::Outside { index });
    }
    // Sorted by their top-left corner, a rectangle can only overlap those after it that start
    // above its bottom row; the sweep stops at the first one below.
    let mut order: Vec<usize> = (0..rects.len()).collect();
    order.sort_by_key(|&i| (rects[i].y0, rects[i].x0));
    for (at, &i) in order.iter().enumerate() {
        let later = order[at + 1..]
            .iter()
            .take_while(|&&j| rects[j].y0 < rects[i].y1);
        if let Some(&j) = later.into_iter().find(|&&j| rects[i].overlaps(&rects[j])) {
            let (first, second) = (i.min(j), i.max(j));
            return Err(CoverError::Overlap { first, second });
        }
    }
    let covered: u64 = rects.iter().map(Rect::pixels).sum();
    if covered == image.pixels() {
        return Ok(());
    }
    // Not overlapping and fewer pixels: find the first hole, row by row.
    for y in image.y0..image.y1 {
        let mut row: Vec<&Rect> = rects.iter().filter(|r| r.y0 <= y && y < r.y1).collect();
        row.sort_by_key(|r| r.x0);
        let mut x = image.x0;
        for r in row {
            if r.x0 > x {
                break;
            }
            x = r.x1;
        }
        if x < image.x1 {
            return Err(CoverError::Gap { x, y });
        }
    }
    unreachable!("rectangles inside the image, not overlapping, with fewer pixels leave a gap")
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn tiles_are_near_square_cells_of_a_grid() {
        assert_eq!(grid(100, 100, 4), Some((2, 2)));
        assert_eq!(grid(200, 100, 8), Some((2, 4)));
        assert_eq!(grid(37, 23, 7), Some((1, 7)), "a prime: bands of columns");
        assert_eq!(grid(37, 23, 1), Some((1, 1)));
        assert_eq!(grid(3, 2, 7), None, "7 columns of a 3-pixel-wide image");
        assert_eq!(
            tile(37, 23, 2, 3).unwrap(),
            Rect {
                x0: 24,
                y0: 0,
                x1: 37,
                y1: 23
            }
        );
    }

    #[test]
    fn bad_tiles_are_errors() {
        assert_eq!(tile(10, 10, 0, 0), Err(SplitError::NoTiles));
        assert_eq!(
            tile(10, 10, 3, 3),
            Err(SplitError::TileOutOfRange { k: 3, n: 3 })
        );
        assert!(
            tile(2, 2, 0, 5)
                .unwrap_err()
                .to_string()
                .contains("without an empty one")
        );
    }

    #[test]
    fn cover_errors_name_the_rectangles() {
        let image = Rect::image(10, 4);
        let tiles = split(10, 4, 4).unwrap();
        assert_eq!(check_cover(&image, &tiles), Ok(()));
        assert_eq!(
            check_cover(&image, &tiles[1..]),
            Err(CoverError::Gap { x: 0, y: 0 })
        );
        let mut twice = tiles.clone();
        twice.push(tiles[2]);
        assert_eq!(
            check_cover(&image, &twice),
            Err(CoverError::Overlap {
                first: 2,
                second: 4
            })
        );
        let outside = [Rect::image(11, 4)];
        assert_eq!(
            check_cover(&image, &outside),
            Err(CoverError::Outside { index: 0 })
        );
    }

    proptest! {
        /// Whatever the size and count, the tiles cover the image exactly once, none empty.
        #[test]
        fn tiles_cover_the_image_exactly_once(width in 1u32..200, height in 1u32..200, n in 1u32..70) {
            let Ok(tiles) = split(width, height, n) else {
                // Only when no grid of n cells fits.
                prop_assert!(grid(width, height, n).is_none());
                return Ok(());
            };
            prop_assert_eq!(tiles.len(), n as usize);
            prop_assert!(tiles.iter().all(|t| t.pixels() > 0));
            prop_assert_eq!(check_cover(&Rect::image(width, height), &tiles), Ok(()));
            // Checked pixel by pixel too, not only by the function under test.
            let mut count = vec![0u8; (width * height) as usize];
            for t in &tiles {
                for y in t.y0..t.y1 {
                    for x in t.x0..t.x1 {
                        count[(y * width + x) as usize] += 1;
                    }
                }
            }
            prop_assert!(count.iter().all(|&c| c == 1));
        }

        /// A tile left out is found as a gap, a tile given twice as an overlap.
        #[test]
        fn a_missing_or_doubled_tile_is_found(width in 1u32..100, height in 1u32..100, n in 2u32..30, pick in 0u32..1000) {
            let Ok(tiles) = split(width, height, n) else { return Ok(()); };
            let k = (pick % n) as usize;
            let mut missing = tiles.clone();
            missing.remove(k);
            let gap = check_cover(&Rect::image(width, height), &missing);
            prop_assert!(
                matches!(gap, Err(CoverError::Gap { x, y }) if x >= tiles[k].x0 && x < tiles[k].x1 && y >= tiles[k].y0 && y < tiles[k].y1),
                "{:?}", gap
            );
            let mut doubled = tiles.clone();
            doubled.push(tiles[k]);
            let overlap = check_cover(&Rect::image(width, height), &doubled);
            prop_assert!(matches!(overlap, Err(CoverError::Overlap { .. })), "{:?}", overlap);
        }
    }
}
