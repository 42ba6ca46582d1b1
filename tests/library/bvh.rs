//! The BVH must return exactly what testing every primitive returns.

use std::collections::BTreeSet;
use std::ops::ControlFlow;

use crate::common::random::{Rng, in_cube, in_range};
use glam::Vec3;
use proptest::prelude::*;
use raylab::aabb::Aabb;
use raylab::bvh::packet::PACKET_SIZE;
use raylab::bvh::{Bvh, Simd};
use raylab::camera::{Camera, CameraSpec, PIXEL_CENTRE};
use raylab::mesh::Mesh;
use raylab::primitive::{Geometry, Hit, Object, PrimId, PrimKind};
use raylab::ray::Ray;
use raylab::shapes::{Plane, Polygon, Shape, Sphere, TaperedCylinder};
use raylab::transform::{Transform, TransformStep};
use strum::{IntoEnumIterator, VariantNames};

/// A scene of `spheres` spheres (every third one transformed), half as many flat polygons
/// (triangles, quads and hexagons; every fifth one transformed) and a third as many tapered
/// cylinders (open and capped; every fifth one transformed), `triangles` mesh triangles and
/// `planes` planes: every kind of leaf the BVH makes.
fn random_scene(seed: u64, spheres: usize, triangles: usize, planes: usize) -> Geometry {
    let mut rng = Rng::with_seed(seed);
    let mut g = Geometry::default();
    for i in 0..spheres {
        let sphere = Shape::Sphere(Sphere {
            center: in_cube(&mut rng, -10.0, 10.0),
            radius: in_range(&mut rng, 0.05, 1.5),
        });
        // Every third sphere is squashed and turned, to exercise transformed bounds.
        let transform = (i % 3 == 0).then(|| {
            Transform::from_steps(&[
                TransformStep::Scale(in_cube(&mut rng, 0.3, 2.0)),
                TransformStep::Rotate {
                    axis: in_cube(&mut rng, -1.0, 1.0) + Vec3::splat(0.01),
                    degrees: in_range(&mut rng, 0.0, 360.0),
                },
            ])
            .unwrap()
        });
        g.objects.push(Object {
            shape: sphere,
            transform: transform.map(Box::new),
            material: 0,
        });
    }
    for i in 0..spheres / 2 {
        // A regular polygon of 3, 4 or 6 corners in a random plane.
        let corners = [3, 4, 6][i % 3];
        let centre = in_cube(&mut rng, -10.0, 10.0);
        let u = in_cube(&mut rng, -1.0, 1.0);
        let v =
            (u.cross(in_cube(&mut rng, -1.0, 1.0)) + Vec3::splat(1e-3)).normalize() * u.length();
        let vertices = (0..corners)
            .map(|k| {
                let angle = k as f32 * std::f32::consts::TAU / corners as f32;
                centre + u * angle.cos() + v * angle.sin()
            })
            .collect();
        let Ok(polygon) = Polygon::new(vertices) else {
            continue;
        };
        let transform = (i % 5 == 0).then(|| {
            Transform::from_steps(&[TransformStep::Rotate {
                axis: in_cube(&mut rng, -1.0, 1.0) + Vec3::splat(0.01),
                degrees: in_range(&mut rng, 0.0, 360.0),
            }])
            .unwrap()
        });
        g.objects.push(Object {
            shape: Shape::Polygon(polygon),
            transform: transform.map(Box::new),
            material: 0,
        });
    }
    for i in 0..spheres / 3 {
        let base = in_cube(&mut rng, -10.0, 10.0);
        let top = base + in_cube(&mut rng, -2.0, 2.0);
        let radii = (in_range(&mut rng, 0.0, 1.0), in_range(&mut rng, 0.05, 1.0));
        let Ok(cylinder) = TaperedCylinder::new(base, top, radii.0, radii.1, i % 2 == 1) else {
            continue;
        };
        let transform = (i % 5 == 0).then(|| {
            Transform::from_steps(&[TransformStep::Scale(in_cube(&mut rng, 0.5, 2.0))]).unwrap()
        });
        g.objects.push(Object {
            shape: Shape::TaperedCylinder(cylinder),
            transform: transform.map(Box::new),
            material: 0,
        });
    }
    for _ in 0..planes {
        g.objects.push(Object {
            shape: Shape::Plane(Plane {
                point: in_cube(&mut rng, -12.0, 12.0),
                normal: (in_cube(&mut rng, -1.0, 1.0) + Vec3::splat(1e-3)).normalize(),
            }),
            transform: None,
            material: 0,
        });
    }
    let mut mesh = Mesh::default();
    for i in 0..triangles as u32 {
        let c = in_cube(&mut rng, -10.0, 10.0);
        mesh.positions.extend([
            c,
            c + in_cube(&mut rng, -2.0, 2.0),
            c + in_cube(&mut rng, -2.0, 2.0),
        ]);
        mesh.faces.push([3 * i, 3 * i + 1, 3 * i + 2]);
    }
    g.add_mesh(mesh);
    g
}

