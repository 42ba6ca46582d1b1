//! The pinhole camera of the lecture: the eye, the axes `u, v, n`, the near distance `N` and the
//! view angle `θ`, and the eye ray through each pixel; and the camera that frames a scene
//! whose file gives none ([`frame`]).

use glam::{Vec2, Vec3};

use crate::aabb::Aabb;
use crate::limits;
use crate::ray::Ray;

/// The camera as a scene file describes it: where the eye is, what it looks at, which way is up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    pub eye: Vec3,
    pub look_at: Vec3,
    pub up: Vec3,
    /// Vertical view angle `θ` in degrees.
    pub view_angle: f32,
    /// Distance `N` from the eye to the image plane.
    pub near: f32,
}

impl Default for CameraSpec {
    fn default() -> Self {
        CameraSpec {
            eye: Vec3::new(0.0, 0.0, 5.0),
            look_at: Vec3::ZERO,
            up: Vec3::Y,
            view_angle: 45.0,
            near: 1.0,
        }
    }
}

/// Smallest radius [`CameraSpec::framing`] fits in view, so that a point-sized scene still leaves
/// the eye away from the look-at point.
const MIN_FRAMING_RADIUS: f32 = 1e-3;

/// Where the eye of [`frame`] looks from, seen from the scene's centre: to the right (+x), above
/// (+y) and in front (+z, where the default camera stands), a three-quarter view.
pub const THREE_QUARTER_VIEW: Vec3 = Vec3::new(0.6, 0.5, 1.0);

impl CameraSpec {
    /// The camera looking the same way at the centre of `bounds`, just far enough that the box's
    /// bounding sphere fits the view of an image `aspect` wide per unit of height, its image plane
    /// (which eye rays see beyond) brought nearer than the sphere when the camera's near distance
    /// would cut into it. `None` for an empty or infinite box.
    pub fn framing(&self, bounds: &Aabb, aspect: f32) -> Option<CameraSpec> {
        if !bounds.is_finite() || bounds.is_empty() {
            return None;
        }
        let radius = (bounds.extent().length() * 0.5).max(MIN_FRAMING_RADIUS);
        let half_v = self.view_angle.to_radians() * 0.5;
        let half_h = (half_v.tan() * aspect.max(1e-3)).atan();
        let distance = radius / half_v.min(half_h).sin();
        let back = (self.eye - self.look_at).try_normalize().unwrap_or(Vec3::Z);
        let in_front = (distance - radius) * 0.5;
        Some(CameraSpec {
            eye: bounds.center() + back * distance,
            look_at: bounds.center(),
            near: self.near.min(in_front).max(*limits::NEAR_RANGE.start()),
            ..*self
        })
    }
}

/// The default camera of a scene whose format has none: a three-quarter view
/// ([`THREE_QUARTER_VIEW`]) of the centre of `bounds` (the scene's finite objects: infinite planes
/// left out), far enough that their bounding sphere fits an image `aspect` wide per unit of
/// height. A scene with nothing finite gets [`CameraSpec::default`].
pub fn frame(bounds: &Aabb, aspect: f32) -> Camera {
    let three_quarter = CameraSpec {
        eye: THREE_QUARTER_VIEW,
        look_at: Vec3::ZERO,
        ..CameraSpec::default()
    };
    three_quarter
        .framing(bounds, aspect)
        .and_then(|spec| Camera::new(spec).ok())
        .unwrap_or_default()
}

/// Why a camera cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraError {
    EyeAtLookAt,
    /// The up vector is parallel to the view direction, so `u = up × n` is undefined.
    UpParallelToView,
    ViewAngle(f32),
    /// Outside [`limits::NEAR_RANGE`].
    Near(f32),
    /// The eye or the look-at point lies past [`limits::MAX_COORDINATE`].
    Eye(Vec3),
    LookAt(Vec3),
}

