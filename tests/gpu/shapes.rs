//! The GPU's parts against the CPU's on the same rays: each shape's WGSL against its Rust twin
//! (every object tried one by one, `shaders/probe.wgsl`), the BVH's walk against
//! `Bvh::closest_hit`, every kind of texture against `Texture::color`, the structs Rust and WGSL
//! share laid out alike, and the WGSL valid as a whole. These tests need a GPU adapter: without one they fail, saying what to install
//! (Mesa's lavapipe will do).

use std::sync::Arc;

use crate::common::random::{Rng, direction, in_cube, in_range};
use crate::gpu;
use glam::{Vec2, Vec3};
use raylab::aabb::Aabb;
use raylab::camera::{Camera, PIXEL_CENTRE};
use raylab::color::Color;
use raylab::gpu::bvh::NodeLayout;
use raylab::gpu::caustics::GpuPhoton;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::item_raster::{CpuItems, proxy_box};
use raylab::gpu::probe::{
    NO_PRIM, ProbeHit, ProbeRay, Search, TextureProbe, closest_hits, texture_colors,
};
use raylab::gpu::record::{GpuRecord, wgsl_name};
use raylab::gpu::scene::GpuScene;
use raylab::gpu::tracer::tracer_wgsl;
use raylab::material::Material;
use raylab::memory::Bytes;
use raylab::mesh::Mesh;
use raylab::primitive::{PrimId, PrimKind};
use raylab::ray::Ray;
use raylab::render::{Assembled, assemble};
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{
    Csg, CsgOperation, Cuboid, Ellipsoid, Operand, Paraboloid, Plane, Polygon, Shape, Sphere,
    TaperedCylinder, Torus,
};
use raylab::srgb_image::SrgbImage;
use raylab::texture::{Texture, WOOD_COLORS, Wrap};
use raylab::transform::{Transform, TransformStep};
use raylab::whitted::EYE_RAY_T_MIN;
use strum::IntoEnumIterator;

/// A scene of `objects` (each shape with its transform, if any) and `meshes`, one material,
/// ready on the CPU.
fn scene_of(objects: Vec<(Shape, Option<Transform>)>, meshes: Vec<Mesh>) -> Assembled {
    let mut scene = Scene::new(RenderSettings::default(), Camera::default());
    let material = scene.add_material(Material::default());
    for (shape, transform) in objects {
        scene.add_object(shape, transform, material);
    }
    for mesh in meshes {
        scene.geometry.add_mesh(mesh);
    }
    assemble(scene).unwrap()
}

/// The closest hit of `ray` on the CPU as the probe reports it, by `Geometry::intersect` of
/// every object (`search` Objects) or by the BVH.
fn cpu_hit(assembled: &Assembled, search: Search, ray: &ProbeRay) -> ProbeHit {
    let r = Ray::new(ray.origin.into(), ray.dir.into());
    let geometry = &assembled.scene.geometry;
    let hit = match search {
        Search::Objects => {
            let mut best = None;
            let mut t_max = ray.t_max;
            for id in (0..geometry.objects.len()).map(PrimId::object) {
                if let Some(hit) = geometry.intersect(id, &r, ray.t_min, t_max) {
                    t_max = hit.t;
                    best = Some(hit);
                }
            }
            best
        }
        Search::Bvh => assembled
            .bvh
            .closest_hit(geometry, &r, ray.t_min, ray.t_max),
    };
    match hit {
        None => ProbeHit {
            normal: [0.0; 3],
            t: ray.t_max,
            uv: [0.0; 2],
            prim: NO_PRIM,
            part: 0,
        },
        Some(hit) => {
            let surface = geometry.surface(&r, &hit);
            ProbeHit {
                normal: surface.normal.to_array(),
                t: hit.t,
                uv: surface.uv.to_array(),
                prim: hit.prim.0,
                part: hit.part,
            }
        }
    }
}

/// Shapes without a transform, for [`scene_of`].
fn untransformed(shapes: Vec<Shape>) -> Vec<(Shape, Option<Transform>)> {
    shapes.into_iter().map(|shape| (shape, None)).collect()
}