/// The closest hit found by testing every primitive (an instance tests each of its triangles).
pub fn brute_force(g: &Geometry, ray: &Ray) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for id in g.prim_ids() {
        let t_max = best.map_or(f32::INFINITY, |h| h.t);
        if let Some(hit) = g.intersect(id, ray, 0.0, t_max) {
            best = Some(hit);
        }
    }
    best
}

/// A ray from somewhere around the scenes' cube towards a point in it.
pub fn random_ray(rng: &mut Rng) -> Ray {
    let origin = in_cube(rng, -15.0, 15.0);
    let target = in_cube(rng, -10.0, 10.0);
    Ray::new(origin, (target - origin) * in_range(rng, 0.2, 3.0))
}

/// Checks that the BVH finds the brute force's closest hit for `ray`; whether there is one.
fn assert_same_closest(g: &Geometry, bvh: &Bvh, ray: &Ray) -> bool {
    let expected = brute_force(g, ray);
    let got = bvh.closest_hit(g, ray, 0.0, f32::INFINITY);
    match (expected, got) {
        (None, None) => false,
        (Some(e), Some(h)) => {
            assert_eq!(e.t, h.t, "ray {ray:?}");
            // Ties go to the primitive first in the scene, as in the brute force.
            assert_eq!(e.prim, h.prim, "ray {ray:?}");
            true
        }
        _ => panic!("brute force {expected:?} but BVH {got:?} for {ray:?}"),
    }
}

#[test]
fn closest_hit_equals_brute_force_on_random_scenes() {
    for seed in 0..12 {
        let g = random_scene(seed, 40 + 30 * seed as usize, 200, (seed % 3) as usize);
        let bvh = Bvh::build(&g);
        let mut rng = Rng::with_seed(seed + 1000);
        let hits = (0..1000)
            .filter(|_| assert_same_closest(&g, &bvh, &random_ray(&mut rng)))
            .count();
        // Agreeing on misses proves nothing: at least a tenth of the rays, aimed into the scene, hit.
        assert!(hits >= 100, "only {hits} of 1000 rays hit (seed {seed})");
    }
}

#[test]
fn any_hit_visits_exactly_the_primitives_on_the_segment() {
    let g = random_scene(7, 150, 300, 2);
    let bvh = Bvh::build(&g);
    let mut rng = Rng::with_seed(99);
    let mut rays_with_hits = 0;
    for _ in 0..2000 {
        let ray = random_ray(&mut rng);
        let t_max = in_range(&mut rng, 0.1, 2.0);
        let expected: BTreeSet<PrimId> = g
            .prim_ids()
            .filter(|&id| g.intersect(id, &ray, 0.0, t_max).is_some())
            .collect();
        let mut got = BTreeSet::new();
        bvh.any_hit(&g, &ray, 0.0, t_max, |hit| {
            assert!(got.insert(hit.prim), "primitive visited twice");
            ControlFlow::Continue(())
        });
        assert_eq!(got, expected);
        rays_with_hits += usize::from(!got.is_empty());
    }
    // Segments that meet nothing agree trivially: at least a tenth must meet something.
    assert!(
        rays_with_hits >= 200,
        "only {rays_with_hits} of 2000 segments hit"
    );
}

