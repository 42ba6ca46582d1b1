//! The shapes' WGSL against the CPU's intersection: the same random rays through the same random
//! shapes, each ray's closest hit found on the GPU (`shaders/first_hits.wgsl`) and on the CPU,
//! and the structs Rust and WGSL share laid out alike. These tests need a GPU adapter: without
//! one they fail, saying what to install (Mesa's lavapipe will do).

mod common;

use common::random::{Rng, direction, in_cube, in_range};
use raylab::gpu::device::GpuDevice;
use raylab::gpu::shapes::{FIRST_HITS_WGSL, GpuHit, GpuRay, GpuSphere, NO_OBJECT, first_hits};
use raylab::ray::Ray;
use raylab::shapes::Sphere;

fn gpu() -> GpuDevice {
    GpuDevice::new().unwrap_or_else(|e| panic!("these tests run on a GPU: {e}"))
}

/// The closest hit of `ray` among `spheres` on the CPU, as the GPU's entry point looks for it.
fn cpu_first_hit(spheres: &[Sphere], ray: &GpuRay) -> GpuHit {
    let r = Ray::new(ray.origin.into(), ray.dir.into());
    let mut best = GpuHit {
        t: ray.t_max,
        object: NO_OBJECT,
    };
    for (k, sphere) in spheres.iter().enumerate() {
        if let Some(hit) = sphere.intersect(&r, ray.t_min, best.t) {
            best = GpuHit {
                t: hit.t,
                object: k as u32,
            };
        }
    }
    best
}

#[test]
fn spheres_give_the_cpus_closest_hits_on_random_rays() {
    let gpu = gpu();
    let mut rng = Rng::with_seed(31);
    let spheres: Vec<Sphere> = (0..24)
        .map(|_| Sphere::new(in_cube(&mut rng, -10.0, 10.0), in_range(&mut rng, 0.2, 3.0)).unwrap())
        .collect();
    // Rays from all around, half of them aimed at a sphere so that most hit something.
    let rays: Vec<GpuRay> = (0..40_000)
        .map(|i| {
            let origin = in_cube(&mut rng, -20.0, 20.0);
            let dir = if i % 2 == 0 {
                let target = &spheres[rng.usize(..spheres.len())];
                (target.center + direction(&mut rng) * target.radius * 0.9 - origin).normalize()
            } else {
                direction(&mut rng)
            };
            GpuRay::new(&Ray::new(origin, dir), 1e-3, f32::INFINITY)
        })
        .collect();
    let on_gpu = first_hits(&gpu, &spheres, &rays).unwrap();
    assert_eq!(on_gpu.len(), rays.len());
    let (mut compared, mut grazing) = (0, 0);
    for (i, (ray, gpu_hit)) in rays.iter().zip(&on_gpu).enumerate() {
        let cpu_hit = cpu_first_hit(&spheres, ray);
        let r = Ray::new(ray.origin.into(), ray.dir.into());
        // Away from grazing angles and from two spheres hit at almost the same `t`.
        if cpu_hit.object != NO_OBJECT {
            let sphere = spheres[cpu_hit.object as usize];
            let cos = sphere.normal(r.at(cpu_hit.t)).dot(r.dir).abs();
            let runner_up = spheres
                .iter()
                .enumerate()
                .filter(|&(k, _)| k as u32 != cpu_hit.object)
                .filter_map(|(_, s)| s.intersect(&r, ray.t_min, f32::INFINITY))
                .map(|h| h.t)
                .fold(f32::INFINITY, f32::min);
            if cos < 0.05 || (runner_up - cpu_hit.t).abs() < 1e-3 * cpu_hit.t {
                grazing += 1;
                continue;
            }
        }
        assert_eq!(
            gpu_hit.object, cpu_hit.object,
            "ray {i} {ray:?}: GPU {gpu_hit:?}, CPU {cpu_hit:?}"
        );
        if cpu_hit.object != NO_OBJECT {
            let error = (gpu_hit.t - cpu_hit.t).abs() / cpu_hit.t;
            assert!(
                error < 1e-4,
                "ray {i} {ray:?}: GPU t {} against CPU t {} (relative {error:e})",
                gpu_hit.t,
                cpu_hit.t
            );
            compared += 1;
        }
    }
    assert!(
        compared >= 10_000,
        "{compared} hits compared ({grazing} grazing or tied left out)"
    );
}