/// Compares the GPU's hits with the CPU's: the same primitive and part, `t` within 10⁻⁴
/// relative (absolute below 1, where the rounding of the ray's coordinates, which are about 1
/// or larger, outweighs that of `t`: a ray starting 0.003 from a plane), the normal within 10⁻³ and the texture coordinates within 10⁻³ (relative where
/// they are larger than 1, as a plane's are), away from grazing hits and near ties (where
/// rounding may pick the other primitive), which are counted. Returns how many hits were
/// compared, and prints it with the largest error of `t`.
pub fn compare(
    assembled: &Assembled,
    search: Search,
    rays: &[ProbeRay],
    on_gpu: &[ProbeHit],
) -> usize {
    assert_eq!(on_gpu.len(), rays.len());
    let (mut compared, mut left_out) = (0, 0);
    let mut max_t_error = 0.0f32;
    for (i, (ray, gpu_hit)) in rays.iter().zip(on_gpu).enumerate() {
        let cpu = cpu_hit(assembled, search, ray);
        let dir = Vec3::from(ray.dir).normalize();
        let grazing = cpu.prim != NO_PRIM && Vec3::from(cpu.normal).dot(dir).abs() < 0.05;
        // The runner-up: the closest hit beyond a sliver past the CPU's.
        let beyond = ProbeRay {
            t_min: cpu.t * (1.0 + 1e-3),
            ..*ray
        };
        let tied = cpu.prim != NO_PRIM && {
            let next = cpu_hit(assembled, search, &beyond);
            next.prim != NO_PRIM && next.prim != cpu.prim && next.t < cpu.t * (1.0 + 2e-3)
        };
        if grazing || tied {
            left_out += 1;
            continue;
        }
        assert_eq!(
            (gpu_hit.prim, gpu_hit.part),
            (cpu.prim, cpu.part),
            "ray {i} {ray:?}: GPU {gpu_hit:?}, CPU {cpu:?}"
        );
        if cpu.prim != NO_PRIM {
            let error = (gpu_hit.t - cpu.t).abs() / cpu.t.max(1.0);
            assert!(
                error < 1e-4,
                "ray {i} {ray:?}: GPU {gpu_hit:?}, CPU {cpu:?} (t off by {error:e})"
            );
            let normal_error = (Vec3::from(gpu_hit.normal) - Vec3::from(cpu.normal)).length();
            assert!(
                normal_error < 1e-3,
                "ray {i} {ray:?}: GPU {gpu_hit:?}, CPU {cpu:?}"
            );
            let tolerance = 1e-3 * Vec2::from(cpu.uv).abs().max_element().max(1.0);
            let mut uv_error = (Vec2::from(gpu_hit.uv) - Vec2::from(cpu.uv)).abs();
            // The round shapes' u jumps from 1 to 0 at their seam (where `atan2` goes from π to
            // −π), so a point on the seam may get either: a difference of 1 there is none.
            if (uv_error.x - 1.0).abs() < tolerance {
                uv_error.x = (uv_error.x - 1.0).abs();
            }
            assert!(
                uv_error.max_element() < tolerance,
                "ray {i} {ray:?}: GPU {gpu_hit:?}, CPU {cpu:?} (uv off by {uv_error})"
            );
            max_t_error = max_t_error.max(error);
            compared += 1;
        }
    }
    println!(
        "{search:?}: {compared} hits compared, {left_out} left out, t off by {max_t_error:e} at most"
    );
    assert!(
        left_out * 20 < rays.len(),
        "{left_out} of {} rays grazing or tied",
        rays.len()
    );
    compared
}

/// `count` rays from all around the box `-extent..extent`, every other one aimed at a point
/// `aim` gives, so that most hit something.
fn rays_towards(
    rng: &mut Rng,
    count: usize,
    extent: f32,
    mut aim: impl FnMut(&mut Rng) -> Vec3,
) -> Vec<ProbeRay> {
    (0..count)
        .map(|i| {
            let origin = in_cube(rng, -extent, extent);
            let dir = if i % 2 == 0 {
                (aim(rng) - origin).normalize()
            } else {
                direction(rng)
            };
            ProbeRay::new(&Ray::new(origin, dir), 1e-3, f32::MAX)
        })
        .collect()
}

#[test]
fn spheres_give_the_cpus_closest_hits_on_random_rays() {
    let gpu = gpu();
    let mut rng = Rng::with_seed(31);
    let spheres: Vec<Sphere> = (0..24)
        .map(|_| Sphere::new(in_cube(&mut rng, -10.0, 10.0), in_range(&mut rng, 0.2, 3.0)).unwrap())
        .collect();
    let assembled = scene_of(
        untransformed(spheres.iter().map(|s| Shape::Sphere(*s)).collect()),
        Vec::new(),
    );
    let rays = rays_towards(&mut rng, 40_000, 20.0, |rng| {
        let target = spheres[rng.usize(..spheres.len())];
        target.center + direction(rng) * target.radius * 0.9
    });
    let scene = GpuScene::upload(&gpu, &assembled).unwrap();
    for search in [Search::Objects, Search::Bvh] {
        let on_gpu = closest_hits(&gpu, &scene, search, &rays).unwrap();
        let compared = compare(&assembled, search, &rays, &on_gpu);
        assert!(compared >= 10_000, "{search:?}: {compared} hits compared");
    }
}

#[test]
fn rays_past_every_sphere_miss_on_the_gpu_too() {
    let gpu = gpu();
    let assembled = scene_of(
        untransformed(vec![Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap())]),
        Vec::new(),
    );
    let scene = GpuScene::upload(&gpu, &assembled).unwrap();
    let rays = [
        ProbeRay::new(&Ray::new(Vec3::new(0.0, 2.0, -5.0), Vec3::Z), 1e-3, 100.0),
        // Aimed at the sphere, but the range ends before it.
        ProbeRay::new(&Ray::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z), 1e-3, 3.0),
        // From inside: the far side.
        ProbeRay::new(&Ray::new(Vec3::ZERO, Vec3::X), 1e-3, 100.0),
    ];
    for search in [Search::Objects, Search::Bvh] {
        let hits = closest_hits(&gpu, &scene, search, &rays).unwrap();
        assert_eq!((hits[0].prim, hits[0].t), (NO_PRIM, 100.0), "{search:?}");
        assert_eq!(hits[1].prim, NO_PRIM, "{search:?}");
        assert_eq!(
            (hits[2].prim, hits[2].t),
            (PrimId::object(0).0, 1.0),
            "{search:?}"
        );
        assert_eq!(hits[2].normal, [1.0, 0.0, 0.0], "{search:?}");
    }
}

/// A random placement: a non-uniform scale, a turn about a random axis, then a move to `to`.
fn random_transform(rng: &mut Rng, to: Vec3) -> Transform {
    let scale = Vec3::new(
        in_range(rng, 0.5, 2.0),
        in_range(rng, 0.5, 2.0),
        in_range(rng, 0.5, 2.0),
    );
    Transform::from_steps(&[
        TransformStep::Scale(scale),
        TransformStep::Rotate {
            axis: direction(rng),
            degrees: in_range(rng, 0.0, 360.0),
        },
        TransformStep::Translate(to),
    ])
    .unwrap()
}

