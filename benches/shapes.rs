//! Ray–shape intersection, one benchmark per shape: 256 rays from all around towards each
//! shape (some hit, some miss), through [`Shape::intersect`] as the tracer calls it, and the
//! watertight triangle test.

mod common;

use std::hint::black_box;

use common::random::{Rng, direction, in_cube};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use raylab::ray::Ray;
use raylab::shapes::{
    Cuboid, Ellipsoid, Paraboloid, Plane, Polygon, Shape, Sphere, TaperedCylinder, Torus, Triangle,
};

/// 256 rays from a sphere of radius 4 around the origin towards points near it.
fn rays_at_origin() -> Vec<Ray> {
    let mut rng = Rng::with_seed(7);
    (0..256)
        .map(|_| {
            let from = direction(&mut rng) * 4.0;
            Ray::new(from, in_cube(&mut rng, -0.8, 0.8) - from)
        })
        .collect()
}

fn shapes() -> Vec<(&'static str, Shape)> {
    let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    vec![
        (
            "sphere",
            Shape::Sphere(Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            }),
        ),
        (
            "plane",
            Shape::Plane(Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            }),
        ),
        (
            "polygon (square)",
            Shape::Polygon(
                Polygon::new(square.map(|(x, z)| Vec3::new(x, 0.0, z)).to_vec()).unwrap(),
            ),
        ),
        (
            "box",
            Shape::Cuboid(Cuboid::new(Vec3::splat(-0.7), Vec3::splat(0.7)).unwrap()),
        ),
        (
            "cylinder (capped)",
            Shape::TaperedCylinder(
                TaperedCylinder::new(-Vec3::Y, Vec3::Y, 0.7, 0.7, true).unwrap(),
            ),
        ),
        (
            "cone",
            Shape::TaperedCylinder(
                TaperedCylinder::new(-Vec3::Y, Vec3::Y, 0.8, 0.0, false).unwrap(),
            ),
        ),
        (
            "ellipsoid",
            Shape::Ellipsoid(Ellipsoid::new(Vec3::ZERO, Vec3::new(1.0, 0.5, 0.7)).unwrap()),
        ),
        (
            "paraboloid (capped)",
            Shape::Paraboloid(Paraboloid::new(-Vec3::Y, 0.8, 1.6, true).unwrap()),
        ),
        (
            "torus",
            Shape::Torus(Torus::new(Vec3::ZERO, 0.7, 0.3).unwrap()),
        ),
    ]
}

fn intersection(c: &mut Criterion) {
    let rays = rays_at_origin();
    let mut group = c.benchmark_group("intersect 256 rays");
    for (name, shape) in shapes() {
        group.bench_function(name, |b| {
            b.iter(|| {
                rays.iter()
                    .filter(|r| black_box(&shape).intersect(r, 0.0, f32::INFINITY).is_some())
                    .count()
            })
        });
    }
    let triangle = Triangle::new(
        [
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, -1.0, 0.0),
            Vec3::Y,
        ],
        0,
    );
    group.bench_function("triangle (watertight)", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| {
                    black_box(&triangle)
                        .intersect(r, 0.0, f32::INFINITY)
                        .is_some()
                })
                .count()
        })
    });
    group.finish();
}

criterion_group!(benches, intersection);
criterion_main!(benches);
