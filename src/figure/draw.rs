//! Drawing the figure over the observer's render ([`draw`]): the scene camera's image plane
//! with the traced image on it, then each line and marker, all tested against the observer's
//! depths so that surfaces hide what lies behind them (or, in x-ray, show it dashed), then the
//! legend. Lines are unlit and drawn in their kind's exact colour.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::layer::{Layer, line_width};
use super::legend;
use super::observer::view_depth;
use super::segments::{RayFigure, Segment, SegmentKind};
use crate::camera::{Camera, PIXEL_CENTRE};
use crate::srgb_image::SrgbImage;
use crate::whitted::EYE_RAY_T_MIN;

/// How the figure is drawn.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FigureStyle {
    /// Draw the hidden parts of lines dashed instead of leaving them out.
    pub xray: bool,
    /// Draw the lines of this node of the ray tree wider.
    pub highlight: Option<usize>,
    /// The legend's first line; no legend when `None`.
    pub legend: Option<String>,
}

/// The order kinds are drawn in, later ones over earlier ones: the short normals on top.
const DRAW_ORDER: [SegmentKind; 7] = [
    SegmentKind::ImagePlane,
    SegmentKind::ShadowBlocked,
    SegmentKind::Shadow,
    SegmentKind::Transmitted,
    SegmentKind::Reflected,
    SegmentKind::Eye,
    SegmentKind::Normal,
];

/// A line in front of a surface by less than this share of its depth still shows: the ends of
/// rays lie on the surfaces they hit.
const DEPTH_TOLERANCE: f32 = 2e-3;

/// The dashes of hidden lines in x-ray: this many pixels on, then as many off.
const DASH: f32 = 6.0;

/// The figure of `figure` seen by `observer`: its [`Layer`] ([`draw_layer`]) over `scene_view`,
/// the observer's render.
pub fn draw(
    figure: &RayFigure,
    observer: &Camera,
    scene_view: &SrgbImage,
    depths: &[f32],
    traced: &SrgbImage,
    style: &FigureStyle,
) -> SrgbImage {
    let size = (scene_view.width, scene_view.height);
    draw_layer(figure, observer, size, depths, traced, style).over(scene_view)
}

/// The figure's [`Layer`] on a `width × height` view of `observer`, with `depths` from
/// [`super::observer_depths`] for the same camera and size, and `traced` (the scene camera's
/// image, whose size the figure was made for) on the image plane.
pub fn draw_layer(
    figure: &RayFigure,
    observer: &Camera,
    (width, height): (u32, u32),
    depths: &[f32],
    traced: &SrgbImage,
    style: &FigureStyle,
) -> Layer {
    let mut canvas = Canvas {
        layer: Layer {
            width,
            height,
            pixels: vec![None; width as usize * height as usize],
        },
        depths: depths.to_vec(),
        camera: *observer,
    };
    canvas.image_plane(figure.image_plane, traced);
    let line = line_width(height);
    for kind in DRAW_ORDER {
        for segment in figure.segments.iter().filter(|s| s.kind == kind) {
            let wide = style.highlight.is_some() && segment.node == style.highlight;
            canvas.line(segment, line + 2 * u32::from(wide), style.xray);
        }
    }
    let radius = 2 * line;
    let light = SegmentKind::Shadow.color();
    for &at in &figure.lights {
        canvas.marker(at, radius, light, style.xray);
    }
    canvas.marker(figure.eye, radius, SegmentKind::Eye.color(), style.xray);
    if let Some(title) = &style.legend {
        legend::draw(&mut canvas.layer, title);
    }
    canvas.layer
}

/// The layer being drawn, the depth of what each pixel shows, and the camera it is seen by.
struct Canvas {
    layer: Layer,
    depths: Vec<f32>,
    camera: Camera,
}

impl Canvas {
    fn size(&self) -> (u32, u32) {
        (self.layer.width, self.layer.height)
    }

    /// Paints the image plane (corners top left, top right, bottom right, bottom left) with
    /// `traced` where it lies in front of the scene, each pixel the texel its centre sees.
    fn image_plane(&mut self, corners: [Vec3; 4], traced: &SrgbImage) {
        let (width, height) = self.size();
        let origin = corners[0];
        let (across, down) = (corners[1] - origin, corners[3] - origin);
        let normal = across.cross(down);
        let camera = self.camera;
        let rows = self.layer.pixels.par_chunks_mut(width as usize);
        rows.zip(self.depths.par_chunks_mut(width as usize))
            .enumerate()
            .for_each(|(y, (pixels, depths))| {
                for x in 0..width as usize {
                    let ray = camera.eye_ray((x as u32, y as u32), PIXEL_CENTRE, (width, height));
                    let t = (origin - ray.origin).dot(normal) / ray.dir.dot(normal);
                    let on_plane = ray.at(t) - origin;
                    let a = on_plane.dot(across) / across.length_squared();
                    let b = on_plane.dot(down) / down.length_squared();
                    let depth = view_depth(&camera, ray.at(t));
                    let inside = (0.0..1.0).contains(&a) && (0.0..1.0).contains(&b);
                    if t >= EYE_RAY_T_MIN && inside && depth < depths[x] {
                        let tx = (a * traced.width as f32) as u32;
                        let ty = (b * traced.height as f32) as u32;
                        pixels[x] =
                            Some(traced.at(tx.min(traced.width - 1), ty.min(traced.height - 1)));
                        depths[x] = depth;
                    }
                }
            });
    }