/// `count` shapes from `make`, each about a random point of the box `-extent..extent`: every
/// other one made about the origin and moved there by a [`random_transform`].
fn random_objects(
    rng: &mut Rng,
    count: usize,
    extent: f32,
    mut make: impl FnMut(&mut Rng, Vec3) -> Shape,
) -> Vec<(Shape, Option<Transform>)> {
    (0..count)
        .map(|i| {
            let at = in_cube(rng, -extent, extent);
            if i % 2 == 0 {
                (make(rng, at), None)
            } else {
                (make(rng, Vec3::ZERO), Some(random_transform(rng, at)))
            }
        })
        .collect()
}

/// A random point in the world bounds of a random bounded object of `assembled`.
fn in_some_bounds(rng: &mut Rng, assembled: &Assembled) -> Vec3 {
    let geometry = &assembled.scene.geometry;
    loop {
        let id = PrimId::object(rng.usize(..geometry.objects.len()));
        if let Some(b) = geometry.bounds(id) {
            let f = in_cube(rng, 0.0, 1.0);
            return b.min + (b.max - b.min) * f;
        }
    }
}

/// `count` random rays at `objects`, on the GPU and on the CPU, by both searches: at least
/// 10,000 hits compared by each. Returns the GPU's hits by the BVH.
fn check_random_objects(
    rng: &mut Rng,
    objects: Vec<(Shape, Option<Transform>)>,
    count: usize,
) -> Vec<ProbeHit> {
    let gpu = gpu();
    let assembled = scene_of(objects, Vec::new());
    let rays = rays_towards(rng, count, 20.0, |rng| in_some_bounds(rng, &assembled));
    let scene = GpuScene::upload(&gpu, &assembled).unwrap();
    let mut on_gpu = Vec::new();
    for search in [Search::Objects, Search::Bvh] {
        on_gpu = closest_hits(&gpu, &scene, search, &rays).unwrap();
        let compared = compare(&assembled, search, &rays, &on_gpu);
        assert!(compared >= 10_000, "{search:?}: {compared} hits compared");
    }
    on_gpu
}

/// How many of `hits` are on the first `count` objects.
fn hits_on_first(hits: &[ProbeHit], count: usize) -> usize {
    let first: Vec<u32> = (0..count).map(|i| PrimId::object(i).0).collect();
    hits.iter().filter(|h| first.contains(&h.prim)).count()
}

#[test]
fn cuboids_give_the_cpus_closest_hits_on_random_rays() {
    let mut rng = Rng::with_seed(41);
    let objects = random_objects(&mut rng, 24, 10.0, |rng, at| {
        let half = in_cube(rng, 0.2, 2.0);
        Shape::Cuboid(Cuboid::new(at - half, at + half).unwrap())
    });
    check_random_objects(&mut rng, objects, 40_000);
}

#[test]
fn ellipsoids_give_the_cpus_closest_hits_on_random_rays() {
    let mut rng = Rng::with_seed(42);
    let objects = random_objects(&mut rng, 24, 10.0, |rng, at| {
        Shape::Ellipsoid(Ellipsoid::new(at, in_cube(rng, 0.2, 2.0)).unwrap())
    });
    check_random_objects(&mut rng, objects, 40_000);
}

#[test]
fn tapered_cylinders_give_the_cpus_closest_hits_on_random_rays() {
    let mut rng = Rng::with_seed(43);
    // Cylinders, cones pointing up and down, and truncated cones, capped or open.
    let objects = random_objects(&mut rng, 24, 10.0, |rng, at| {
        let half_axis = direction(rng) * in_range(rng, 0.3, 2.0);
        let radius = in_range(rng, 0.2, 1.5);
        let (base_radius, top_radius) = match rng.u32(..4) {
            0 => (radius, radius),
            1 => (radius, 0.0),
            2 => (0.0, radius),
            _ => (radius, in_range(rng, 0.2, 1.5)),
        };
        let cylinder = TaperedCylinder::new(
            at - half_axis,
            at + half_axis,
            base_radius,
            top_radius,
            rng.bool(),
        );
        Shape::TaperedCylinder(cylinder.unwrap())
    });
    check_random_objects(&mut rng, objects, 40_000);
}

#[test]
fn paraboloids_give_the_cpus_closest_hits_on_random_rays() {
    let mut rng = Rng::with_seed(44);
    let objects = random_objects(&mut rng, 24, 10.0, |rng, at| {
        let radius = in_range(rng, 0.3, 2.0);
        let height = in_range(rng, 0.3, 2.0);
        Shape::Paraboloid(Paraboloid::new(at, radius, height, rng.bool()).unwrap())
    });
    check_random_objects(&mut rng, objects, 40_000);
}

/// A polygon about `at` in a random plane: 3 to 40 vertices around it at random distances, so
/// that many are concave and those of more than 8 edges are split into several bands.
fn random_polygon(rng: &mut Rng, at: Vec3) -> Polygon {
    let (s, t) = direction(rng).any_orthonormal_pair();
    let count = rng.usize(3..=40);
    let vertices = (0..count)
        .map(|i| {
            let angle = (i as f32 + in_range(rng, 0.0, 0.8)) * std::f32::consts::TAU / count as f32;
            let radius = in_range(rng, 0.5, 2.5);
            at + (s * angle.cos() + t * angle.sin()) * radius
        })
        .collect();
    Polygon::new(vertices).unwrap()
}