impl std::fmt::Display for CameraError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CameraError::EyeAtLookAt => write!(f, "the eye and the look-at point coincide"),
            CameraError::UpParallelToView => {
                write!(
                    f,
                    "the up vector is parallel to the view direction (or zero)"
                )
            }
            CameraError::ViewAngle(a) => {
                write!(f, "view angle must be between 0 and 180 degrees, got {a}")
            }
            CameraError::Near(n) => write!(
                f,
                "near distance must be from {:e} to {:e}, got {n}",
                limits::NEAR_RANGE.start(),
                limits::NEAR_RANGE.end()
            ),
            CameraError::Eye(p) => write!(f, "{}", limits::out_of_range_message("the eye", *p)),
            CameraError::LookAt(p) => {
                write!(
                    f,
                    "{}",
                    limits::out_of_range_message("the look-at point", *p)
                )
            }
        }
    }
}

impl std::error::Error for CameraError {}

/// The centre of a pixel, as the offset within it that [`Camera::eye_ray`] takes.
pub const PIXEL_CENTRE: (f32, f32) = (0.5, 0.5);

/// A camera ready to shoot rays: the eye and the orthonormal axes `u` (right), `v` (up) and `n`
/// (from the look-at point back towards the eye), with the image plane's half sizes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub spec: CameraSpec,
    pub eye: Vec3,
    pub u: Vec3,
    pub v: Vec3,
    pub n: Vec3,
    /// Near distance `N`.
    pub near: f32,
    /// `H = N·tan(θ/2)`: half the image plane's height.
    pub half_height: f32,
}

impl Default for Camera {
    /// The camera of [`CameraSpec::default`].
    fn default() -> Camera {
        let spec = CameraSpec::default();
        let half_height = spec.near * (spec.view_angle.to_radians() * 0.5).tan();
        Camera {
            spec,
            eye: spec.eye,
            u: Vec3::X,
            v: Vec3::Y,
            n: Vec3::Z,
            near: spec.near,
            half_height,
        }
    }
}

impl Camera {
    pub fn new(spec: CameraSpec) -> Result<Camera, CameraError> {
        if !(spec.view_angle > 0.0 && spec.view_angle < 180.0) {
            return Err(CameraError::ViewAngle(spec.view_angle));
        }
        if !limits::NEAR_RANGE.contains(&spec.near) {
            return Err(CameraError::Near(spec.near));
        }
        if !limits::within_range(spec.eye) {
            return Err(CameraError::Eye(spec.eye));
        }
        if !limits::within_range(spec.look_at) {
            return Err(CameraError::LookAt(spec.look_at));
        }
        let n = (spec.eye - spec.look_at)
            .try_normalize()
            .ok_or(CameraError::EyeAtLookAt)?;
        let u = spec
            .up
            .cross(n)
            .try_normalize()
            .filter(|_| spec.up.cross(n).length() > 1e-6 * spec.up.length())
            .ok_or(CameraError::UpParallelToView)?;
        let v = n.cross(u);
        Ok(Camera {
            spec,
            eye: spec.eye,
            u,
            v,
            n,
            near: spec.near,
            half_height: spec.near * (spec.view_angle.to_radians() * 0.5).tan(),
        })
    }

    /// `dir_rc = −N·n + W(2c/nCols − 1)·u + H(2r/nRows − 1)·v`, with `W = H·aspect` and
    /// `aspect = nCols / nRows`. `r` and `c` are continuous: the centre of pixel (r, c) is
    /// (r + ½, c + ½), and row r = 0 is at the bottom of the image plane.
    pub fn dir_rc(&self, r: f32, c: f32, n_rows: u32, n_cols: u32) -> Vec3 {
        let h = self.half_height;
        let w = h * n_cols as f32 / n_rows as f32;
        -self.near * self.n
            + w * (2.0 * c / n_cols as f32 - 1.0) * self.u
            + h * (2.0 * r / n_rows as f32 - 1.0) * self.v
    }

