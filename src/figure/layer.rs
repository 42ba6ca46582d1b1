//! The figure as a layer of pixels over the observer's render ([`Layer`]): what it paints and
//! what it leaves clear, and how wide its lines are.

use crate::srgb_image::SrgbImage;

/// The width in pixels of the figure's lines on an image `height` pixels tall: 3 up to
/// 768 rows, then growing with the height.
pub fn line_width(height: u32) -> u32 {
    (height / 256).max(3)
}

/// What the figure draws over the observer's render: the pixels of the image plane, the lines,
/// the markers and the legend, the rest left clear.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    pub width: u32,
    pub height: u32,
    /// Row by row from the top; `None` where the render shows through.
    pub pixels: Vec<Option<[u8; 3]>>,
}

impl Layer {
    /// The layer over `image`, which has its size.
    pub fn over(&self, image: &SrgbImage) -> SrgbImage {
        let pixels = self.pixels.iter().zip(&image.pixels);
        let pixels = pixels.map(|(top, below)| top.unwrap_or(*below)).collect();
        SrgbImage::new(image.width, image.height, pixels)
    }

    /// Paints pixel `i` (row by row).
    pub fn paint(&mut self, i: usize, color: [u8; 3]) {
        self.pixels[i] = Some(color);
    }

    /// Fills the rectangle from `(x0, y0)` to `(x1, y1)` (excluded), clipped to the layer.
    pub fn fill(&mut self, (x0, y0): (u32, u32), (x1, y1): (u32, u32), color: [u8; 3]) {
        for y in y0..y1.min(self.height) {
            for x in x0..x1.min(self.width) {
                self.paint((y * self.width + x) as usize, color);
            }
        }
    }
}
