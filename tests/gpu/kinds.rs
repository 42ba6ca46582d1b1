//! One test per family of kinds, over every kind the Rust enumerates (`ShapeKind`, `LightKind`,
//! `TextureKind`; the views are in images.rs): each kind's example (`common::kinds`) rendered by
//! both tracers and compared as images.rs compares them, and each shape's closest hits probed
//! on the GPU against the CPU's. A new variant needs an example to compile, and then fails here
//! until the WGSL traces it.

use glam::Vec3;
use raylab::camera::PIXEL_CENTRE;
use raylab::color::{Color, to_srgb8};
use raylab::gpu::probe::{ProbeRay, Search, closest_hits};
use raylab::gpu::scene::GpuScene;
use raylab::light::{Light, LightKind};
use raylab::material::Material;
use raylab::primitive::PrimId;
use raylab::progressive::gpu::GpuRenderer;
use raylab::progressive::render_image;
use raylab::render::{Assembled, assemble};
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Shape, ShapeKind};
use raylab::texture::{Texture, TextureKind};
use raylab::whitted::EYE_RAY_T_MIN;
use strum::IntoEnumIterator;

use crate::common::kinds::{example_light, example_shape, example_texture};
use crate::images::{difference, gpu_render};
use crate::{common, gpu, shapes};

const SIZE: (u32, u32) = (64, 48);

/// `shape` (with `texture`, if any) on a floor, lit by `light`, seen from up and to the side.
fn scene_of(shape: Shape, light: Light, texture: Option<Texture>) -> Assembled {
    let settings = RenderSettings {
        width: SIZE.0,
        height: SIZE.1,
        ..RenderSettings::default()
    };
    let camera = common::camera(Vec3::new(2.5, 3.5, 4.5), Vec3::ZERO, 45.0);
    let mut scene = Scene::new(settings, camera);
    scene.lights.push(light);
    let mut material = Material {
        color: Color::new(0.8, 0.5, 0.3),
        ..Material::default()
    };
    if let Some(texture) = texture {
        scene.textures.push(texture);
        material.texture = Some(0);
    }
    let material = scene.add_material(material);
    scene.add_object(shape, None, material);
    let floor = scene.add_material(Material::default());
    let below = Shape::Plane(raylab::shapes::Plane {
        point: Vec3::new(0.0, -1.6, 0.0),
        normal: Vec3::Y,
    });
    scene.add_object(below, None, floor);
    assemble(scene).unwrap()
}

/// Renders `assembled` on both tracers and compares the images: mean difference at most 0.5
/// levels, 99 % of pixels within 3, and the image not of one colour.
fn renders_alike(what: &str, assembled: &Assembled) {
    let renderer = GpuRenderer::new(gpu(), assembled).unwrap_or_else(|e| panic!("{what}: {e}"));
    let (on_gpu, _) = gpu_render(&renderer, &assembled.tracer());
    let (cpu_pixels, _) = render_image(&assembled.tracer());
    let on_cpu = to_srgb8(&cpu_pixels);
    let (mean, close) = difference(&on_gpu, &on_cpu);
    assert!(
        mean <= 0.5 && close >= 0.99,
        "{what}: mean {mean:.3} levels, {:.2} % within 3",
        close * 100.0
    );
    let colours: std::collections::BTreeSet<&[u8]> = on_cpu.chunks(3).collect();
    assert!(colours.len() > 20, "{what}: {} colours", colours.len());
}

#[test]
fn every_kind_of_shape_renders_on_the_gpu_as_on_the_cpu_and_gives_its_closest_hits() {
    let gpu = gpu();
    for kind in ShapeKind::iter() {
        let what = format!("{kind:?}");
        let assembled = scene_of(example_shape(kind), example_light(LightKind::Point), None);
        renders_alike(&what, &assembled);
        let camera = &assembled.scene.camera;
        let rays: Vec<ProbeRay> = (0..SIZE.1)
            .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
            .map(|pixel| {
                let ray = camera.eye_ray(pixel, PIXEL_CENTRE, SIZE);
                ProbeRay::new(&ray, EYE_RAY_T_MIN, f32::MAX)
            })
            .collect();
        let on_the_gpu = GpuScene::upload(&gpu, &assembled).unwrap();
        let hits = closest_hits(&gpu, &on_the_gpu, Search::Bvh, &rays).unwrap();
        let compared = shapes::compare(&assembled, Search::Bvh, &rays, &hits);
        let on_shape = hits
            .iter()
            .filter(|h| h.prim == PrimId::object(0).0)
            .count();
        assert!(
            compared > rays.len() / 2 && on_shape > rays.len() / 20,
            "{what}: {compared} hits compared, {on_shape} on the shape"
        );
    }
}

#[test]
fn every_kind_of_light_lights_on_the_gpu_as_on_the_cpu() {
    for kind in LightKind::iter() {
        let ball = example_shape(ShapeKind::Sphere);
        renders_alike(
            &format!("{kind:?}"),
            &scene_of(ball, example_light(kind), None),
        );
    }
}

#[test]
fn every_kind_of_texture_renders_on_the_gpu_as_on_the_cpu() {
    for kind in TextureKind::iter() {
        let ball = example_shape(ShapeKind::Ellipsoid);
        let light = example_light(LightKind::Point);
        let assembled = scene_of(ball, light, Some(example_texture(kind)));
        renders_alike(&format!("{kind:?}"), &assembled);
    }
}
