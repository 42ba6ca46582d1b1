//! The figure's legend: a dark box in the top-left corner with a title and, for each kind of
//! line, a swatch of its colour and what it means, written in an 8×8 bitmap font scaled to the
//! image.

use strum::IntoEnumIterator;

use super::layer::{Layer, line_width};
use super::segments::SegmentKind;

const BACKGROUND: [u8; 3] = [24, 24, 24];
const TEXT: [u8; 3] = [235, 235, 235];
/// A glyph's side in font pixels.
const GLYPH: u32 = 8;

/// The legend's layout on an image `height` pixels tall: its scale (image pixels per font pixel),
/// its margin and padding, the swatches' length and the rows' height, in image pixels.
struct Layout {
    scale: u32,
    pad: u32,
    swatch: u32,
    row: u32,
}

impl Layout {
    fn new(height: u32) -> Layout {
        let scale = (height / 600).max(1);
        Layout {
            scale,
            pad: 6 * scale,
            swatch: 20 * scale,
            row: 10 * scale,
        }
    }

    /// The text of each row: the title, then each kind's meaning.
    fn rows(title: &str) -> Vec<(Option<SegmentKind>, String)> {
        let kinds = SegmentKind::iter().map(|k| (Some(k), k.meaning().to_string()));
        std::iter::once((None, title.to_string()))
            .chain(kinds)
            .collect()
    }

    /// The box `(left, top, right, bottom)`, right and bottom excluded.
    fn area(&self, rows: &[(Option<SegmentKind>, String)]) -> (u32, u32, u32, u32) {
        let chars = rows.iter().map(|(kind, text)| {
            let indent = if kind.is_some() {
                self.swatch + self.pad
            } else {
                0
            };
            indent + text.chars().count() as u32 * GLYPH * self.scale
        });
        let width = 2 * self.pad + chars.max().unwrap_or(0);
        let height = 2 * self.pad + rows.len() as u32 * self.row;
        (self.pad, self.pad, self.pad + width, self.pad + height)
    }
}

/// Where the legend titled `title` lies on a `width × height` figure: `(left, top, right,
/// bottom)` in pixels, right and bottom excluded, clipped to the image.
pub fn area((width, height): (u32, u32), title: &str) -> (u32, u32, u32, u32) {
    let (l, t, r, b) = Layout::new(height).area(&Layout::rows(title));
    (l.min(width), t.min(height), r.min(width), b.min(height))
}

/// Draws the legend titled `title` on `image`.
pub fn draw(image: &mut Layer, title: &str) {
    let layout = Layout::new(image.height);
    let rows = Layout::rows(title);
    let (left, top, right, bottom) = area((image.width, image.height), title);
    image.fill((left, top), (right, bottom), BACKGROUND);
    let thickness = line_width(image.height);
    for (i, (kind, text)) in rows.iter().enumerate() {
        let y = top + layout.pad + i as u32 * layout.row;
        let mut x = left + layout.pad;
        if let Some(kind) = kind {
            let middle = y + GLYPH * layout.scale / 2;
            let from = (x, middle - thickness / 2);
            image.fill(from, (x + layout.swatch, from.1 + thickness), kind.color());
            x += layout.swatch + layout.pad;
        }
        write(image, (x, y), text, layout.scale);
    }
}

/// Writes `text` (ASCII; anything else shows as `?`) with its top-left corner at `(x, y)`.
fn write(image: &mut Layer, (x, y): (u32, u32), text: &str, scale: u32) {
    for (i, c) in text.chars().enumerate() {
        let code = if c.is_ascii() {
            c as usize
        } else {
            '?' as usize
        };
        let glyph = font8x8::legacy::BASIC_LEGACY[code];
        let left = x + i as u32 * GLYPH * scale;
        for (row, bits) in glyph.iter().enumerate() {
            for column in 0..GLYPH {
                if bits >> column & 1 == 1 {
                    let from = (left + column * scale, y + row as u32 * scale);
                    image.fill(from, (from.0 + scale, from.1 + scale), TEXT);
                }
            }
        }
    }
}