#[test]
fn any_hit_stops_when_asked() {
    let mut g = random_scene(3, 300, 0, 0);
    // And ten balls in a row along the ray, so that it meets at least ten primitives.
    let ray = Ray::new(Vec3::new(-20.0, 0.0, 0.0), Vec3::X);
    for i in 0..10 {
        g.objects.push(Object {
            shape: Shape::Sphere(Sphere {
                center: Vec3::new(2.0 * i as f32 - 9.0, 0.0, 0.0),
                radius: 0.5,
            }),
            transform: None,
            material: 0,
        });
    }
    let bvh = Bvh::build(&g);
    let on_the_ray = g
        .prim_ids()
        .filter(|&id| g.intersect(id, &ray, 0.0, f32::INFINITY).is_some())
        .count();
    assert!(on_the_ray >= 10, "{on_the_ray} primitives on the ray");
    let calls_until = |answer: ControlFlow<()>| {
        let mut calls = 0;
        bvh.any_hit(&g, &ray, 0.0, f32::INFINITY, |_| {
            calls += 1;
            answer
        });
        calls
    };
    assert_eq!(calls_until(ControlFlow::Continue(())), on_the_ray);
    assert_eq!(calls_until(ControlFlow::Break(())), 1);
}

#[test]
fn tree_is_shallow_and_covers_every_primitive_once() {
    let g = random_scene(5, 2000, 8000, 1);
    let bvh = Bvh::build(&g);
    assert_eq!(bvh.unbounded.len(), 1, "the plane stays out of the tree");
    assert!(bvh.depth() < 40, "depth {}", bvh.depth());
    let mut seen: Vec<PrimId> = Vec::new();
    // Each leaf's box holds its primitives' boxes; each interior child's box holds its
    // children's.
    let inside =
        |b: Aabb, outer: Aabb| b.min.cmpge(outer.min).all() && b.max.cmple(outer.max).all();
    for node in &bvh.nodes {
        for k in 0..raylab::bvh::WIDTH {
            let Some(child) = node.child(k) else {
                continue;
            };
            let outer = node.child_bounds(k);
            if child.is_leaf() {
                let prims = bvh.leaf_prims(child);
                assert!(!prims.is_empty());
                let kinds: BTreeSet<bool> = prims
                    .iter()
                    .map(|id| matches!(id.kind(), PrimKind::Object(_)))
                    .collect();
                assert_eq!(kinds.len(), 1, "a leaf holds one kind of primitive");
                for &id in &prims {
                    assert!(inside(g.bounds(id).unwrap(), outer));
                }
                seen.extend(prims);
            } else {
                let inner = &bvh.nodes[child.first as usize];
                for j in (0..raylab::bvh::WIDTH).filter(|&j| inner.child(j).is_some()) {
                    assert!(inside(inner.child_bounds(j), outer));
                }
            }
        }
    }
    let leaves = seen.len();
    seen.sort();
    seen.dedup();
    assert_eq!(seen.len(), leaves, "no primitive is in two leaves");
    assert_eq!(
        seen.len(),
        g.prim_ids().count() - 1,
        "every bounded primitive is"
    );
}

#[test]
fn ties_go_to_the_primitive_first_in_the_scene() {
    // Many copies of one sphere: every ray hits all of them at the same t.
    let mut g = Geometry::default();
    for _ in 0..50 {
        g.objects.push(Object {
            shape: Shape::Sphere(Sphere {
                center: Vec3::ZERO,
                radius: 1.0,
            }),
            transform: None,
            material: 0,
        });
    }
    let bvh = Bvh::build(&g);
    let mut rng = Rng::with_seed(5);
    for _ in 0..200 {
        let origin = in_cube(&mut rng, -5.0, 5.0) + Vec3::splat(6.0);
        // Aimed at a point inside the spheres (at most √0.75 from their centre): a hit.
        let ray = Ray::new(origin, in_cube(&mut rng, -0.5, 0.5) - origin);
        let hit = bvh.closest_hit(&g, &ray, 0.0, f32::INFINITY);
        assert_eq!(hit.map(|h| h.prim), Some(PrimId::object(0)), "ray {ray:?}");
    }
}