#[test]
fn rays_past_every_sphere_miss_on_the_gpu_too() {
    let gpu = gpu();
    let spheres = [Sphere::new(glam::Vec3::ZERO, 1.0).unwrap()];
    let rays = [
        GpuRay::new(
            &Ray::new(glam::Vec3::new(0.0, 2.0, -5.0), glam::Vec3::Z),
            1e-3,
            100.0,
        ),
        // Aimed at the sphere, but the range ends before it.
        GpuRay::new(
            &Ray::new(glam::Vec3::new(0.0, 0.0, -5.0), glam::Vec3::Z),
            1e-3,
            3.0,
        ),
        // From inside: the far side.
        GpuRay::new(&Ray::new(glam::Vec3::ZERO, glam::Vec3::X), 1e-3, 100.0),
    ];
    let hits = first_hits(&gpu, &spheres, &rays).unwrap();
    assert_eq!(hits[0].object, NO_OBJECT);
    assert_eq!(hits[0].t, 100.0);
    assert_eq!(hits[1].object, NO_OBJECT);
    assert_eq!((hits[2].object, hits[2].t), (0, 1.0));
}

/// The size of the WGSL struct `name` and the offsets of its members, as naga lays them out.
fn wgsl_layout(name: &str) -> (u32, Vec<(String, u32)>) {
    let module = naga::front::wgsl::parse_str(FIRST_HITS_WGSL).unwrap();
    let ty = module
        .types
        .iter()
        .map(|(_, ty)| ty)
        .find(|ty| ty.name.as_deref() == Some(name))
        .unwrap_or_else(|| panic!("no struct {name} in the WGSL"));
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        panic!("{name} is not a struct");
    };
    let offsets = members
        .iter()
        .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
        .collect();
    (*span, offsets)
}

#[test]
fn the_structs_rust_and_wgsl_share_have_the_same_layout() {
    use std::mem::{offset_of, size_of};
    let field = |name: &str, offset: usize| (name.to_string(), offset as u32);
    let cases = [
        (
            "Sphere",
            size_of::<GpuSphere>(),
            vec![
                field("center", offset_of!(GpuSphere, center)),
                field("radius", offset_of!(GpuSphere, radius)),
            ],
        ),
        (
            "Ray",
            size_of::<GpuRay>(),
            vec![
                field("origin", offset_of!(GpuRay, origin)),
                field("t_min", offset_of!(GpuRay, t_min)),
                field("dir", offset_of!(GpuRay, dir)),
                field("t_max", offset_of!(GpuRay, t_max)),
            ],
        ),
        (
            "Hit",
            size_of::<GpuHit>(),
            vec![
                field("t", offset_of!(GpuHit, t)),
                field("object", offset_of!(GpuHit, object)),
            ],
        ),
    ];
    for (name, rust_size, rust_offsets) in cases {
        let (wgsl_size, wgsl_offsets) = wgsl_layout(name);
        assert_eq!(wgsl_size as usize, rust_size, "size of {name}");
        assert_eq!(wgsl_offsets, rust_offsets, "fields of {name}");
    }
}

#[test]
fn more_rays_than_the_gpu_dispatches_are_refused_with_the_limit() {
    let gpu = gpu();
    let max_groups = gpu.device.limits().max_compute_workgroups_per_dimension as usize;
    let too_many = (max_groups + 1) * 64;
    let rays = vec![GpuRay::new(&Ray::new(glam::Vec3::ZERO, glam::Vec3::Z), 1e-3, 1.0); too_many];
    let spheres = [Sphere::new(glam::Vec3::ZERO, 1.0).unwrap()];
    match first_hits(&gpu, &spheres, &rays) {
        Err(e) => assert!(
            e.contains("workgroups") && e.contains(&max_groups.to_string()) || e.contains("bytes"),
            "{e}"
        ),
        Ok(_) => panic!("{too_many} rays were dispatched"),
    }
}
