//! Picking: the surface point seen at a point of the image, found by tracing the same eye ray the
//! renderer traces there (used by double-click to set the orbit centre).

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::camera::Camera;
use raylab::scene::Scene;
use raylab::whitted::{EYE_RAY_T_MIN, Tracer};

/// The first surface point along the eye ray through image point `(x, y)` (in pixels, `y` down)
/// of a `width × height` image, or `None` if that ray leaves the scene.
pub fn surface_point(
    scene: &Scene,
    bvh: &Bvh,
    camera: &Camera,
    (width, height): (u32, u32),
    (x, y): (f32, f32),
) -> Option<Vec3> {
    // The pixel under (x, y) and the point within it: the same ray as `height − y`, `x`.
    let pixel = (x.floor(), y.floor());
    let offset = (x - pixel.0, y - pixel.1);
    let ray = camera.eye_ray((pixel.0 as u32, pixel.1 as u32), offset, (width, height));
    let hit = Tracer::new(scene, bvh).closest_hit(&ray, EYE_RAY_T_MIN)?;
    Some(ray.origin + ray.dir * hit.t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::scene::source;

    #[test]
    fn the_centre_of_the_image_hits_what_the_camera_looks_at() {
        let loaded = source::load(None, None).unwrap();
        let camera = loaded.assembled.scene.camera;
        let size = (64, 48);
        let centre = surface_point(
            &loaded.assembled.scene,
            &loaded.assembled.bvh,
            &camera,
            size,
            (32.0, 24.0),
        )
        .unwrap();
        // The point lies on the view axis, in front of the eye.
        let to_point = (centre - camera.eye).normalize();
        assert!(to_point.dot(-camera.n) > 0.999, "{centre}");
    }

    #[test]
    fn a_ray_into_the_sky_hits_nothing() {
        let loaded = source::load(None, None).unwrap();
        let camera = loaded.assembled.scene.camera;
        // The top-left corner of a very wide view looks up past everything.
        let mut spec = camera.spec;
        spec.look_at = spec.eye + glam::Vec3::new(0.0, 1.0, -0.2);
        let up = Camera::new(spec).unwrap();
        assert_eq!(
            surface_point(
                &loaded.assembled.scene,
                &loaded.assembled.bvh,
                &up,
                (64, 48),
                (0.5, 0.5)
            ),
            None
        );
    }
}