#[test]
fn polygons_give_the_cpus_closest_hits_on_random_rays() {
    let mut rng = Rng::with_seed(45);
    let objects = random_objects(&mut rng, 24, 10.0, |rng, at| {
        Shape::Polygon(random_polygon(rng, at))
    });
    // Rays aimed into a flat polygon's bounds miss it more often than not.
    check_random_objects(&mut rng, objects, 80_000);
}

/// Planes, which the BVH keeps in a list that every ray tests, among boxes and ellipsoids in
/// its tree.
#[test]
fn planes_among_bounded_shapes_give_the_cpus_closest_hits_on_random_rays() {
    let mut rng = Rng::with_seed(46);
    let planes = 4;
    let mut objects = random_objects(&mut rng, planes, 10.0, |rng, at| {
        Shape::Plane(Plane {
            point: at,
            normal: direction(rng),
        })
    });
    objects.extend(random_objects(&mut rng, 16, 10.0, |rng, at| {
        if rng.bool() {
            let half = in_cube(rng, 0.2, 2.0);
            Shape::Cuboid(Cuboid::new(at - half, at + half).unwrap())
        } else {
            Shape::Ellipsoid(Ellipsoid::new(at, in_cube(rng, 0.2, 2.0)).unwrap())
        }
    }));
    let on_gpu = check_random_objects(&mut rng, objects, 40_000);
    let on_planes = hits_on_first(&on_gpu, planes);
    assert!(on_planes >= 10_000, "{on_planes} hits on planes");
}

/// A random closed solid about `at`, about a unit in size: a sphere, a box, an ellipsoid, a
/// capped cone or cylinder, a capped paraboloid or a torus.
fn random_solid(rng: &mut Rng, at: Vec3) -> Shape {
    match rng.u32(..6) {
        0 => Shape::Sphere(Sphere::new(at, in_range(rng, 0.5, 1.5)).unwrap()),
        1 => {
            let half = in_cube(rng, 0.4, 1.2);
            Shape::Cuboid(Cuboid::new(at - half, at + half).unwrap())
        }
        2 => Shape::Ellipsoid(Ellipsoid::new(at, in_cube(rng, 0.4, 1.5)).unwrap()),
        3 => {
            let half_axis = direction(rng) * in_range(rng, 0.4, 1.5);
            let radii = (in_range(rng, 0.3, 1.0), in_range(rng, 0.0, 1.0));
            let cylinder =
                TaperedCylinder::new(at - half_axis, at + half_axis, radii.0, radii.1, true);
            Shape::TaperedCylinder(cylinder.unwrap())
        }
        4 => {
            let (radius, height) = (in_range(rng, 0.4, 1.2), in_range(rng, 0.4, 1.5));
            Shape::Paraboloid(Paraboloid::new(at, radius, height, true).unwrap())
        }
        _ => {
            let major = in_range(rng, 0.6, 1.2);
            let minor = major * in_range(rng, 0.25, 0.6);
            Shape::Torus(Torus::new(at, major, minor).unwrap())
        }
    }
}

/// A random CSG node about `at`: the union, intersection or difference of 2 to 4 random solids,
/// every other one placed by a [`random_transform`], with a plane's half-space among those of an
/// intersection or subtracted in a third of them (never where the node would reach infinitely
/// far) and, where `nest`, a nested node of the same kind in place of a solid now and then.
fn random_csg(rng: &mut Rng, at: Vec3, nest: bool) -> Csg {
    let operation = match rng.u32(..3) {
        0 => CsgOperation::Union,
        1 => CsgOperation::Intersection,
        _ => CsgOperation::Difference,
    };
    let count = rng.usize(2..=4);
    let plane =
        (operation != CsgOperation::Union && rng.u32(..3) == 0).then(|| rng.usize(1..count));
    let children = (0..count)
        .map(|k| {
            let to = at + in_cube(rng, -0.8, 0.8);
            let (shape, transform) = if plane == Some(k) {
                let shape = Shape::Plane(Plane {
                    point: to,
                    normal: direction(rng),
                });
                (shape, None)
            } else if nest && rng.u32(..4) == 0 {
                (Shape::Csg(Box::new(random_csg(rng, to, false))), None)
            } else if rng.bool() {
                (random_solid(rng, to), None)
            } else {
                (
                    random_solid(rng, Vec3::ZERO),
                    Some(random_transform(rng, to)),
                )
            };
            Operand {
                shape,
                transform,
                material: 0,
            }
        })
        .collect();
    Csg::new(operation, children).unwrap()
}

#[test]
fn csg_objects_give_the_cpus_closest_hits_on_random_rays() {
    let mut rng = Rng::with_seed(47);
    let objects = random_objects(&mut rng, 24, 10.0, |rng, at| {
        Shape::Csg(Box::new(random_csg(rng, at, true)))
    });
    let leaves: Vec<&Shape> = objects
        .iter()
        .flat_map(|(shape, _)| match shape {
            Shape::Csg(csg) => csg.leaves().iter().map(|leaf| &leaf.shape),
            _ => unreachable!(),
        })
        .collect();
    for (kind, count) in [
        (
            "plane",
            leaves
                .iter()
                .filter(|s| matches!(s, Shape::Plane(_)))
                .count(),
        ),
        (
            "torus",
            leaves
                .iter()
                .filter(|s| matches!(s, Shape::Torus(_)))
                .count(),
        ),
    ] {
        assert!(count >= 3, "{count} {kind} operands");
    }
    let nested = objects
        .iter()
        .filter(|(shape, _)| match shape {
            Shape::Csg(csg) => csg.leaves().iter().any(|leaf| leaf.label.contains("(csg)")),
            _ => false,
        })
        .count();
    assert!(nested >= 3, "{nested} nested nodes");
    // Rays aimed into the bounds of an intersection or a difference miss it often.
    check_random_objects(&mut rng, objects, 60_000);
}

