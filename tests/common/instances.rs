//! Scenes of one model placed many times: the lumpy ball, stored once and placed by instances
//! or copied into the world, for the library's tests and the GPU's.

use glam::{Vec2, Vec3};
use raylab::color::Color;
use raylab::light::Light;
use raylab::material::Material;
use raylab::mesh::Mesh;
use raylab::primitive::{Geometry, Instance};
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape};
use raylab::transform::{Transform, TransformStep};

use super::camera;

/// A lumpy ball of `rings` × `2·rings` quads cut in two, with vertex normals and texture
/// coordinates.
pub fn lumpy_ball(rings: u32) -> Mesh {
    let segments = 2 * rings;
    let mut mesh = Mesh::default();
    for i in 0..=rings {
        let theta = std::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = std::f32::consts::TAU * j as f32 / segments as f32;
            let r = 1.0 + 0.15 * (5.0 * phi).sin() * (3.0 * theta).sin();
            let dir = Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            );
            mesh.positions.push(dir * r);
            mesh.normals.push(dir);
            mesh.uvs.push(Vec2::new(
                j as f32 / segments as f32,
                i as f32 / rings as f32,
            ));
        }
    }
    for i in 0..rings {
        for j in 0..segments {
            let at = |i: u32, j: u32| i * segments + j % segments;
            let (a, b, c, d) = (at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
            mesh.faces.extend([[a, b, c], [a, c, d]]);
        }
    }
    mesh
}

/// Where the `k`th of many placements of a model stands: turned about a tilted axis, squashed
/// and moved onto a grid of ten by ten by `layers`.
fn placement(k: usize) -> Transform {
    let (x, z, y) = (k % 10, k / 10 % 10, k / 100);
    Transform::from_steps(&[
        TransformStep::Rotate {
            axis: Vec3::new(0.3, 1.0, 0.2),
            degrees: 13.0 * k as f32,
        },
        TransformStep::Scale(Vec3::new(0.4, 0.5, 0.35)),
        TransformStep::Translate(Vec3::new(
            x as f32 * 1.1 - 5.0,
            y as f32 * 1.2 + 0.5,
            z as f32 * 1.1 - 5.0,
        )),
    ])
    .unwrap()
}

/// A scene of a floor, two lights and three materials (matte, mirror, glass) that the test
/// adds `count` lumpy balls to: as copies moved into the world, or as instances of one model.
pub fn balls_scene(count: usize, instanced: bool) -> Scene {
    let settings = RenderSettings {
        width: 160,
        height: 120,
        max_depth: 4,
        ..RenderSettings::default()
    };
    let eye = Vec3::new(9.0, 9.0, 14.0);
    let mut scene = Scene::new(settings, camera(eye, Vec3::new(0.0, 1.0, 0.0), 50.0));
    scene.lights.push(Light::Point {
        position: Vec3::new(6.0, 14.0, 8.0),
        color: Color::splat(0.8),
    });
    scene.lights.push(Light::Directional {
        direction: Vec3::new(-1.0, 2.0, 1.0),
        color: Color::splat(0.3),
    });
    let materials = [
        scene.add_material(Material {
            color: Color::new(0.8, 0.25, 0.2),
            specular: 0.5,
            ..Material::default()
        }),
        scene.add_material(Material {
            color: Color::splat(0.9),
            diffuse: 0.1,
            reflectivity: 0.8,
            ..Material::default()
        }),
        scene.add_material(super::clear_glass()),
    ];
    let floor = Shape::Plane(Plane {
        point: Vec3::ZERO,
        normal: Vec3::Y,
    });
    scene.add_object(floor, None, materials[0]);
    let ball = lumpy_ball(8);
    let model = instanced.then(|| {
        let mut model = Geometry::default();
        model.add_mesh(ball.clone());
        scene.geometry.add_model(model)
    });
    for k in 0..count {
        let material = materials[k % 3];
        match model {
            Some(model) => {
                let instance = Instance {
                    model,
                    transform: placement(k),
                    material: Some(material),
                };
                scene.geometry.add_instance(instance).unwrap();
            }
            None => {
                let mut copy = ball.clone();
                copy.transform(&placement(k));
                copy.material = material;
                scene.geometry.add_mesh(copy);
            }
        }
    }
    scene
}
