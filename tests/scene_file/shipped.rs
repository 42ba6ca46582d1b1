//! The shipped scenes in `assets/scenes`: each loads into the scene it describes, with its
//! images, textures and OBJ files found beside it.

use glam::Vec2;
use raylab::color::Color;
use raylab::formats::toml::load_scene;
use raylab::scene::Scene;
use raylab::shapes::Shape;
use raylab::texture::{Texture, WOOD_COLORS, Wrap};

use crate::harness::{assert_error, scenes_dir};

fn shipped_scene(name: &str) -> Scene {
    let path = scenes_dir().join(name);
    load_scene(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn shadows_scene_has_a_sphere_over_a_plane_and_one_light() {
    let scene = shipped_scene("shadows.toml");
    let shapes: Vec<&Shape> = scene.geometry.objects.iter().map(|o| &o.shape).collect();
    assert!(matches!(shapes[..], [Shape::Plane(_), Shape::Sphere(_)]));
    assert_eq!(scene.lights.len(), 1);
    assert!(scene.settings.shadows);
}

#[test]
fn mirrors_scene_has_two_facing_mirrors() {
    let scene = shipped_scene("mirrors.toml");
    let mirrors: Vec<_> = scene
        .geometry
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            Shape::Polygon(p) => Some((p.normal(), o.material)),
            _ => None,
        })
        .collect();
    assert_eq!(mirrors.len(), 2);
    for (_, material) in &mirrors {
        assert_eq!(scene.materials[*material as usize].reflectivity, 0.9);
    }
    assert!(
        (mirrors[0].0 + mirrors[1].0).length() < 1e-6,
        "they face each other"
    );
    assert_eq!(scene.settings.max_depth, 8);
}

#[test]
fn glass_scene_has_a_refracting_sphere_over_a_checkerboard() {
    let scene = shipped_scene("glass.toml");
    let sphere = &scene.geometry.objects[1];
    let glass = &scene.materials[sphere.material as usize];
    assert_eq!(
        (glass.ior, glass.transparency, glass.fresnel),
        (1.5, 0.9, true)
    );
    let floor = &scene.materials[scene.geometry.objects[0].material as usize];
    let texture = &scene.textures[floor.texture.expect("the floor is textured") as usize];
    assert!(matches!(texture, Texture::Checker3d { size: 1.0, .. }));
}

#[test]
fn textures_scene_loads_the_image_relative_to_the_scene_file() {
    let scene = shipped_scene("textures.toml");
    // Textures are numbered in name order: grid, squares.
    match &scene.textures[0] {
        Texture::Image {
            image, wrap, scale, ..
        } => {
            assert_eq!((image.width, image.height), (64, 64));
            assert_eq!(*wrap, [Wrap::Repeat; 2]);
            assert_eq!(*scale, Vec2::new(2.0, 1.0));
        }
        other => panic!("expected the grid image, got {other:?}"),
    }
    assert!(matches!(
        scene.textures[1],
        Texture::CheckerUv {
            u_count: 16.0,
            v_count: 8.0,
            ..
        }
    ));
    let right = &scene.geometry.objects[2];
    assert!(right.transform.is_some());
    assert_eq!(scene.materials[right.material as usize].texture, Some(1));
}

#[test]
fn wood_and_marble_scene_names_the_books_solid_textures_and_a_background_image() {
    let scene = shipped_scene("wood_and_marble.toml");
    // Textures by name: carrara, oak, verde, walnut. Left out, a colour is the book's.
    assert_eq!(
        scene.textures[1],
        Texture::Wood {
            a: WOOD_COLORS.0,
            b: WOOD_COLORS.1
        }
    );
    assert_eq!(
        scene.textures[3],
        Texture::Wood {
            a: Color::new(0.35, 0.2, 0.1),
            b: Color::new(0.55, 0.33, 0.16)
        }
    );
    assert!(matches!(scene.textures[0], Texture::Marble { .. }));
    assert_eq!(
        scene.textures[2],
        Texture::Marble {
            color: Color::new(0.3, 0.7, 0.45)
        }
    );
    let sky = scene.background_image.as_ref().expect("a background image");
    assert_eq!((sky.width, sky.height), (192, 96));
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

#[test]
fn a_background_image_that_cannot_be_loaded_is_an_error_at_its_name() {
    assert_error(
        "[render]\nbackground_image = \"missing.png\"\n",
        2,
        20,
        "cannot load background image",
    );
    assert_error(
        "[render]\nbackground_image = \"wood_and_marble.toml\"\n",
        2,
        20,
        "cannot load background image",
    );
    assert_error(
        "[textures.t]\ntype = \"wood\"\nc = [1, 1, 1]\n",
        3,
        1,
        "unexpected keys in table: c",
    );
}

#[test]
fn meshes_scene_reads_the_obj_file_and_its_materials() {
    let scene = shipped_scene("meshes.toml");
    // Triangle, pyramid, then the OBJ's two groups.
    let triangles: Vec<usize> = scene
        .geometry
        .meshes
        .iter()
        .map(|m| m.faces.len())
        .collect();
    assert_eq!(triangles, [1, 4, 3, 1]);
    assert_eq!(scene.geometry.triangle_count(), 9);
    let copper = &scene.materials[scene.geometry.meshes[2].material as usize];
    assert_eq!(copper.color, Color::new(0.72, 0.45, 0.2));
    assert_eq!(copper.shininess, 64.0);
    let slate = &scene.materials[scene.geometry.meshes[3].material as usize];
    assert_eq!(slate.color, Color::new(0.25, 0.27, 0.3));
    assert!(
        scene.geometry.meshes[2..]
            .iter()
            .all(|m| !m.normals.is_empty())
    );
}