/// The largest relative difference in `t` between the GPU's hits and the CPU's where both hit
/// the same primitive, away from grazing hits (as [`compare`] counts them).
fn max_t_error(
    assembled: &Assembled,
    search: Search,
    rays: &[ProbeRay],
    on_gpu: &[ProbeHit],
) -> f32 {
    rays.iter()
        .zip(on_gpu)
        .map(|(ray, gpu_hit)| {
            let cpu = cpu_hit(assembled, search, ray);
            let dir = Vec3::from(ray.dir).normalize();
            if cpu.prim == NO_PRIM
                || cpu.prim != gpu_hit.prim
                || Vec3::from(cpu.normal).dot(dir).abs() < 0.05
            {
                return 0.0;
            }
            (gpu_hit.t - cpu.t).abs() / cpu.t
        })
        .fold(0.0, f32::max)
}

/// A torus around a point of the cube `-extent..extent`, of major radius in `major` and minor
/// radius in `ratio` times that, and a point inside its tube.
fn random_torus(rng: &mut Rng, extent: f32, major: (f32, f32), ratio: (f32, f32)) -> (Torus, Vec3) {
    let center = in_cube(rng, -extent, extent);
    let major = in_range(rng, major.0, major.1);
    let minor = major * in_range(rng, ratio.0, ratio.1);
    let torus = Torus::new(center, major, minor).unwrap();
    let angle = in_range(rng, 0.0, std::f32::consts::TAU);
    let ring = center + Vec3::new(angle.cos(), 0.0, angle.sin()) * major;
    (torus, ring + direction(rng) * minor * 0.9)
}

/// `count` tori made by [`random_torus`], every other one placed by a random transform, and a
/// point inside the tube of each, in the world.
fn random_tori(
    rng: &mut Rng,
    count: usize,
    extent: f32,
    major: (f32, f32),
    ratio: (f32, f32),
) -> (Assembled, Vec<Vec3>) {
    let mut objects = Vec::new();
    let mut inside = Vec::new();
    for k in 0..count {
        let (torus, point) = random_torus(rng, extent, major, ratio);
        let transform = (k % 2 == 1).then(|| {
            let to = in_cube(rng, -extent / 4.0, extent / 4.0);
            random_transform(rng, to)
        });
        inside.push(transform.map_or(point, |t| t.point_to_world(point)));
        objects.push((Shape::Torus(torus), transform));
    }
    (scene_of(objects, Vec::new()), inside)
}

/// The GPU's closest hits of `rays` against the CPU's, by [`compare`], with both searches.
fn compare_both_searches(gpu: &GpuDevice, assembled: &Assembled, rays: &[ProbeRay]) {
    let scene = GpuScene::upload(gpu, assembled).unwrap();
    for search in [Search::Objects, Search::Bvh] {
        let on_gpu = closest_hits(gpu, &scene, search, rays).unwrap();
        let compared = compare(assembled, search, rays, &on_gpu);
        assert!(compared >= 10_000, "{search:?}: {compared} hits compared");
        let error = max_t_error(assembled, search, rays, &on_gpu);
        println!("{search:?}: {compared} hits compared, t off by at most {error:e}");
    }
}

#[test]
fn tori_give_the_cpus_closest_hits_on_random_rays() {
    let gpu = gpu();
    let mut rng = Rng::with_seed(33);
    let (assembled, inside) = random_tori(&mut rng, 24, 10.0, (0.3, 3.0), (0.05, 0.9));
    let mut rays = rays_towards(&mut rng, 40_000, 20.0, |rng| {
        inside[rng.usize(..inside.len())]
    });
    // A hit just past the origin has its t to about 10⁻⁷ in f32, shifted to the ray's point
    // closest to the centre and back, too little for a relative 10⁻⁴ where t is 10⁻³.
    for ray in &mut rays {
        ray.t_min = 0.05;
    }
    compare_both_searches(&gpu, &assembled, &rays);
}

#[test]
fn tori_seen_from_far_away_give_the_cpus_closest_hits() {
    // Rays from about 1000 units off, where a quartic in t solved in f32 has coefficients of
    // order 10¹² that cancel to nothing. There an ulp of t, by which the GPU's t and the CPU's
    // may differ where the exact one lies halfway, moves the hit point by 10⁻⁴: the tubes are
    // thick enough (0.25 of the ring and more) for that to turn their normals by less than
    // compare's 10⁻³.
    let gpu = gpu();
    let mut rng = Rng::with_seed(34);
    let (assembled, inside) = random_tori(&mut rng, 6, 12.0, (0.5, 1.5), (0.25, 0.9));
    let rays: Vec<ProbeRay> = (0..20_000)
        .map(|_| {
            let origin = direction(&mut rng) * in_range(&mut rng, 900.0, 1100.0);
            let target = inside[rng.usize(..inside.len())];
            ProbeRay::new(
                &Ray::new(origin, (target - origin).normalize()),
                1e-3,
                f32::MAX,
            )
        })
        .collect();
    compare_both_searches(&gpu, &assembled, &rays);
}
/// A mesh of `count` random triangles in the box `-extent..extent`, some with vertex normals.
fn random_mesh(rng: &mut Rng, count: usize, extent: f32, normals: bool) -> Mesh {
    let mut mesh = Mesh::default();
    for k in 0..count as u32 {
        let center = in_cube(rng, -extent, extent);
        let size = in_range(rng, 0.3, 2.0);
        for _ in 0..3 {
            mesh.positions.push(center + direction(rng) * size);
            if normals {
                mesh.normals.push(direction(rng));
            }
        }
        mesh.faces.push([3 * k, 3 * k + 1, 3 * k + 2]);
    }
    mesh
}

