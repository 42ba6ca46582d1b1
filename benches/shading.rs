//! Shading: the whole ray tree of one pixel (eye ray, shadow rays, reflections, refraction),
//! and a whole small render of the default scene.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use raylab::camera::PIXEL_CENTRE;
use raylab::formats::toml::default_scene;
use raylab::progressive;
use raylab::render::assemble;
use raylab::stats::RayCounts;

fn shading(c: &mut Criterion) {
    let mut scene = default_scene().expect("the built-in scene loads");
    scene.settings.width = 128;
    scene.settings.height = 128;
    let assembled = assemble(scene).expect("the built-in scene has no caustics to shoot");
    let tracer = assembled.tracer();
    // A pixel on the glass sphere: reflected, refracted and shadow rays several levels deep.
    let glass = tracer
        .scene
        .camera
        .eye_ray((66, 87), PIXEL_CENTRE, (128, 128));
    c.bench_function("shade one pixel (glass sphere, default scene)", |b| {
        b.iter(|| tracer.trace_eye(black_box(&glass), &mut RayCounts::default()))
    });
    // A pixel on the floor: one eye ray, two shadow rays, one reflected ray.
    let floor = tracer
        .scene
        .camera
        .eye_ray((20, 121), PIXEL_CENTRE, (128, 128));
    c.bench_function("shade one pixel (floor, default scene)", |b| {
        b.iter(|| tracer.trace_eye(black_box(&floor), &mut RayCounts::default()))
    });
    c.bench_function("render the default scene, 128×128", |b| {
        b.iter(|| progressive::render_image(black_box(&tracer)))
    });
}

criterion_group!(benches, shading);
criterion_main!(benches);
