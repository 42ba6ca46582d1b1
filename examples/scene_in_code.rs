//! Build a scene in code instead of reading a file: a mirror ball and a glass ball on a
//! floor, one point light, the lecture's camera. Writes `scene_in_code.png`, or the file named.
//!
//! ```sh
//! cargo run --release --example scene_in_code -- balls.png
//! ```

use std::path::Path;

use glam::Vec3;
use raylab::backend::Backend;
use raylab::camera::{Camera, CameraSpec};
use raylab::color::Color;
use raylab::formats::image::save_image;
use raylab::light::Light;
use raylab::material::Material;
use raylab::render::assemble;
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape, Sphere};

fn main() {
    if let Err(error) = run() {
        eprintln!("error: {error}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let settings = RenderSettings {
        width: 320,
        height: 240,
        ..RenderSettings::default()
    };
    let camera = Camera::new(CameraSpec {
        eye: Vec3::new(0.0, 1.5, 6.0),
        look_at: Vec3::new(0.0, 0.8, 0.0),
        up: Vec3::Y,
        view_angle: 40.0,
        near: 1.0,
    })?;
    let mut scene = Scene::new(settings, camera);

    let floor = scene.add_material(Material {
        color: Color::new(0.6, 0.55, 0.5),
        ..Material::default()
    });
    let mirror = scene.add_material(Material {
        color: Color::splat(0.2),
        reflectivity: 0.8,
        ..Material::default()
    });
    let glass = scene.add_material(Material {
        color: Color::ONE,
        diffuse: 0.05,
        transparency: 0.9,
        ior: 1.5,
        fresnel: true,
        ..Material::default()
    });

    let plane = Plane {
        point: Vec3::ZERO,
        normal: Vec3::Y,
    };
    scene.add_object(Shape::Plane(plane), None, floor);
    let ball = Sphere::new(Vec3::new(-1.1, 1.0, 0.0), 1.0)?;
    scene.add_object(Shape::Sphere(ball), None, mirror);
    let ball = Sphere::new(Vec3::new(1.1, 1.0, 0.5), 1.0)?;
    scene.add_object(Shape::Sphere(ball), None, glass);
    scene.lights.push(Light::Point {
        position: Vec3::new(-4.0, 6.0, 5.0),
        color: Color::ONE,
    });

    let assembled = assemble(scene)?;
    let (film, _) = Backend::on_all_cores()?.render_image(&assembled)?;
    let out = std::env::args()
        .nth(1)
        .unwrap_or("scene_in_code.png".into());
    save_image(Path::new(&out), 320, 240, &film.pixels())?;
    println!("wrote {out}");
    Ok(())
}