#[test]
fn the_bvh_walk_finds_the_cpus_closest_hits_among_triangles_and_spheres() {
    let gpu = gpu();
    let mut rng = Rng::with_seed(32);
    let spheres: Vec<Shape> = (0..40)
        .map(|_| {
            let sphere = Sphere::new(in_cube(&mut rng, -12.0, 12.0), in_range(&mut rng, 0.2, 1.5));
            Shape::Sphere(sphere.unwrap())
        })
        .collect();
    let meshes = vec![
        random_mesh(&mut rng, 3000, 12.0, false),
        random_mesh(&mut rng, 1000, 12.0, true),
    ];
    let assembled = scene_of(untransformed(spheres), meshes);
    assert!(assembled.bvh.depth() >= 3, "a tree deep enough to walk");
    let rays = rays_towards(&mut rng, 30_000, 20.0, |rng| in_cube(rng, -12.0, 12.0));
    for nodes in NodeLayout::iter() {
        let scene = GpuScene::upload_with(&gpu, &assembled, nodes).unwrap();
        let on_gpu = closest_hits(&gpu, &scene, Search::Bvh, &rays).unwrap();
        let compared = compare(&assembled, Search::Bvh, &rays, &on_gpu);
        assert!(compared >= 10_000, "{nodes}: {compared} hits compared");
        let triangles = on_gpu.iter().filter(|h| {
            h.prim != NO_PRIM && matches!(PrimId(h.prim).kind(), PrimKind::Triangle(_))
        });
        assert!(
            triangles.count() >= 5_000,
            "{nodes}: most hits are triangles"
        );
    }
}

