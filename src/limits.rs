//! How large the numbers of a scene and its images may be: images of at most
//! [`MAX_IMAGE_SIDE`] pixels a side ([`check_image_size`]). raylab computes in single precision, whose largest
//! number is about 3.4·10³⁸, and its intersection tests square and multiply coordinates: a
//! sphere 10¹⁹ across would overflow to infinity and silently draw nothing. So coordinates and
//! sizes are held to ±[`MAX_COORDINATE`] and the near distance to [`NEAR_RANGE`], and the
//! readers refuse what lies outside with a message that says why.

use std::ops::RangeInclusive;

use glam::Vec3;

use crate::aabb::Aabb;

/// Largest magnitude of a coordinate, a size or an object's extent in the world. Squares and
/// products of a few such numbers stay far below the single-precision limit.
pub const MAX_COORDINATE: f32 = 1e15;

/// The near distance `N` from the eye to the image plane, in scene units. Much closer, the
/// eye rays' directions underflow; much farther, their products overflow.
pub const NEAR_RANGE: RangeInclusive<f32> = 1e-6..=1e6;

/// Whether every coordinate of `p` is a number within ±[`MAX_COORDINATE`].
pub fn within_range(p: Vec3) -> bool {
    p.abs().cmple(Vec3::splat(MAX_COORDINATE)).all()
}

/// Why a value is refused: what it is (`the sphere`) reaches `p`.
pub fn out_of_range_message(what: &str, p: Vec3) -> String {
    format!(
        "{what} reaches {}, beyond ±{MAX_COORDINATE:e}: {WHY}",
        short_vector(p)
    )
}

/// The reason behind [`MAX_COORDINATE`], for messages.
pub const WHY: &str = "raylab computes in single precision, where larger numbers overflow";

/// `[x, y, z]` with large and small numbers in scientific notation (`3e38`, not 39 digits).
pub fn short_vector(p: Vec3) -> String {
    let short = |x: f32| {
        if x != 0.0 && !(1e-3..1e6).contains(&x.abs()) {
            format!("{x:e}")
        } else {
            format!("{x}")
        }
    };
    format!("[{}, {}, {}]", short(p.x), short(p.y), short(p.z))
}

/// Checks that the world-space box `bounds` of `what` lies within ±[`MAX_COORDINATE`].
pub fn check_bounds(what: &str, bounds: &Aabb) -> Result<(), String> {
    for corner in [bounds.min, bounds.max] {
        if !within_range(corner) {
            return Err(out_of_range_message(what, corner));
        }
    }
    Ok(())
}

/// Largest image side, to keep an absurd setting from allocating gigabytes.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Checks that raylab renders images of `width` × `height` pixels: at least 1×1, sides at most
/// [`MAX_IMAGE_SIDE`]. The message says what is allowed.
pub fn check_image_size(width: u32, height: u32) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err(format!(
            "image size must be at least 1×1, got {width}×{height}"
        ));
    }
    if width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE {
        return Err(format!(
            "image sides must be at most {MAX_IMAGE_SIDE}, got {width}×{height}"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_past_the_limit_or_not_numbers_are_out_of_range() {
        assert!(within_range(Vec3::splat(MAX_COORDINATE)));
        assert!(!within_range(Vec3::new(0.0, -2e15, 0.0)));
        assert!(!within_range(Vec3::new(f32::NAN, 0.0, 0.0)));
        assert!(!within_range(Vec3::new(f32::INFINITY, 0.0, 0.0)));
    }

    #[test]
    fn large_numbers_are_shown_short() {
        assert_eq!(short_vector(Vec3::new(3e38, -0.5, 0.0)), "[3e38, -0.5, 0]");
    }

    #[test]
    fn boxes_are_checked_at_both_corners() {
        let inside = Aabb::new(Vec3::splat(-1e14), Vec3::splat(1e14));
        assert!(check_bounds("the box", &inside).is_ok());
        let beyond = Aabb::new(Vec3::splat(-1.0), Vec3::new(1.0, 3e38, 1.0));
        let message = check_bounds("the sphere", &beyond).unwrap_err();
        assert!(message.starts_with("the sphere reaches"), "{message}");
        assert!(message.contains("single precision"), "{message}");
    }
}
