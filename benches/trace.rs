//! Inner loops of the tracer: shape intersection, BVH build and traversal, one full render.
//! `cargo bench` (release build); compare runs made on the same machine in the same session.

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::mesh::Mesh;
use raylab::primitive::Geometry;
use raylab::progressive;
use raylab::ray::Ray;
use raylab::scene;
use raylab::shapes::{Sphere, Triangle};
use raylab::whitted::Tracer;
use std::hint::black_box;

/// A deterministic cloud of `n` small triangles in a 20-unit cube.
fn triangle_soup(n: u32) -> Geometry {
    let mut state = 12345u64;
    let mut next = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
        (state >> 40) as f32 / (1u64 << 24) as f32 * 20.0 - 10.0
    };
    let mut mesh = Mesh::default();
    for i in 0..n {
        let c = Vec3::new(next(), next(), next());
        let e = |v: f32| v * 0.05;
        mesh.positions.extend([
            c,
            c + Vec3::new(e(next()), e(next()), e(next())),
            c + Vec3::new(e(next()), e(next()), e(next())),
        ]);
        mesh.faces.push([3 * i, 3 * i + 1, 3 * i + 2]);
    }
    let mut g = Geometry::default();
    g.add_mesh(mesh);
    g
}

fn intersection(c: &mut Criterion) {
    let ray = Ray::new(Vec3::new(0.1, 0.2, 5.0), Vec3::new(0.0, 0.0, -1.0));
    let sphere = Sphere {
        center: Vec3::ZERO,
        radius: 1.0,
    };
    c.bench_function("sphere hit", |b| {
        b.iter(|| black_box(&sphere).intersect(black_box(&ray), 0.0, f32::INFINITY))
    });
    let tri = Triangle::new(
        [
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::Y,
        ],
        0,
        0,
    );
    c.bench_function("triangle hit", |b| {
        b.iter(|| black_box(&tri).intersect(black_box(&ray), 0.0, f32::INFINITY))
    });
}

fn bvh(c: &mut Criterion) {
    let soup = triangle_soup(100_000);
    c.bench_function("bvh build 100k triangles", |b| {
        b.iter(|| Bvh::build(black_box(&soup)))
    });
    let bvh = Bvh::build(&soup);
    let rays: Vec<Ray> = (0..1024)
        .map(|i| {
            let (x, y) = ((i % 32) as f32 / 16.0 - 1.0, (i / 32) as f32 / 16.0 - 1.0);
            Ray::new(
                Vec3::new(0.0, 0.0, 30.0),
                Vec3::new(x * 0.35, y * 0.35, -1.0),
            )
        })
        .collect();
    c.bench_function("closest hit, 1024 coherent rays, 100k triangles", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| bvh.closest_hit(&soup, r, 0.0, f32::INFINITY).is_some())
                .count()
        })
    });
}

fn render(c: &mut Criterion) {
    let mut scene = scene::default_scene().expect("the built-in scene loads");
    scene.settings.width = 128;
    scene.settings.height = 128;
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    c.bench_function("default scene 128×128", |b| {
        b.iter(|| progressive::render_image(black_box(&tracer)))
    });
}

criterion_group!(benches, intersection, bvh, render);
criterion_main!(benches);
