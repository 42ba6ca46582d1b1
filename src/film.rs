//! The film: the image being rendered, in linear RGB floats, with the number of samples averaged
//! into each pixel, written by the tracer's threads and readable by anyone (the viewer, a
//! progress display) while a pass is running. It also keeps which rows changed since a reader
//! last asked (one bit a row), so that a viewer copies only those. A film can also hold a window
//! of a larger image ([`Film::window`]), for rendering a tile of it.

use std::ops::Range;
use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};

use crate::color::Color;
use crate::tiles::Rect;
use rayon::prelude::*;

/// A `width × height` image, row 0 at the top. Each channel is an `f32` stored in an atomic, so
/// threads can write pixels while others read without locks; a reader may see a pixel from
/// before and its neighbour from after a write, never a torn channel.
#[derive(Debug)]
pub struct Film {
    width: u32,
    height: u32,
    /// Where the film's pixel (0, 0) lies in the image it is a window of, and that image's size
    /// (the film's own size, at (0, 0), for a whole image).
    origin: (u32, u32),
    image_size: (u32, u32),
    channels: Vec<AtomicU32>,
    /// Samples averaged into each pixel (0 where a coarse block was only painted over it).
    samples: Vec<AtomicU32>,
    /// Bumped whenever pixels change, so a viewer uploads only when there is something new.
    version: AtomicU64,
    /// One bit per row, set when the row's pixels changed and cleared when a reader takes it.
    changed_rows: Vec<AtomicU64>,
}

impl Film {
    /// The memory a `width × height` film takes.
    pub fn memory_bytes(width: u32, height: u32) -> u64 {
        u64::from(width) * u64::from(height) * 4 * std::mem::size_of::<AtomicU32>() as u64
    }

    pub fn new(width: u32, height: u32) -> Film {
        Film::window(width, height, Rect::image(width, height))
    }