    /// The eye ray `eye + dir_rc·t` through the point (r, c) of the image plane, reached at t = 1.
    pub fn ray(&self, r: f32, c: f32, n_rows: u32, n_cols: u32) -> Ray {
        Ray::new(self.eye, self.dir_rc(r, c, n_rows, n_cols))
    }

    /// The eye ray through the point `offset` of pixel (x, y) of a `width × height` image: x
    /// from the left, y from the top (like the offset within the pixel, which is in [0, 1)²;
    /// [`PIXEL_CENTRE`] is the centre). This is [`Self::ray`] at `r = (height − y) − offset.1`
    /// and `c = x + offset.0`, and the one place where a pixel becomes an eye ray: the renderer,
    /// the inspector and the viewer's picking all call it.
    #[inline]
    pub fn eye_ray(
        &self,
        (x, y): (u32, u32),
        offset: (f32, f32),
        (width, height): (u32, u32),
    ) -> Ray {
        // The lecture counts rows from the bottom of the image.
        let r = (height - y) as f32 - offset.1;
        let c = x as f32 + offset.0;
        self.ray(r, c, height, width)
    }

    /// Where the world point lands on the `width × height` image: x from the left, y from the
    /// top, in pixels, continuous (the centre of pixel (x, y) is (x + ½, y + ½)); `None` for a
    /// point not in front of the eye. The inverse of [`Self::dir_rc`].
    pub fn project(&self, point: Vec3, width: u32, height: u32) -> Option<Vec2> {
        let d = point - self.eye;
        let depth = d.dot(-self.n);
        if depth <= f32::EPSILON * d.length() {
            return None;
        }
        // On the image plane at distance N: (x, y) in units of the half sizes W and H.
        let h = self.half_height;
        let w = h * width as f32 / height as f32;
        let x = self.near * d.dot(self.u) / depth / w;
        let y = self.near * d.dot(self.v) / depth / h;
        let c = (x + 1.0) * width as f32 / 2.0;
        let r = (y + 1.0) * height as f32 / 2.0;
        Some(Vec2::new(c, height as f32 - r))
    }

    /// Where a ray in direction `dir` crosses an image of aspect ratio `aspect` (width over
    /// height) standing on the image plane, as tall as the view and centred: texture
    /// coordinates in [0, 1]² (v up), or `None` if the ray passes beside the image or points
    /// away from the plane. For an eye ray, that is the point of the image behind its pixel.
    pub fn backdrop_uv(&self, dir: Vec3, aspect: f32) -> Option<Vec2> {
        let depth = dir.dot(-self.n);
        if depth <= f32::EPSILON * dir.length() {
            return None;
        }
        // On the image plane at distance N, in units of the half height H.
        let y = self.near * dir.dot(self.v) / depth / self.half_height;
        let x = self.near * dir.dot(self.u) / depth / (self.half_height * aspect);
        let uv = (Vec2::new(x, y) + 1.0) * 0.5;
        (uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()).then_some(uv)
    }

    /// The part of the segment `a → b` in front of the image plane, projected as by
    /// [`Self::project`]: its two ends in pixels, or `None` if all of it is behind.
    pub fn project_segment(
        &self,
        a: Vec3,
        b: Vec3,
        width: u32,
        height: u32,
    ) -> Option<(Vec2, Vec2)> {
        let depth = |p: Vec3| (p - self.eye).dot(-self.n);
        let (da, db) = (depth(a), depth(b));
        if da < self.near && db < self.near {
            return None;
        }
        // Clip the end behind the image plane to where the segment crosses it.
        let crossing = |from: Vec3, d_from: f32, to: Vec3, d_to: f32| {
            from + (to - from) * ((self.near - d_from) / (d_to - d_from))
        };
        let a = if da < self.near {
            crossing(a, da, b, db)
        } else {
            a
        };
        let b = if db < self.near {
            crossing(b, db, a, da)
        } else {
            b
        };
        Some((
            self.project(a, width, height)?,
            self.project(b, width, height)?,
        ))
    }
}