#[test]
fn the_tree_does_not_depend_on_the_thread_count() {
    // Enough primitives for the builder to split the top nodes' halves between threads.
    let g = random_scene(11, 3000, 30_000, 1);
    let build_on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| Bvh::build(&g))
    };
    let one = build_on(1);
    let four = build_on(4);
    assert_eq!(one.nodes, four.nodes);
    assert_eq!(one.objects, four.objects);
    let packs = |bvh: &Bvh| -> Vec<_> {
        bvh.packs
            .iter()
            .map(|pack| (pack.tags, pack.p.map(|v| v.map(|a| a.map(f32::to_bits)))))
            .collect()
    };
    assert_eq!(packs(&one), packs(&four));
    let tags = |bvh: &Bvh| -> Vec<_> {
        let spheres = bvh.spheres.iter().map(|pack| pack.tags);
        let cylinders = bvh.cylinders.iter().map(|pack| pack.tags);
        let polygons = bvh.polygons.iter().map(|pack| pack.tags);
        spheres.chain(cylinders).chain(polygons).collect()
    };
    assert!(!one.spheres.is_empty() && !one.cylinders.is_empty() && !one.polygons.is_empty());
    assert_eq!(tags(&one), tags(&four));
}

#[test]
fn empty_and_single_primitive_scenes() {
    let empty = Geometry::default();
    let bvh = Bvh::build(&empty);
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    assert!(bvh.closest_hit(&empty, &ray, 0.0, f32::INFINITY).is_none());
    let one = random_scene(1, 1, 0, 0);
    let bvh = Bvh::build(&one);
    let Shape::Sphere(s) = one.objects[0].shape.clone() else {
        unreachable!()
    };
    let at = one.objects[0]
        .transform
        .as_ref()
        .map_or(s.center, |t| t.point_to_world(s.center));
    let ray = Ray::new(at + Vec3::new(0.0, 0.0, 50.0), -Vec3::Z);
    assert!(bvh.closest_hit(&one, &ray, 0.0, f32::INFINITY).is_some());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn closest_hit_equals_brute_force_for_any_scene(seed in 0u64..1_000_000, n in 1usize..120) {
        let g = random_scene(seed, n, n * 2, (seed % 2) as usize);
        let bvh = Bvh::build(&g);
        let mut rng = Rng::with_seed(seed ^ 0xdead_beef);
        for _ in 0..64 {
            assert_same_closest(&g, &bvh, &random_ray(&mut rng));
        }
    }

    #[test]
    fn packets_get_the_single_ray_hits_from_any_eye(seed in 0u64..1_000_000, n in 1usize..200) {
        let g = random_scene(seed, n, n * 3, (seed % 2) as usize);
        let bvh = Bvh::build(&g);
        let mut rng = Rng::with_seed(seed ^ 0x5eed);
        let camera = camera_at(in_cube(&mut rng, -30.0, 30.0));
        let rays = eye_rays_in_tiles(&camera, 24, 16);
        assert_packets_equal_single_rays(&g, &bvh, &rays, PACKET_SIZE);
    }
}

/// Traces `rays` in packets of `size` and checks that each ray gets exactly its single-ray hit.
fn assert_packets_equal_single_rays(g: &Geometry, bvh: &Bvh, rays: &[Ray], size: usize) {
    let t_min = 1.0;
    let mut hits = vec![None; size];
    for packet in rays.chunks(size) {
        let hits = &mut hits[..packet.len()];
        bvh.closest_hits(g, packet, t_min, f32::INFINITY, hits);
        for (ray, hit) in packet.iter().zip(hits.iter()) {
            let single = bvh.closest_hit(g, ray, t_min, f32::INFINITY);
            assert_eq!(*hit, single, "ray {ray:?}");
        }
    }
}