    /// A film for the pixels `rect` of an `image_width × image_height` image: its pixel (x, y)
    /// is the image's (rect.x0 + x, rect.y0 + y).
    pub fn window(image_width: u32, image_height: u32, rect: Rect) -> Film {
        let (width, height) = (rect.width(), rect.height());
        let n = width as usize * height as usize;
        Film {
            width,
            height,
            origin: (rect.x0, rect.y0),
            image_size: (image_width, image_height),
            channels: zeroed_atomics(n * 3),
            samples: zeroed_atomics(n),
            version: AtomicU64::new(0),
            changed_rows: (0..height.div_ceil(64))
                .map(|_| AtomicU64::new(0))
                .collect(),
        }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Where the film's pixel (0, 0) lies in its image.
    pub fn origin(&self) -> (u32, u32) {
        self.origin
    }

    /// The size of the image the film is a window of.
    pub fn image_size(&self) -> (u32, u32) {
        self.image_size
    }

    fn pixel(&self, x: u32, y: u32) -> usize {
        y as usize * self.width as usize + x as usize
    }

    fn index(&self, x: u32, y: u32) -> usize {
        self.pixel(x, y) * 3
    }

    pub fn get(&self, x: u32, y: u32) -> Color {
        let i = self.index(x, y);
        Color::new(
            f32::from_bits(self.channels[i].load(Ordering::Relaxed)),
            f32::from_bits(self.channels[i + 1].load(Ordering::Relaxed)),
            f32::from_bits(self.channels[i + 2].load(Ordering::Relaxed)),
        )
    }

    pub fn set(&self, x: u32, y: u32, c: Color) {
        let i = self.index(x, y);
        self.channels[i].store(c.x.to_bits(), Ordering::Relaxed);
        self.channels[i + 1].store(c.y.to_bits(), Ordering::Relaxed);
        self.channels[i + 2].store(c.z.to_bits(), Ordering::Relaxed);
    }

    /// Sets pixel (x, y) to colour `c`, the mean of `samples` samples.
    pub fn put(&self, x: u32, y: u32, c: Color, samples: u32) {
        self.set(x, y, c);
        self.samples[self.pixel(x, y)].store(samples, Ordering::Relaxed);
    }

    /// Paints the block of `size × size` pixels whose top-left corner is (x, y), clipped at the
    /// image's edges, with the colour of the one sample taken at (x, y): that pixel now holds one
    /// sample, the others none.
    pub fn fill_block(&self, x: u32, y: u32, size: u32, c: Color) {
        for by in y..(y + size).min(self.height) {
            for bx in x..(x + size).min(self.width) {
                self.set(bx, by, c);
                self.samples[self.pixel(bx, by)].store(0, Ordering::Relaxed);
            }
        }
        self.samples[self.pixel(x, y)].store(1, Ordering::Relaxed);
    }

    /// Samples averaged into pixel (x, y) so far.
    pub fn samples(&self, x: u32, y: u32) -> u32 {
        self.samples[self.pixel(x, y)].load(Ordering::Relaxed)
    }

    /// Adds one sample of colour `c` to pixel (x, y): the pixel becomes the mean of its samples.
    /// Only one thread at a time may add to a pixel.
    pub fn add_sample(&self, x: u32, y: u32, c: Color) {
        let n = self.samples(x, y);
        let mean = self.get(x, y);
        self.set(x, y, mean + (c - mean) / (n + 1) as f32);
        self.samples[self.pixel(x, y)].store(n + 1, Ordering::Relaxed);
    }

    /// Marks the whole image as changed.
    pub fn touch(&self) {
        self.touch_rows(0..self.height);
    }

    /// Marks `rows` (clipped to the image) as changed, after writing their pixels. The renderer
    /// calls it once per band of rows, not per pixel: a few atomic operations.
    pub fn touch_rows(&self, rows: Range<u32>) {
        let rows = rows.start.min(self.height)..rows.end.min(self.height);
        let mut row = rows.start;
        while row < rows.end {
            // The rows of this 64-row word, as bits.
            let (word, first) = (row / 64, row % 64);
            let last = (rows.end - word * 64).min(64);
            let bits = (u64::MAX >> (64 - (last - first))) << first;
            self.changed_rows[word as usize].fetch_or(bits, Ordering::Release);
            row = (word + 1) * 64;
        }
        self.version.fetch_add(1, Ordering::Release);
    }

    /// The rows changed since the last call, as ascending runs of rows, and forgets them: a row
    /// written after this call is in the next one's answer.
    pub fn take_changed_rows(&self) -> Vec<Range<u32>> {
        let mut runs: Vec<Range<u32>> = Vec::new();
        for (word, bits) in self.changed_rows.iter().enumerate() {
            let mut bits = bits.swap(0, Ordering::Acquire);
            while bits != 0 {
                let row = word as u32 * 64 + bits.trailing_zeros();
                bits &= bits - 1;
                match runs.last_mut() {
                    Some(run) if run.end == row => run.end += 1,
                    _ => runs.push(row..row + 1),
                }
            }
        }
        runs
    }

    pub fn version(&self) -> u64 {
        self.version.load(Ordering::Acquire)
    }

    /// A copy of the pixels, row by row.
    pub fn pixels(&self) -> Vec<Color> {
        // On all threads, each pixel written once: a large film takes milliseconds to copy.
        let width = self.width.max(1);
        (0..self.width * self.height)
            .into_par_iter()
            .map(|i| self.get(i % width, i / width))
            .collect()
    }

    /// A copy of the pixels `rect` of the image, row by row: a rectangle inside the film's
    /// window, in the image's coordinates.
    pub fn pixels_in(&self, rect: Rect) -> Vec<Color> {
        let (left, top) = self.origin;
        (rect.y0 - top..rect.y1 - top)
            .flat_map(|y| (rect.x0 - left..rect.x1 - left).map(move |x| (x, y)))
            .map(|(x, y)| self.get(x, y))
            .collect()
    }
}

/// `n` atomics holding 0, in memory allocated zeroed: a large allocation is fresh pages the
/// system zeroes itself as they are first touched, so a film costs nothing to clear and its
/// pages are touched by the threads that trace them, not all by the one that made it.
fn zeroed_atomics(n: usize) -> Vec<AtomicU32> {
    let zeroed = Box::<[AtomicU32]>::new_zeroed_slice(n);
    // SAFETY: an `AtomicU32` has the bit validity of a `u32`; all-zero bits are 0.
    unsafe { zeroed.assume_init() }.into_vec()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_film_is_black_and_unsampled_and_pixels_copies_it_row_by_row() {
        // Large enough that its arrays are fresh pages from the system, zeroed by it.
        let (width, height) = (701, 499);
        let film = Film::new(width, height);
        assert!(film.pixels().iter().all(|&c| c == Color::ZERO));
        assert!((0..height).all(|y| (0..width).all(|x| film.samples(x, y) == 0)));
        let colour = |x: u32, y: u32| Color::new(x as f32, y as f32, (x ^ y) as f32);
        for (x, y) in [(0, 0), (700, 0), (0, 498), (700, 498), (350, 250)] {
            film.set(x, y, colour(x, y));
        }
        let pixels = film.pixels();
        assert_eq!(pixels.len(), (width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                assert_eq!(
                    pixels[(y * width + x) as usize],
                    film.get(x, y),
                    "({x}, {y})"
                );
            }
        }
        assert_eq!(pixels[(498 * width + 700) as usize], colour(700, 498));
    }

    #[test]
    fn changed_rows_are_given_once_as_runs() {
        let film = Film::new(3, 200);
        assert!(film.take_changed_rows().is_empty());
        let before = film.version();
        film.touch_rows(10..20);
        film.touch_rows(60..70);
        film.touch_rows(70..72);
        film.touch_rows(190..260);
        assert!(film.version() > before);
        assert_eq!(film.take_changed_rows(), vec![10..20, 60..72, 190..200]);
        assert!(film.take_changed_rows().is_empty(), "taken once");
        film.touch_rows(127..129);
        film.touch_rows(5..5);
        assert_eq!(
            film.take_changed_rows(),
            std::iter::once(127..129).collect::<Vec<_>>()
        );
        film.touch();
        assert_eq!(
            film.take_changed_rows(),
            std::iter::once(0..200).collect::<Vec<_>>()
        );
    }
}
