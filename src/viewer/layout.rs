//! Where the image sits in the window: the whole view area when the image's size follows it (the
//! [`Resolution::Fit`] mode), else the largest rectangle of the image's aspect that fits the
//! free area (letterboxing), in whole physical pixels; the way back from a cursor position to
//! a point or a pixel of the image, and the way from a point of the image to the window.

/// Largest side of the window, in logical pixels, that the viewer asks the window system for:
/// X11 holds sizes in 16 bits, and no GPU draws into a surface much larger. The window's
/// physical pixels are checked against the GPU's own limit once it is known
/// ([`check_window_size`]).
pub const MAX_WINDOW_SIDE: u32 = 16384;

/// Checks a window of `width × height` pixels against the largest side `max_side` (logical
/// pixels against [`MAX_WINDOW_SIDE`], or physical ones against a GPU's largest surface); the
/// message says what is allowed, naming `whose` limit it is.
pub fn check_window_size(
    width: u32,
    height: u32,
    max_side: u32,
    whose: &str,
) -> Result<(), String> {
    if width == 0 || height == 0 || width > max_side || height > max_side {
        return Err(format!(
            "a window of {width}×{height} pixels: sides must be from 1 to {max_side} ({whose})"
        ));
    }
    Ok(())
}

/// How the viewer chooses the image's size (the resolution control).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolution {
    /// The view area's physical pixels: the image fills the window beside the panels, and a
    /// resized window renders at its new size.
    Fit,
    /// A fixed N×N image (width and height kept equal), letterboxed.
    Square,
    /// A fixed W×H image, letterboxed.
    Free,
}

impl Resolution {
    /// The mode the viewer starts in: fit, unless the command line gave a size (`--size`,
    /// `--width`, `--height`), square when it gave equal sides.
    pub fn at_start(width: Option<u32>, height: Option<u32>) -> Resolution {
        match (width, height) {
            (None, None) => Resolution::Fit,
            (w, h) if w == h => Resolution::Square,
            _ => Resolution::Free,
        }
    }
}

/// A rectangle in physical pixels, `x, y` its top-left corner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelRect {
    pub x: f32,
    pub y: f32,
    pub width: f32,
    pub height: f32,
}

impl PixelRect {
    pub const ZERO: PixelRect = PixelRect {
        x: 0.0,
        y: 0.0,
        width: 0.0,
        height: 0.0,
    };

    pub fn is_empty(&self) -> bool {
        !(self.width >= 1.0 && self.height >= 1.0)
    }
}

/// The largest rectangle with the aspect of a `image_width × image_height` image that fits in
/// `area`, centred, with whole-pixel position and size (so nearest sampling is exact).
pub fn letterbox(area: PixelRect, image_width: u32, image_height: u32) -> PixelRect {
    if area.is_empty() || image_width == 0 || image_height == 0 {
        return PixelRect {
            x: area.x,
            y: area.y,
            width: 0.0,
            height: 0.0,
        };
    }
    let aspect = image_width as f32 / image_height as f32;
    let (width, height) = if area.width / area.height > aspect {
        (area.height * aspect, area.height)
    } else {
        (area.width, area.width / aspect)
    };
    let (width, height) = (width.floor().max(1.0), height.floor().max(1.0));
    PixelRect {
        x: (area.x + (area.width - width) / 2.0).round(),
        y: (area.y + (area.height - height) / 2.0).round(),
        width,
        height,
    }
}

/// The whole physical pixels of `area` (its edges rounded): where a fitted image goes, and that
/// image's size.
pub fn whole_pixels(area: PixelRect) -> PixelRect {
    let (x, y) = (area.x.round(), area.y.round());
    PixelRect {
        x,
        y,
        width: ((area.x + area.width).round() - x).max(0.0),
        height: ((area.y + area.height).round() - y).max(0.0),
    }
}

/// The image point (continuous, `x` right and `y` down, in image pixels) shown at window
/// position `(px, py)`, or `None` outside the image.
pub fn image_point(
    image_rect: PixelRect,
    image_width: u32,
    image_height: u32,
    px: f32,
    py: f32,
) -> Option<(f32, f32)> {
    if image_rect.is_empty() {
        return None;
    }
    let u = (px - image_rect.x) / image_rect.width;
    let v = (py - image_rect.y) / image_rect.height;
    ((0.0..1.0).contains(&u) && (0.0..1.0).contains(&v))
        .then_some((u * image_width as f32, v * image_height as f32))
}

/// The image pixel (`x` right and `y` down) shown at window position `(px, py)`, or `None`
/// outside the image.
pub fn image_pixel(
    image_rect: PixelRect,
    image_width: u32,
    image_height: u32,
    px: f32,
    py: f32,
) -> Option<(u32, u32)> {
    let (x, y) = image_point(image_rect, image_width, image_height, px, py)?;
    Some((
        (x as u32).min(image_width - 1),
        (y as u32).min(image_height - 1),
    ))
}