/// The size of the WGSL struct `name` and the offsets of its members, as naga lays them out.
fn wgsl_layout(module: &naga::Module, name: &str) -> (u32, Vec<(String, u32)>) {
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

/// The tracer's whole WGSL, parsed and validated by naga.
fn tracer_module(nodes: NodeLayout) -> naga::Module {
    parsed(&tracer_wgsl(nodes))
}

/// `source` parsed and validated by naga.
fn parsed(source: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
    module
}

/// Record `T` against its WGSL twin in `module`: the same size, and the same fields by name
/// and offset, in order; what differs, if anything.
fn same_layout<T: GpuRecord>(module: &naga::Module) -> Option<String> {
    let name = wgsl_name::<T>();
    let (wgsl_size, wgsl_fields) = wgsl_layout(module, name);
    let rust_size = size_of::<T>() as u32;
    let rust_fields: Vec<(String, u32)> = T::fields()
        .into_iter()
        .map(|(field, offset)| (field.to_string(), offset as u32))
        .collect();
    ((wgsl_size, &wgsl_fields) != (rust_size, &rust_fields)).then(|| {
        format!(
            "{name}: WGSL {wgsl_size} bytes {wgsl_fields:?}, Rust {rust_size} bytes {rust_fields:?}"
        )
    })
}

#[test]
fn the_structs_rust_and_wgsl_share_have_the_same_layout() {
    use raylab::gpu::bvh::{GpuBinaryNode, GpuTriangle, GpuWideNode};
    use raylab::gpu::film::{FilmPass, FilmPixel, ShowRows, Tally, film_wgsl};
    use raylab::gpu::frame::GpuFrame;
    use raylab::gpu::item_raster::{GpuProxy, ITEM_BUFFER_WGSL};
    use raylab::gpu::materials::{GpuLight, GpuMaterial, GpuTriangleShading, GpuVertexAttributes};
    use raylab::gpu::probe::ProbeHit;
    use raylab::gpu::shapes::GpuObject;
    use raylab::gpu::texture::GpuTexture;
    use raylab::gpu::tracer::{PixelSample, SampleColor};
    let tracer = tracer_module(NodeLayout::Wide);
    let binary = tracer_module(NodeLayout::Binary);
    let film = parsed(&film_wgsl());
    let raster = parsed(&(tracer_wgsl(NodeLayout::Wide) + ITEM_BUFFER_WGSL));
    let differences: Vec<String> = [
        same_layout::<GpuObject>(&tracer),
        same_layout::<GpuWideNode>(&tracer),
        same_layout::<GpuTriangle>(&tracer),
        same_layout::<GpuTriangleShading>(&tracer),
        same_layout::<GpuVertexAttributes>(&tracer),
        same_layout::<GpuMaterial>(&tracer),
        same_layout::<GpuLight>(&tracer),
        same_layout::<GpuFrame>(&tracer),
        same_layout::<PixelSample>(&tracer),
        same_layout::<GpuPhoton>(&tracer),
        same_layout::<SampleColor>(&tracer),
        same_layout::<ProbeRay>(&tracer),
        same_layout::<ProbeHit>(&tracer),
        same_layout::<GpuTexture>(&tracer),
        same_layout::<TextureProbe>(&tracer),
        same_layout::<GpuBinaryNode>(&binary),
        same_layout::<PixelSample>(&film),
        same_layout::<FilmPixel>(&film),
        same_layout::<FilmPass>(&film),
        same_layout::<Tally>(&film),
        same_layout::<ShowRows>(&film),
        same_layout::<GpuProxy>(&raster),
    ]
    .into_iter()
    .flatten()
    .collect();
    assert!(differences.is_empty(), "{differences:#?}");
}

/// A `width × height` image of random texels.
fn random_image(rng: &mut Rng, width: u32, height: u32) -> Arc<SrgbImage> {
    let pixels = (0..width * height)
        .map(|_| [rng.u8(..), rng.u8(..), rng.u8(..)])
        .collect();
    Arc::new(SrgbImage::new(width, height, pixels))
}

#[test]
fn every_kind_of_texture_gives_the_cpus_colours_at_random_points() {
    let gpu = gpu();
    let mut rng = Rng::with_seed(33);
    let (a, b) = (Color::new(0.9, 0.8, 0.2), Color::new(0.1, 0.3, 0.7));
    let textures = vec![
        Texture::Checker3d { a, b, size: 0.7 },
        Texture::CheckerUv {
            a,
            b,
            u_count: 5.0,
            v_count: 3.0,
        },
        Texture::Wood {
            a: WOOD_COLORS.0,
            b: WOOD_COLORS.1,
        },
        Texture::Marble {
            color: Color::new(0.9, 0.85, 0.8),
        },
        Texture::Image {
            image: random_image(&mut rng, 7, 5),
            wrap: [Wrap::Repeat, Wrap::Mirror],
            scale: Vec2::new(2.5, 1.5),
            offset: Vec2::new(0.3, -0.2),
        },
        Texture::Image {
            image: random_image(&mut rng, 4, 6),
            wrap: [Wrap::Clamp, Wrap::Repeat],
            scale: Vec2::new(0.8, 1.2),
            offset: Vec2::new(0.1, 0.05),
        },
        Texture::Image {
            image: random_image(&mut rng, 5, 3),
            wrap: [Wrap::Mirror, Wrap::Clamp],
            scale: Vec2::new(3.5, 2.5),
            offset: Vec2::new(-0.7, 0.4),
        },
    ];
    let background = random_image(&mut rng, 9, 4);
    let mut scene = Scene::new(RenderSettings::default(), Camera::default());
    scene.textures = textures.clone();
    scene.background_image = Some(Arc::clone(&background));
    let material = scene.add_material(Material::default());
    let sphere = Sphere::new(Vec3::ZERO, 1.0).unwrap();
    scene.add_object(Shape::Sphere(sphere), None, material);
    let assembled = assemble(scene).unwrap();
    let gpu_scene = GpuScene::upload(&gpu, &assembled).unwrap();
    // The CPU's colour of each texture record: the scene's textures, then the background image.
    let cpu_color = |texture: usize, uv: Vec2, point: Vec3| match textures.get(texture) {
        Some(t) => t.color(uv, point),
        None => background.sample(uv, [Wrap::Clamp; 2]),
    };
    let per_texture = 10_000;
    let probes: Vec<TextureProbe> = (0..=textures.len())
        .flat_map(|texture| std::iter::repeat_n(texture, per_texture))
        .map(|texture| TextureProbe {
            point: in_cube(&mut rng, -4.0, 4.0).to_array(),
            texture: texture as u32,
            uv: [in_range(&mut rng, -2.0, 3.0), in_range(&mut rng, -2.0, 3.0)],
            pad0: 0,
            pad1: 0,
        })
        .collect();
    let on_gpu = texture_colors(&gpu, &gpu_scene, &probes).unwrap();
    assert_eq!(on_gpu.len(), probes.len());
    let mut compared = vec![0; textures.len() + 1];
    let mut largest_error = vec![0.0f32; textures.len() + 1];
    for (probe, gpu_color) in probes.iter().zip(&on_gpu) {
        let texture = probe.texture as usize;
        let (uv, point) = (Vec2::from(probe.uv), Vec3::from(probe.point));
        let cpu = cpu_color(texture, uv, point);
        let gpu = Vec3::from_slice(gpu_color);
        let piecewise = matches!(
            textures.get(texture),
            Some(Texture::Checker3d { .. } | Texture::CheckerUv { .. } | Texture::Wood { .. })
        );
        if piecewise {
            // Away from the boundaries between cells (or rings), where rounding may pick
            // either side: the CPU's colour is the same 10⁻³ away along every axis.
            let step = 1e-3;
            let near_boundary = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z]
                .into_iter()
                .any(|d| cpu_color(texture, uv + d.truncate() * step, point + d * step) != cpu);
            if near_boundary {
                continue;
            }
            assert_eq!(gpu, cpu, "texture {texture} at uv {uv}, point {point}");
        } else {
            let error = (gpu - cpu).abs().max_element();
            largest_error[texture] = largest_error[texture].max(error);
            assert!(
                error < 1e-4,
                "texture {texture} at uv {uv}, point {point}: GPU {gpu}, CPU {cpu}"
            );
        }
        compared[texture] += 1;
    }
    for (texture, count) in compared.iter().enumerate() {
        eprintln!(
            "texture {texture}: {count} points compared, largest difference {:e}",
            largest_error[texture]
        );
        assert!(
            *count >= per_texture * 9 / 10,
            "texture {texture}: {count} of {per_texture} points compared"
        );
    }
}

