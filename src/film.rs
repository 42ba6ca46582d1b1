//! The film: the image being rendered, in linear RGB floats, with the number of samples averaged
//! into each pixel, written by the tracer's threads and readable by anyone (the viewer, a
//! progress display) while a pass is running.

use std::sync::atomic::{AtomicU32, AtomicU64, Ordering};

use crate::color::Color;

/// A `width × height` image, row 0 at the top. Each channel is an `f32` stored in an atomic, so
/// threads can write pixels while others read without locks; a reader may see a pixel from
/// before and its neighbour from after a write, never a torn channel.
#[derive(Debug)]
pub struct Film {
    width: u32,
    height: u32,
    channels: Vec<AtomicU32>,
    /// Samples averaged into each pixel (0 where a coarse block was only painted over it).
    samples: Vec<AtomicU32>,
    /// Bumped whenever pixels change, so a viewer uploads only when there is something new.
    version: AtomicU64,
}

impl Film {
    /// The memory a `width × height` film takes.
    pub fn memory_bytes(width: u32, height: u32) -> u64 {
        u64::from(width) * u64::from(height) * 4 * std::mem::size_of::<AtomicU32>() as u64
    }

    pub fn new(width: u32, height: u32) -> Film {
        let n = width as usize * height as usize;
        Film {
            width,
            height,
            channels: (0..n * 3).map(|_| AtomicU32::new(0)).collect(),
            samples: (0..n).map(|_| AtomicU32::new(0)).collect(),
            version: AtomicU64::new(0),
        }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
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

    /// Marks the image as changed (the renderer calls it once per band of rows, not per pixel).
    pub fn touch(&self) {
        self.version.fetch_add(1, Ordering::Release);
    }

    pub fn version(&self) -> u64 {
        self.version.load(Ordering::Acquire)
    }

    /// A copy of the pixels, row by row.
    pub fn pixels(&self) -> Vec<Color> {
        (0..self.height)
            .flat_map(|y| (0..self.width).map(move |x| (x, y)))
            .map(|(x, y)| self.get(x, y))
            .collect()
    }
}