    /// The part of `a → b` at or beyond the camera's image plane: its ends, or `None` if all
    /// of it is nearer.
    fn clip(&self, a: Vec3, b: Vec3) -> Option<(Vec3, Vec3)> {
        let near = self.camera.near;
        let (da, db) = (view_depth(&self.camera, a), view_depth(&self.camera, b));
        if da < near && db < near {
            return None;
        }
        let crossing = |from: Vec3, d_from: f32, to: Vec3, d_to: f32| {
            from + (to - from) * ((near - d_from) / (d_to - d_from))
        };
        let a2 = if da < near { crossing(a, da, b, db) } else { a };
        let b2 = if db < near { crossing(b, db, a, da) } else { b };
        Some((a2, b2))
    }

    /// Draws `segment` `width` pixels wide where it lies in front of what the pixels show, and
    /// with `xray` dashed where it does not.
    fn line(&mut self, segment: &Segment, width: u32, xray: bool) {
        let (width_px, height_px) = self.size();
        let Some((a, b)) = self.clip(segment.from, segment.to) else {
            return;
        };
        let project = |p| self.camera.project(p, width_px, height_px);
        let (Some(pa), Some(pb)) = (project(a), project(b)) else {
            return;
        };
        let (za, zb) = (view_depth(&self.camera, a), view_depth(&self.camera, b));
        let length = pa.distance(pb);
        // Only the part over the image (and a line's width around it) is stepped along.
        let margin = Vec2::splat(width as f32);
        let (low, high) = (
            -margin,
            Vec2::new(width_px as f32, height_px as f32) + margin,
        );
        let Some((first, last)) = clip_2d(pa, pb, low, high) else {
            return;
        };
        let steps = (2.0 * length * (last - first)).ceil() as u32 + 1;
        let color = segment.kind.color();
        for k in 0..=steps {
            let s = first + (last - first) * k as f32 / steps as f32;
            let at = pa + (pb - pa) * s;
            // Depth is not linear across the screen, its reciprocal is.
            let depth = 1.0 / ((1.0 - s) / za + s / zb);
            let dashed_on = (s * length) % (2.0 * DASH) < DASH;
            self.stamp(at, width, depth, |hidden| {
                (!hidden || (xray && dashed_on)).then_some(color)
            });
        }
    }

    /// Draws a disc of `radius` pixels in `color` at the world point `at`, ringed in black.
    fn marker(&mut self, at: Vec3, radius: u32, color: [u8; 3], xray: bool) {
        let (width, height) = self.size();
        let depth = view_depth(&self.camera, at);
        let centre = match self.camera.project(at, width, height) {
            Some(centre) if depth >= self.camera.near => centre,
            _ => return,
        };
        let r = radius as f32;
        let ring = (r / 3.0).max(1.5);
        let xs = (centre.x - r).max(0.0) as u32..((centre.x + r).max(0.0) as u32).min(width);
        let ys = (centre.y - r).max(0.0) as u32..((centre.y + r).max(0.0) as u32).min(height);
        for y in ys {
            for x in xs.clone() {
                let off = Vec2::new(x as f32 + 0.5, y as f32 + 0.5).distance(centre);
                let i = y as usize * width as usize + x as usize;
                let hidden = depth > self.depths[i] * (1.0 + DEPTH_TOLERANCE);
                if off <= r && (xray || !hidden) {
                    self.layer
                        .paint(i, if off <= r - ring { color } else { [0, 0, 0] });
                }
            }
        }
    }

    /// Paints the pixels within a square `width` pixels wide centred on `at` (pixel
    /// coordinates, centres at half integers) with what `paint` gives for whether a surface
    /// hides the point at `depth` there.
    fn stamp(&mut self, at: Vec2, width: u32, depth: f32, paint: impl Fn(bool) -> Option<[u8; 3]>) {
        let (w, h) = self.size();
        let half = width as f32 * 0.5;
        let first = (at - 0.5 - half).ceil();
        let last = (at - 0.5 + half).floor();
        let xs = first.x.max(0.0) as i64..=last.x.min(w as f32 - 1.0) as i64;
        let ys = first.y.max(0.0) as i64..=last.y.min(h as f32 - 1.0) as i64;
        for y in ys {
            for x in xs.clone() {
                let i = y as usize * w as usize + x as usize;
                let hidden = depth > self.depths[i] * (1.0 + DEPTH_TOLERANCE);
                if let Some(color) = paint(hidden) {
                    self.layer.paint(i, color);
                }
            }
        }
    }
}

/// The part of the screen segment `a → b` inside the box from `low` to `high`, as the range of
/// its parameter (0 at `a`, 1 at `b`); `None` if it misses the box.
fn clip_2d(a: Vec2, b: Vec2, low: Vec2, high: Vec2) -> Option<(f32, f32)> {
    let d = b - a;
    let (mut first, mut last) = (0.0f32, 1.0f32);
    for axis in 0..2 {
        if d[axis] == 0.0 {
            if a[axis] < low[axis] || a[axis] > high[axis] {
                return None;
            }
            continue;
        }
        let t0 = (low[axis] - a[axis]) / d[axis];
        let t1 = (high[axis] - a[axis]) / d[axis];
        first = first.max(t0.min(t1));
        last = last.min(t0.max(t1));
    }
    (first <= last).then_some((first, last))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_screen_segment_is_clipped_to_the_box() {
        let (low, high) = (Vec2::ZERO, Vec2::new(10.0, 10.0));
        let clip = |a: [f32; 2], b: [f32; 2]| clip_2d(a.into(), b.into(), low, high);
        assert_eq!(clip([2.0, 2.0], [8.0, 8.0]), Some((0.0, 1.0)));
        assert_eq!(clip([-10.0, 5.0], [30.0, 5.0]), Some((0.25, 0.5)));
        assert_eq!(clip([-10.0, -10.0], [-1.0, 20.0]), None);
        assert_eq!(clip([5.0, 20.0], [5.0, 30.0]), None);
    }
}