#[test]
fn more_rays_than_the_gpu_dispatches_are_refused_with_the_limit() {
    let gpu = gpu();
    let assembled = scene_of(
        untransformed(vec![Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap())]),
        Vec::new(),
    );
    let scene = GpuScene::upload(&gpu, &assembled).unwrap();
    let max_groups = gpu.device.limits().max_compute_workgroups_per_dimension as usize;
    let too_many = (max_groups + 1) * 64;
    let rays = vec![ProbeRay::new(&Ray::new(Vec3::ZERO, Vec3::Z), 1e-3, 1.0); too_many];
    match closest_hits(&gpu, &scene, Search::Objects, &rays) {
        Err(e) => assert!(
            e.contains("workgroups") && e.contains(&max_groups.to_string()) || e.contains("bytes"),
            "{e}"
        ),
        Ok(_) => panic!("{too_many} rays were dispatched"),
    }
}

#[test]
fn a_scene_larger_than_the_gpu_holds_is_refused_with_both_sizes() {
    let small = 64 * 1024;
    let gpu = GpuDevice::with_limits(|offered| wgpu::Limits {
        max_storage_buffer_binding_size: small,
        ..offered
    })
    .unwrap_or_else(|e| panic!("these tests run on a GPU: {e}"));
    let mut rng = Rng::with_seed(35);
    // 48 bytes a triangle: 2000 of them need 96,000 bytes.
    let assembled = scene_of(Vec::new(), vec![random_mesh(&mut rng, 2000, 10.0, false)]);
    let error = GpuScene::upload(&gpu, &assembled)
        .err()
        .expect("the scene is refused");
    // In bytes as people read them, and what to do instead.
    assert!(
        error.contains("the triangles need 96.0 KB")
            && error.contains(&format!("allows {}", Bytes(small)))
            && error.contains("use --device cpu"),
        "{error}"
    );
}

/// Whether `point` lies inside the proxy box `proxy`, or the proxy covers the whole film.
fn in_proxy(proxy: Option<Aabb>, point: Vec3) -> bool {
    proxy.is_none_or(|b| point.cmpgt(b.min).all() && point.cmplt(b.max).all())
}

#[test]
fn every_proxy_covers_its_shape_from_random_cameras() {
    const SIZE: (u32, u32) = (64, 48);
    let gpu = Arc::new(gpu());
    let mut rng = Rng::with_seed(83);
    let (mut hits, mut drawn, mut at_silhouettes) = (0, 0, 0);
    let mut failures = Vec::new();
    for trial in 0..24 {
        let shape = if trial % 3 == 2 {
            Shape::Csg(Box::new(random_csg(&mut rng, Vec3::ZERO, true)))
        } else {
            random_solid(&mut rng, Vec3::ZERO)
        };
        let to = in_cube(&mut rng, -0.5, 0.5);
        let transform = random_transform(&mut rng, to);
        let mut assembled = scene_of(vec![(shape, Some(transform))], Vec::new());
        (
            assembled.scene.settings.width,
            assembled.scene.settings.height,
        ) = SIZE;
        let raster = CpuItems::new(Arc::clone(&gpu), &assembled).unwrap();
        for _ in 0..2 {
            let eye = direction(&mut rng) * in_range(&mut rng, 1.5, 12.0);
            let look_at = in_cube(&mut rng, -1.0, 1.0);
            let camera = crate::common::camera(eye, look_at, in_range(&mut rng, 20.0, 100.0));
            assembled.scene.camera = camera;
            let proxy = proxy_box(&assembled.scene.geometry, PrimId::object(0), eye);
            let items = raster.draw(&assembled.scene, ((0, 0), SIZE)).unwrap();
            let tracer = assembled.tracer();
            let pixels: Vec<(u32, u32)> = (0..SIZE.1)
                .flat_map(|y| (0..SIZE.0).map(move |x| (x, y)))
                .collect();
            let hit = |&(x, y): &(u32, u32)| {
                let ray = camera.eye_ray((x, y), PIXEL_CENTRE, SIZE);
                tracer.closest_hit(&ray, EYE_RAY_T_MIN).map(|h| ray.at(h.t))
            };
            let on_shape: Vec<Option<Vec3>> = pixels.iter().map(hit).collect();
            for (i, &(x, y)) in pixels.iter().enumerate() {
                let Some(point) = on_shape[i] else {
                    continue;
                };
                hits += 1;
                if !in_proxy(proxy, point) {
                    failures.push(format!(
                        "trial {trial}: ({x}, {y}) hits {point} outside {proxy:?}"
                    ));
                }
                if items.at(x, y).is_some() {
                    drawn += 1;
                    continue;
                }
                // Not drawn: the GPU's own test may round the other way at the silhouette.
                let neighbour_misses = [(-1, 0), (1, 0), (0, -1), (0, 1)].iter().any(|(dx, dy)| {
                    let (nx, ny) = (x as i32 + dx, y as i32 + dy);
                    let inside =
                        (0..SIZE.0 as i32).contains(&nx) && (0..SIZE.1 as i32).contains(&ny);
                    inside && on_shape[(ny * SIZE.0 as i32 + nx) as usize].is_none()
                });
                if neighbour_misses {
                    at_silhouettes += 1;
                } else {
                    failures.push(format!(
                        "trial {trial}: ({x}, {y}) hits {point} but nothing was drawn"
                    ));
                }
            }
        }
    }
    eprintln!("{hits} pixels hit the shapes, {drawn} drawn, {at_silhouettes} at silhouettes not");
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(hits > 10_000, "only {hits} pixels hit a shape");
    assert!(
        at_silhouettes * 1000 <= hits,
        "{at_silhouettes} of {hits} hits not drawn"
    );
}
