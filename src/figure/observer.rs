//! The observer: the camera the figure is seen from, other than the scene's. Where it stands
//! when nobody says ([`side_view`]), the scene as it sees it ([`observed`], rendered by any
//! tracer) and how far it sees at each pixel ([`observer_depths`]), which hides the lines behind
//! surfaces.

use glam::Vec3;
use rayon::prelude::*;

use super::segments::RayFigure;
use crate::aabb::Aabb;
use crate::camera::{Camera, CameraSpec, PIXEL_CENTRE};
use crate::render::Assembled;
use crate::whitted::{EYE_RAY_T_MIN, Tracer};

/// The observer's vertical view angle `θ` in degrees when nobody gives one.
pub const OBSERVER_ANGLE: f32 = 45.0;

/// The observer's direction from the figure's centre, in the scene camera's axes: to its right
/// (`u`), towards its eye's side of the image plane (`n`), and a little above (world +y), so that
/// the image plane is seen from the front and the eye and the tree from the side.
const SIDE: (f32, f32, f32) = (1.0, 0.5, 0.4);

/// The observer that frames the whole figure from the side of the scene camera, a little above,
/// looking at the figure's centre with up +y and view angle `view_angle`, on an image `aspect`
/// wide per unit of height.
pub fn side_view(
    figure: &RayFigure,
    scene_camera: &Camera,
    view_angle: f32,
    aspect: f32,
) -> CameraSpec {
    let focus = figure.focus();
    let bounds = Aabb::from_points(focus.iter().copied());
    let (right, back, up) = SIDE;
    let toward = scene_camera.u * right + scene_camera.n * back + Vec3::Y * up;
    // A scene camera looking straight up or down would put the observer above the figure.
    let toward = if toward.normalize().y.abs() > 0.95 {
        Vec3::new(1.0, up, back)
    } else {
        toward
    };
    let start = CameraSpec {
        eye: bounds.center() + toward.normalize(),
        look_at: bounds.center(),
        up: Vec3::Y,
        view_angle,
        near: CameraSpec::default().near,
    };
    let framed = start.framing(&bounds, aspect).unwrap_or(start);
    closer(framed, &focus, aspect)
}

/// Margin left around the framed points, a share of the image's height: (top, the rest). The
/// top one leaves room for the legend.
const MARGIN: (f32, f32) = (0.16, 0.05);

/// `spec` moved along its view direction as near to its look-at point as it can come while
/// every point of `points` stays in view, within [`MARGIN`] of the edges ([`CameraSpec::framing`]
/// fits the box's bounding sphere, which leaves the box itself small in the view).
fn closer(spec: CameraSpec, points: &[Vec3], aspect: f32) -> CameraSpec {
    let height = 1000;
    let width = ((height as f32 * aspect).round() as u32).max(1);
    let (top, margin) = (MARGIN.0 * height as f32, MARGIN.1 * height as f32);
    let at = |f: f32| CameraSpec {
        eye: spec.look_at + (spec.eye - spec.look_at) * f,
        near: spec.near * f,
        ..spec
    };
    let fits = |candidate: CameraSpec| {
        let Ok(camera) = Camera::new(candidate) else {
            return false;
        };
        points.iter().all(|&p| {
            view_depth(&camera, p) > camera.near
                && camera.project(p, width, height).is_some_and(|q| {
                    q.x >= margin
                        && q.y >= top
                        && q.x <= width as f32 - margin
                        && q.y <= height as f32 - margin
                })
        })
    };
    // The framing distance fits but for the margin (f = 1 or a little more); halve the gap to
    // the nearest that does.
    let Some(mut fit) = [1.0f32, 1.25, 1.5, 2.0].into_iter().find(|&f| fits(at(f))) else {
        return spec;
    };
    let mut miss = 0.05f32;
    for _ in 0..24 {
        let f = 0.5 * (fit + miss);
        if fits(at(f)) { fit = f } else { miss = f }
    }
    at(fit)
}

/// The render of `assembled`'s scene seen by `observer` on a `width × height` image: the same
/// scene and BVH (shared, not built again), the observer's camera and size.
pub fn observed(assembled: &Assembled, observer: Camera, (width, height): (u32, u32)) -> Assembled {
    let mut seen = assembled.clone();
    seen.scene.camera = observer;
    seen.scene.settings.width = width;
    seen.scene.settings.height = height;
    seen
}

/// How far `observer` sees through the centre of each pixel of its `width × height` image, row
/// by row from the top: the depth along the view direction (`(p − eye)·(−n)`) of the closest
/// surface its eye ray meets beyond the image plane, as the render shows it; infinite where the
/// ray leaves the scene.
pub fn observer_depths(
    tracer: &Tracer,
    observer: &Camera,
    (width, height): (u32, u32),
) -> Vec<f32> {
    let mut depths = vec![f32::INFINITY; width as usize * height as usize];
    depths
        .par_chunks_mut(width.max(1) as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, depth) in row.iter_mut().enumerate() {
                let ray = observer.eye_ray((x as u32, y as u32), PIXEL_CENTRE, (width, height));
                if let Some(hit) = tracer.closest_hit(&ray, EYE_RAY_T_MIN) {
                    *depth = view_depth(observer, ray.at(hit.t));
                }
            }
        });
    depths
}

/// The depth of `point` along `camera`'s view direction.
pub fn view_depth(camera: &Camera, point: Vec3) -> f32 {
    (point - camera.eye).dot(-camera.n)
}
