//! A large generated triangle scene for benchmarks of traversal and BVH build: a bumpy sphere
//! of `n` triangles (a latitude–longitude grid displaced by a few waves) on a floor, lit by
//! two lights and seen from the front. Nothing to download, the same on every machine.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use crate::camera::{Camera, CameraSpec};
use crate::color::Color;
use crate::light::Light;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::settings::RenderSettings;
use crate::shapes::{Plane, Shape};

/// The bumpy sphere with at least `triangles` triangles, as one smooth-shaded mesh.
pub fn bumpy_sphere(triangles: usize) -> Mesh {
    // A grid of `rings × segments` quads makes 2·rings·segments triangles; segments = 2·rings.
    let rings = ((triangles as f32 / 4.0).sqrt().ceil() as u32).max(2);
    let segments = 2 * rings;
    let radius_at = |theta: f32, phi: f32| {
        1.0 + 0.04 * (12.0 * theta).sin() * (9.0 * phi).cos()
            + 0.02 * (31.0 * phi + 5.0 * theta).sin()
    };
    let vertices = ((rings + 1) * (segments + 1)) as usize;
    let mut mesh = Mesh {
        positions: Vec::with_capacity(vertices),
        normals: Vec::with_capacity(vertices),
        uvs: Vec::with_capacity(vertices),
        faces: Vec::with_capacity((2 * rings * segments) as usize),
        ..Mesh::default()
    };
    for r in 0..=rings {
        let theta = PI * r as f32 / rings as f32;
        for s in 0..=segments {
            let phi = 2.0 * PI * s as f32 / segments as f32;
            let dir = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            mesh.positions.push(dir * radius_at(theta, phi));
            mesh.normals.push(dir);
            mesh.uvs.push(Vec2::new(
                s as f32 / segments as f32,
                1.0 - r as f32 / rings as f32,
            ));
        }
    }
    let index = |r: u32, s: u32| r * (segments + 1) + s;
    for r in 0..rings {
        for s in 0..segments {
            let (a, b) = (index(r, s), index(r, s + 1));
            let (c, d) = (index(r + 1, s + 1), index(r + 1, s));
            mesh.faces.push([a, b, c]);
            mesh.faces.push([a, c, d]);
        }
    }
    mesh
}

/// Most triangles [`bumpy_sphere_scene`] makes.
pub const MAX_BUMPY_TRIANGLES: usize = 20_000_000;

/// Memory per triangle while the scene and its BVH are built, at most (measured about 200).
pub const BUMPY_BYTES_PER_TRIANGLE: u64 = 300;

/// Checks a triangle count for [`bumpy_sphere_scene`]: from 1 to [`MAX_BUMPY_TRIANGLES`], and
/// within the memory available.
pub fn check_bumpy_triangles(triangles: usize) -> Result<(), String> {
    if !(1..=MAX_BUMPY_TRIANGLES).contains(&triangles) {
        return Err(format!(
            "the bumpy sphere has from 1 to {MAX_BUMPY_TRIANGLES} triangles, got {triangles}"
        ));
    }
    crate::memory::check(
        &format!("a bumpy sphere of {triangles} triangles"),
        triangles as u64 * BUMPY_BYTES_PER_TRIANGLE,
    )
}

/// The benchmark scene: the bumpy sphere of `triangles` triangles, 2 units across, on a floor.
pub fn bumpy_sphere_scene(triangles: usize, width: u32, height: u32) -> Scene {
    let settings = RenderSettings {
        width,
        height,
        ..RenderSettings::default()
    };
    let camera = Camera::new(CameraSpec {
        eye: Vec3::new(0.0, 1.5, 4.0),
        look_at: Vec3::new(0.0, 0.9, 0.0),
        ..CameraSpec::default()
    })
    .expect("a valid fixed camera");
    let mut scene = Scene::new(settings, camera);
    let floor = scene.add_material(Material::default());
    let clay = scene.add_material(Material {
        color: Color::new(0.8, 0.55, 0.4),
        specular: 0.4,
        reflectivity: 0.1,
        ..Material::default()
    });
    scene.add_object(
        Shape::Plane(Plane {
            point: Vec3::new(0.0, -0.1, 0.0),
            normal: Vec3::Y,
        }),
        None,
        floor,
    );
    let mut mesh = bumpy_sphere(triangles);
    for p in &mut mesh.positions {
        *p += Vec3::new(0.0, 1.0, 0.0);
    }
    mesh.material = clay;
    scene.geometry.add_mesh(mesh);
    scene.lights.push(Light::Point {
        position: Vec3::new(4.0, 6.0, 5.0),
        color: Color::splat(0.8),
    });
    scene.lights.push(Light::Point {
        position: Vec3::new(-5.0, 3.0, 2.0),
        color: Color::splat(0.3),
    });
    scene
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn has_at_least_the_asked_triangles_and_a_valid_mesh() {
        for n in [8, 1000, 100_000] {
            let mesh = bumpy_sphere(n);
            assert!(mesh.faces.len() >= n, "{n}: {}", mesh.faces.len());
            assert!(mesh.faces.len() < n + 4 * (n as f32).sqrt() as usize + 16);
            mesh.validate().unwrap();
        }
    }

    #[test]
    fn stays_near_the_unit_sphere() {
        let mesh = bumpy_sphere(10_000);
        for p in &mesh.positions {
            assert!((p.length() - 1.0).abs() <= 0.061, "{p}");
        }
    }
}