/// The window position (physical pixels) where image point `(x, y)` is shown.
pub fn window_point(
    image_rect: PixelRect,
    image_width: u32,
    image_height: u32,
    (x, y): (f32, f32),
) -> (f32, f32) {
    (
        image_rect.x + x * image_rect.width / image_width.max(1) as f32,
        image_rect.y + y * image_rect.height / image_height.max(1) as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(x: f32, y: f32, width: f32, height: f32) -> PixelRect {
        PixelRect {
            x,
            y,
            width,
            height,
        }
    }

    #[test]
    fn a_wide_area_gets_bars_left_and_right() {
        let image_rect = letterbox(rect(0.0, 0.0, 400.0, 200.0), 100, 100);
        assert_eq!(image_rect, rect(100.0, 0.0, 200.0, 200.0));
    }

    #[test]
    fn a_tall_area_gets_bars_above_and_below() {
        let image_rect = letterbox(rect(10.0, 20.0, 300.0, 500.0), 300, 150);
        assert_eq!(image_rect, rect(10.0, 195.0, 300.0, 150.0));
    }

    #[test]
    fn sizes_and_corners_are_whole_pixels() {
        let image_rect = letterbox(rect(0.5, 0.0, 333.0, 101.0), 7, 3);
        for v in [
            image_rect.x,
            image_rect.y,
            image_rect.width,
            image_rect.height,
        ] {
            assert_eq!(v, v.round(), "{image_rect:?}");
        }
        assert!(image_rect.width <= 333.0 && image_rect.height <= 101.0);
    }

    #[test]
    fn an_empty_area_shows_nothing() {
        assert!(letterbox(rect(0.0, 0.0, 0.0, 300.0), 10, 10).is_empty());
        assert!(letterbox(rect(0.0, 0.0, 300.0, 300.0), 0, 10).is_empty());
    }

    #[test]
    fn a_fitted_image_covers_the_area_in_whole_pixels() {
        let fitted = whole_pixels(rect(300.4, 0.0, 799.2, 690.6));
        assert_eq!(fitted, rect(300.0, 0.0, 800.0, 691.0));
        assert!(whole_pixels(rect(5.0, 5.0, 0.2, 10.0)).is_empty());
        assert_eq!(Resolution::at_start(None, None), Resolution::Fit);
    }

    #[test]
    fn window_sizes_are_checked_against_the_limit_named() {
        assert!(check_window_size(1100, 720, MAX_WINDOW_SIDE, "raylab's limit").is_ok());
        let error = check_window_size(16385, 100, 16384, "this GPU's largest surface").unwrap_err();
        assert_eq!(
            error,
            "a window of 16385×100 pixels: sides must be from 1 to 16384 (this GPU's largest \
             surface)"
        );
        assert!(check_window_size(0, 100, 16384, "x").is_err());
        assert_eq!(Resolution::at_start(Some(64), Some(64)), Resolution::Square);
        assert_eq!(Resolution::at_start(Some(64), None), Resolution::Free);
        assert_eq!(Resolution::at_start(None, Some(48)), Resolution::Free);
    }

    #[test]
    fn cursor_positions_map_to_image_pixels() {
        let image_rect = rect(100.0, 0.0, 200.0, 200.0);
        assert_eq!(
            image_point(image_rect, 10, 10, 100.0, 0.0),
            Some((0.0, 0.0))
        );
        assert_eq!(
            image_point(image_rect, 10, 10, 299.0, 199.0),
            Some((9.95, 9.95))
        );
        assert_eq!(image_point(image_rect, 10, 10, 99.0, 50.0), None);
        assert_eq!(image_point(image_rect, 10, 10, 300.0, 50.0), None);
    }

    #[test]
    fn cursor_positions_map_to_whole_pixels_and_back() {
        // A 4×2 image shown 25 times larger, 10 pixels from the window's corner.
        let image_rect = rect(10.0, 10.0, 100.0, 50.0);
        assert_eq!(image_pixel(image_rect, 4, 2, 10.0, 10.0), Some((0, 0)));
        assert_eq!(image_pixel(image_rect, 4, 2, 34.9, 34.9), Some((0, 0)));
        assert_eq!(image_pixel(image_rect, 4, 2, 35.0, 35.0), Some((1, 1)));
        assert_eq!(image_pixel(image_rect, 4, 2, 109.9, 59.9), Some((3, 1)));
        assert_eq!(image_pixel(image_rect, 4, 2, 110.0, 30.0), None);
        // The centre of each pixel lands back on that pixel.
        for (x, y) in [(0, 0), (3, 1), (2, 0)] {
            let (px, py) = window_point(image_rect, 4, 2, (x as f32 + 0.5, y as f32 + 0.5));
            assert_eq!(image_pixel(image_rect, 4, 2, px, py), Some((x, y)));
        }
        assert_eq!(window_point(image_rect, 4, 2, (4.0, 2.0)), (110.0, 60.0));
    }
}
