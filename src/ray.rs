//! Rays: the half-lines `r(t) = origin + dir·t` that the tracer follows through the scene.

use glam::Vec3;

/// A ray `r(t) = origin + dir·t`. The direction is not necessarily unit length: eye rays use the
/// lecture's `dir_rc`, which reaches the image plane at `t = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    pub dir: Vec3,
}

impl Ray {
    pub fn new(origin: Vec3, dir: Vec3) -> Self {
        Ray { origin, dir }
    }

    /// The point reached at parameter `t`.
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + self.dir * t
    }
}

/// Moves a point off a surface along its normal so that a ray leaving it does not hit the same
/// surface again ("shadow acne"). The offset grows with the point's magnitude, because the float
/// error of a computed hit point does.
pub fn offset_origin(point: Vec3, normal: Vec3) -> Vec3 {
    const RELATIVE_EPS: f32 = 2e-4;
    let scale = 1.0 + point.abs().max_element();
    point + normal * (RELATIVE_EPS * scale)
}
