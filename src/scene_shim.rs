//! TEMPORARY stand-in for `raylab::scene::{load_scene, default_scene}` until main's scene-file
//! loader is merged; deleted then.

use std::path::Path;

use glam::Vec3;
use raylab::camera::{Camera, CameraSpec};
use raylab::light::Light;
use raylab::material::{Color, Material};
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape, Sphere};

#[derive(Debug)]
pub struct SceneError(String);

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError(format!("{}:1:1: cannot read the scene file: {e}", path.display())))?;
    if text.contains("broken") {
        return Err(SceneError(format!("{}:1:1: this scene is broken", path.display())));
    }
    default_scene()
}

pub fn default_scene() -> Result<Scene, SceneError> {
    let camera = Camera::new(CameraSpec {
        eye: Vec3::new(0.0, 2.0, 7.0),
        look_at: Vec3::new(0.0, 0.8, 0.0),
        up: Vec3::Y,
        view_angle: 45.0,
        near: 1.0,
    })
    .map_err(|e| SceneError(e.to_string()))?;
    let mut scene = Scene::new(RenderSettings::default(), camera);
    let matte = scene.add_material(Material {
        color: Color::new(0.8, 0.3, 0.2),
        specular: 0.5,
        ..Material::default()
    });
    let mirror = scene.add_material(Material {
        color: Color::splat(0.2),
        reflectivity: 0.8,
        ..Material::default()
    });
    let glass = scene.add_material(Material {
        color: Color::ONE,
        diffuse: 0.0,
        transparency: 0.9,
        ior: 1.5,
        ..Material::default()
    });
    let floor = scene.add_material(Material::default());
    for (x, material) in [(-2.0, matte), (0.0, mirror), (2.0, glass)] {
        scene.add_object(
            Shape::Sphere(Sphere {
                center: Vec3::new(x, 1.0, 0.0),
                radius: 0.9,
            }),
            None,
            material,
        );
    }
    scene.add_object(
        Shape::Plane(Plane {
            point: Vec3::ZERO,
            normal: Vec3::Y,
        }),
        None,
        floor,
    );
    scene.lights.push(Light::Point {
        position: Vec3::new(4.0, 6.0, 4.0),
        color: Color::ONE,
    });
    Ok(scene)
}