/// The eye rays of a `width` × `height` image in tiles of 8 × 8, tile after tile.
fn eye_rays_in_tiles(camera: &Camera, width: u32, height: u32) -> Vec<Ray> {
    let mut rays = Vec::new();
    for tile_y in (0..height).step_by(8) {
        for tile_x in (0..width).step_by(8) {
            for y in tile_y..(tile_y + 8).min(height) {
                for x in tile_x..(tile_x + 8).min(width) {
                    rays.push(camera.eye_ray((x, y), PIXEL_CENTRE, (width, height)));
                }
            }
        }
    }
    rays
}

fn camera_at(eye: Vec3) -> Camera {
    Camera::new(CameraSpec {
        eye,
        look_at: Vec3::ZERO,
        up: Vec3::Y,
        view_angle: 50.0,
        near: 1.0,
    })
    .unwrap()
}

#[test]
fn packets_of_eye_rays_get_the_single_ray_hits() {
    for seed in 0..6 {
        let g = random_scene(seed, 60, 400, (seed % 3) as usize);
        let bvh = Bvh::build(&g);
        let mut rng = Rng::with_seed(seed + 77);
        let camera = camera_at(in_cube(&mut rng, -12.0, 12.0) + Vec3::new(0.0, 0.0, 24.0));
        let rays = eye_rays_in_tiles(&camera, 96, 72);
        assert!(
            rays.iter()
                .filter(|r| bvh.closest_hit(&g, r, 1.0, f32::INFINITY).is_some())
                .count()
                > 1000
        );
        assert_packets_equal_single_rays(&g, &bvh, &rays, PACKET_SIZE);
        assert_packets_equal_single_rays(&g, &bvh, &rays, 5);
    }
}

#[test]
fn packets_of_incoherent_and_axis_parallel_rays_get_the_single_ray_hits() {
    let g = random_scene(3, 120, 600, 1);
    let bvh = Bvh::build(&g);
    let mut rng = Rng::with_seed(99);
    // Directions of every sign: the packet has no bounds to cull with.
    let random: Vec<Ray> = (0..4096).map(|_| random_ray(&mut rng)).collect();
    assert_packets_equal_single_rays(&g, &bvh, &random, PACKET_SIZE);
    // Parallel rays from a grid of origins (one sign per axis, many origins), and the same
    // straight down the z axis (a direction component of zero).
    let grid = |dir: Vec3| -> Vec<Ray> {
        (0..64 * 64)
            .map(|i| {
                let (x, y) = ((i % 64) as f32, (i / 64) as f32);
                Ray::new(Vec3::new(x * 0.3 - 9.6, y * 0.3 - 9.6, 20.0), dir)
            })
            .collect()
    };
    assert_packets_equal_single_rays(&g, &bvh, &grid(Vec3::new(0.1, -0.05, -1.0)), PACKET_SIZE);
    assert_packets_equal_single_rays(&g, &bvh, &grid(Vec3::new(0.0, 0.0, -1.0)), PACKET_SIZE);
    assert_packets_equal_single_rays(&g, &bvh, &[], PACKET_SIZE);
}

#[test]
fn each_triangle_has_its_own_mesh_material() {
    // Two meshes, one triangle each (and a degenerate face in the first, which makes no
    // triangle): each hit reports the material of the mesh its triangle came from.
    let mut g = Geometry::default();
    for (material, z) in [(3, 0.0), (5, 1.0)] {
        let corner = |x: f32, y: f32| Vec3::new(x, y, z);
        g.add_mesh(Mesh {
            positions: vec![corner(-1.0, -1.0), corner(1.0, -1.0), corner(0.0, 1.0)],
            faces: if material == 3 {
                vec![[0, 0, 1], [0, 1, 2]]
            } else {
                vec![[0, 1, 2]]
            },
            material,
            ..Mesh::default()
        });
    }
    let bvh = Bvh::build(&g);
    let material_seen_from = |z: f32, dir: Vec3| {
        let ray = Ray::new(Vec3::new(0.0, 0.0, z), dir);
        let hit = bvh
            .closest_hit(&g, &ray, 0.0, f32::INFINITY)
            .expect("a hit");
        (g.material(&hit), g.surface(&ray, &hit).material)
    };
    assert_eq!(material_seen_from(-5.0, Vec3::Z), (3, 3));
    assert_eq!(material_seen_from(5.0, -Vec3::Z), (5, 5));
}

