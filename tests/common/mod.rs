//! What several test binaries share: scenes built in code, seeded random numbers, seeded
//! mutations of texts, and running the `raylab` binary.

#![allow(dead_code)] // each test binary uses a different part

pub mod fuzz;
pub mod instances;
pub mod kinds;
pub mod random;
pub mod run;
pub mod students;

use glam::Vec3;
use std::path::Path;

use raylab::camera::{Camera, CameraSpec};
use raylab::color::Color;
use raylab::formats::load_any;
use raylab::formats::spd::{Database, load_spd};
use raylab::light::Light;
use raylab::material::Material;
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape, Sphere};
use strum::IntoEnumIterator;

/// A camera at `eye` looking at `look_at` with +Y up.
pub fn camera(eye: Vec3, look_at: Vec3, view_angle: f32) -> Camera {
    Camera::new(CameraSpec {
        eye,
        look_at,
        up: Vec3::Y,
        view_angle,
        near: 1.0,
    })
    .unwrap()
}

/// Clear glass: transmits 0.9, index of refraction 1.5, no diffuse light, no mirror reflection.
pub fn clear_glass() -> Material {
    Material {
        color: Color::ONE,
        diffuse: 0.0,
        transparency: 0.9,
        ior: 1.5,
        ..Material::default()
    }
}

/// Three spheres (one mirror, one glass) on a floor, one light: every kind of ray.
pub fn spheres_on_a_floor(width: u32, height: u32) -> Scene {
    let settings = RenderSettings {
        width,
        height,
        ..RenderSettings::default()
    };
    let mut scene = Scene::new(
        settings,
        camera(Vec3::new(0.0, 2.0, 7.0), Vec3::new(0.0, 0.8, 0.0), 45.0),
    );
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
    let glass = scene.add_material(clear_glass());
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
    scene
}

/// The scene files of `folder` (of the repository), by file name, in order: TOML, SDL and
/// glTF models (`.glb`) on their own.
pub fn scene_files(folder: &str) -> Vec<(String, Scene)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| {
            let name = path.file_name().unwrap().to_string_lossy();
            (name.ends_with(".toml") && !name.ends_with(".camera.toml"))
                || name.ends_with(".dat")
                || name.ends_with(".glb")
        })
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (name, load_any(path.to_str().unwrap()).unwrap())
        })
        .collect()
}

/// Every shipped scene (`assets/scenes/`) and every SPD scene at its standard size, by name.
pub fn shipped_and_spd_scenes() -> Vec<(String, Scene)> {
    let spd = Database::iter().map(|database| {
        let name = format!("spd:{database}");
        let scene = load_spd(&name, Default::default()).unwrap();
        (name, scene)
    });
    scene_files("assets/scenes")
        .into_iter()
        .chain(spd)
        .collect()
}
