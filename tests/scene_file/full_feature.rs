//! A file with every feature becomes the expected `Scene`: every setting, lights, materials and
//! textures by name, transforms in file order, meshes; and the defaults of an empty file.

use glam::{Vec2, Vec3};
use raylab::color::Color;
use raylab::formats::toml::DEFAULT_MATERIAL;
use raylab::light::Light;
use raylab::material::Material;
use raylab::settings::RenderSettings;
use raylab::shapes::Shape;
use raylab::texture::{Texture, Wrap};

use crate::harness::{FULL, assert_error, parse};

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

#[test]
fn full_feature_file_sets_every_setting() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        scene.settings,
        RenderSettings {
            width: 320,
            height: 200,
            max_depth: 7,
            min_weight: 0.05,
            block_size: 8,
            samples: 4,
            aa_threshold: 0.05,
            background: Color::new(0.1, 0.2, 0.3),
            ambient: Color::splat(0.3),
            shadows: false,
            reflections: false,
            transmission: false,
            textures: false,
            fog_steps: 12,
            caustic_photons: 1000,
            caustic_gather: 20,
        }
    );
    let spec = scene.camera.spec;
    assert_eq!(
        (spec.eye, spec.look_at),
        (Vec3::new(0.0, 2.0, 8.0), Vec3::Y)
    );
    assert_eq!((spec.view_angle, spec.near), (30.0, 0.5));
}

#[test]
fn transmission_is_also_read_under_its_old_name_refractions() {
    for key in ["transmission", "refractions"] {
        let scene = parse(&format!("[render]\n{key} = false\n")).unwrap();
        assert!(!scene.settings.transmission, "{key}");
    }
    assert!(parse("").unwrap().settings.transmission);
    // Both names at once is one setting given twice.
    assert_error(
        "[render]\ntransmission = false\nrefractions = true\n",
        3,
        1,
        "`refractions` is the old name of `transmission`",
    );
}

#[test]
fn full_feature_file_scales_light_colours_and_normalises_directions() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        scene.lights,
        [
            Light::Point {
                position: Vec3::new(5.0, 8.0, 5.0),
                color: Color::new(2.0, 1.0, 0.5),
            },
            Light::Directional {
                direction: Vec3::new(0.0, 0.6, 0.8),
                color: Color::ONE,
            },
        ]
    );
}

#[test]
fn full_feature_file_numbers_materials_and_textures_by_name() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    // Default material first, then by name: blue, red, stripy, tiled. Textures by name: checks,
    // stripes, tiles.
    assert_eq!(scene.materials.len(), 5);
    let texture_of = |m: usize| scene.materials[m].texture;
    assert_eq!((texture_of(3), texture_of(4)), (Some(1), Some(2)));
    assert_eq!(
        scene.materials[DEFAULT_MATERIAL as usize],
        Material::default()
    );
    assert_eq!(scene.materials[1].color, Color::new(0.0, 0.0, 1.0));
    assert_eq!(
        scene.materials[2],
        Material {
            color: Color::new(0.8, 0.1, 0.1),
            texture: Some(0),
            alpha_cutoff: Some(0.25),
            emission: Color::new(0.05, 0.1, 0.0),
            emission_texture: None,
            ambient: 0.2,
            diffuse: 0.7,
            specular: 0.5,
            specular_color: Color::new(1.0, 1.0, 0.0),
            shininess: 10.0,
            reflectivity: 0.25,
            reflection_color: Color::new(1.0, 0.5, 0.25),
            transparency: 0.5,
            ior: 1.33,
            fresnel: true,
            medium: None,
        }
    );
    assert!(matches!(
        scene.textures[0],
        Texture::Checker3d { size: 0.5, .. }
    ));
    assert!(matches!(
        scene.textures[1],
        Texture::CheckerUv {
            u_count: 4.0,
            v_count: 1.0,
            ..
        }
    ));
    assert!(matches!(
        &scene.textures[2],
        Texture::Image { wrap: [Wrap::Clamp, Wrap::Clamp], scale, .. } if *scale == Vec2::new(3.0, 2.0)
    ));
    let objects = &scene.geometry.objects;
    assert_eq!(
        (objects[0].material, objects[1].material),
        (2, DEFAULT_MATERIAL)
    );
}

#[test]
fn full_feature_file_composes_transforms_in_file_order() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    let sphere = &scene.geometry.objects[0];
    assert_eq!(
        sphere.shape,
        Shape::Sphere(raylab::shapes::Sphere {
            center: Vec3::Y,
            radius: 2.0,
        })
    );
    let transform = sphere
        .transform
        .as_ref()
        .expect("the sphere has a transform");
    // Translate by +y, then rotate 90° about y, then scale y by 2: (1, 0, 0) → (1, 1, 0) →
    // (0, 1, -1) → (0, 2, -1).
    let p = transform.point_to_world(Vec3::X);
    assert!(close(p, Vec3::new(0.0, 2.0, -1.0)), "{p}");
    // No transform key: no transform.
    assert_eq!(scene.geometry.objects[1].transform, None);
    match &scene.geometry.objects[1].shape {
        Shape::Plane(plane) => assert_eq!((plane.point, plane.normal), (-Vec3::Y, Vec3::Y)),
        other => panic!("expected the plane, got {other:?}"),
    }
}

#[test]
fn full_feature_file_turns_triangles_meshes_and_obj_files_into_meshes() {
    let scene = parse(FULL).unwrap_or_else(|e| panic!("{e}"));
    let meshes = &scene.geometry.meshes;
    assert_eq!(meshes.len(), 4, "triangle, quad and the OBJ's two groups");
    assert_eq!(scene.geometry.triangle_count(), 1 + 2 + 4);
    assert_eq!(meshes[0].normals, [Vec3::Z; 3]);
    assert_eq!(meshes[0].material, 1);
    // The quad was scaled by 2 into the world and took the default material.
    assert_eq!(meshes[1].positions[2], Vec3::new(2.0, 2.0, 0.0));
    assert_eq!(meshes[1].uvs.len(), 4);
    assert_eq!(meshes[1].material, DEFAULT_MATERIAL);
    // A `material` key overrides the OBJ's MTL materials, which are then not added.
    assert!(meshes[2..].iter().all(|m| m.material == 1));
    assert_eq!(scene.materials.len(), 5);
}

#[test]
fn an_empty_file_is_a_scene_with_every_default() {
    let scene = parse("").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.settings, RenderSettings::default());
    assert!(scene.lights.is_empty() && scene.geometry.objects.is_empty());
    assert_eq!(scene.materials, [Material::default()]);
}

#[test]
fn objects_may_be_written_as_inline_tables() {
    let scene =
        parse("objects = [ { type = \"sphere\", radius = 3 } ]").unwrap_or_else(|e| panic!("{e}"));
    assert!(matches!(
        scene.geometry.objects[0].shape,
        Shape::Sphere(s) if s.radius == 3.0 && s.center == Vec3::ZERO
    ));
}