#[test]
fn every_instruction_set_gives_the_same_hits() {
    let g = random_scene(21, 500, 4000, 1);
    let mut bvh = Bvh::build(&g);
    let mut rng = Rng::with_seed(21);
    let mut rays: Vec<Ray> = (0..2000).map(|_| random_ray(&mut rng)).collect();
    rays.extend(eye_rays_in_tiles(
        &camera_at(Vec3::new(0.0, 3.0, 40.0)),
        32,
        32,
    ));
    // Along the axes, where the inverse direction has infinities.
    rays.extend([Vec3::X, -Vec3::Y, Vec3::Z].map(|d| Ray::new(-20.0 * d, d)));
    let answers = |bvh: &Bvh| {
        let closest: Vec<Option<Hit>> = rays
            .iter()
            .map(|ray| bvh.closest_hit(&g, ray, 0.0, f32::INFINITY))
            .collect();
        let blockers: Vec<Vec<PrimId>> = rays
            .iter()
            .map(|ray| {
                let mut on_segment = Vec::new();
                bvh.any_hit(&g, ray, 0.0, 30.0, |hit| {
                    on_segment.push(hit.prim);
                    ControlFlow::Continue(())
                });
                on_segment.sort();
                on_segment
            })
            .collect();
        let mut packets = vec![None; rays.len()];
        for (rays, hits) in rays
            .chunks(PACKET_SIZE)
            .zip(packets.chunks_mut(PACKET_SIZE))
        {
            bvh.closest_hits(&g, rays, 0.0, f32::INFINITY, hits);
        }
        (closest, blockers, packets)
    };
    bvh.set_simd(Simd::Portable).unwrap();
    let reference = answers(&bvh);
    assert!(reference.0.iter().filter(|h| h.is_some()).count() > 500);
    let mut paths = 0;
    for simd in Simd::supported() {
        bvh.set_simd(simd).unwrap();
        let (closest, blockers, packets) = answers(&bvh);
        assert!(closest == reference.0, "{simd}: closest hits differ");
        assert!(blockers == reference.1, "{simd}: any hits differ");
        assert!(packets == reference.2, "{simd}: packet hits differ");
        paths += 1;
    }
    assert!(paths >= 1);
    #[cfg(target_arch = "x86_64")]
    assert!(paths >= 2, "x86-64 always has SSE: {paths} paths");
}

#[test]
fn a_path_the_processor_lacks_is_refused() {
    let mut bvh = Bvh::build(&random_scene(1, 10, 10, 0));
    for simd in Simd::iter() {
        assert_eq!(bvh.set_simd(simd).is_ok(), simd.is_supported(), "{simd}");
    }
    assert_eq!("avx2".parse::<Simd>(), Ok(Simd::Avx2));
    assert_eq!(Simd::VARIANTS, ["portable", "sse", "avx2", "avx512"]);
    assert_eq!(
        "avx3".parse::<Simd>(),
        Err("`avx3` is not one of portable, sse, avx2, avx512".to_string())
    );
}

#[test]
fn the_builder_fills_the_triangle_packs() {
    // A leaf of up to four triangles costs one test of a pack, so the builder makes leaves of
    // about four rather than one or two: fewer nodes, and packs mostly full.
    let mut g = Geometry::default();
    g.add_mesh(raylab::large_mesh::bumpy_sphere(20_000));
    let bvh = Bvh::build(&g);
    let filled = g.triangle_count() as f64 / (bvh.packs.len() * raylab::shapes::PACK_SIZE) as f64;
    assert!(
        filled > 0.6,
        "{:.0} % of the lanes hold a triangle",
        filled * 100.0
    );
}
