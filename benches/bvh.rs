//! The BVH: building it, and walking it for the closest hit and for any hit (shadow rays), with
//! coherent rays (a camera's eye rays, and shadow rays from what they hit towards a light) and
//! incoherent ones (random origins and directions), on the generated 100,000-triangle mesh.

mod common;

use std::hint::black_box;
use std::ops::ControlFlow;

use common::{camera_rays, in_tiles, random_rays};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::bvh::packet::PACKET_SIZE;
use raylab::large_mesh::bumpy_sphere_scene;
use raylab::primitive::Geometry;
use raylab::ray::Ray;

const TRIANGLES: usize = 100_000;

/// Whether anything blocks each segment `(ray, 0, length)`: the any-hit query of shadow rays.
fn count_blocked(bvh: &Bvh, geometry: &Geometry, segments: &[(Ray, f32)]) -> usize {
    segments
        .iter()
        .filter(|(ray, length)| {
            let mut blocked = false;
            bvh.any_hit(geometry, ray, 0.0, *length, |_| {
                blocked = true;
                ControlFlow::Break(())
            });
            blocked
        })
        .count()
}

fn count_hits(bvh: &Bvh, geometry: &Geometry, rays: &[Ray]) -> usize {
    rays.iter()
        .filter(|r| bvh.closest_hit(geometry, r, 0.0, f32::INFINITY).is_some())
        .count()
}

/// [`count_hits`] with the rays traced [`PACKET_SIZE`] at a time.
fn count_hits_in_packets(bvh: &Bvh, geometry: &Geometry, rays: &[Ray]) -> usize {
    let mut hits = [None; PACKET_SIZE];
    rays.chunks(PACKET_SIZE)
        .map(|packet| {
            let hits = &mut hits[..packet.len()];
            bvh.closest_hits(geometry, packet, 0.0, f32::INFINITY, hits);
            hits.iter().filter(|h| h.is_some()).count()
        })
        .sum()
}

fn bvh(c: &mut Criterion) {
    let scene = bumpy_sphere_scene(TRIANGLES, 128, 128);
    let geometry = &scene.geometry;
    let mut group = c.benchmark_group("bvh, 100k-triangle mesh");
    group.sample_size(20);
    group.bench_function("build", |b| b.iter(|| Bvh::build(black_box(geometry))));

    let bvh = Bvh::build(geometry);
    let camera = camera_rays(&scene, 128);
    let random = random_rays(
        16384,
        Vec3::new(-1.2, 0.0, -1.2),
        Vec3::new(1.2, 2.2, 1.2),
        3,
    );
    let light = Vec3::new(4.0, 6.0, 5.0);
    let shadow: Vec<(Ray, f32)> = camera
        .iter()
        .filter_map(|r| {
            let hit = bvh.closest_hit(geometry, r, 0.0, f32::INFINITY)?;
            let from = r.at(hit.t * 0.9999);
            Some((
                Ray::new(from, (light - from).normalize()),
                light.distance(from),
            ))
        })
        .collect();
    let segments: Vec<(Ray, f32)> = random.iter().map(|r| (*r, 1.0)).collect();

    group.bench_function("closest hit, 16384 camera rays", |b| {
        b.iter(|| count_hits(&bvh, geometry, black_box(&camera)))
    });
    let tiled = in_tiles(&camera, 128);
    group.bench_function(
        "closest hit, 16384 camera rays in 8×8 tiles, one by one",
        |b| b.iter(|| count_hits(&bvh, geometry, black_box(&tiled))),
    );
    group.bench_function(
        "closest hit, 16384 camera rays in 8×8 tiles, as packets",
        |b| b.iter(|| count_hits_in_packets(&bvh, geometry, black_box(&tiled))),
    );
    group.bench_function("closest hit, 16384 random rays", |b| {
        b.iter(|| count_hits(&bvh, geometry, black_box(&random)))
    });
    group.bench_function("any hit, shadow rays from the camera's hits", |b| {
        b.iter(|| count_blocked(&bvh, geometry, black_box(&shadow)))
    });
    group.bench_function("any hit, 16384 random segments", |b| {
        b.iter(|| count_blocked(&bvh, geometry, black_box(&segments)))
    });
    group.finish();
}

criterion_group!(benches, bvh);
criterion_main!(benches);
