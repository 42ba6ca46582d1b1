//! The GPU's parts against the CPU's on the same rays: each shape's WGSL against its Rust twin
//! (every object tried one by one, `shaders/probe.wgsl`), the BVH's walk against
//! `Bvh::closest_hit`, every kind of texture against `Texture::color`, the structs Rust and WGSL
//! share laid out alike, and the WGSL valid as a whole. These tests need a GPU adapter: without one they fail, saying what to install
//! (Mesa's lavapipe will do).

mod common;

use common::random::{Rng, direction, in_cube, in_range};
use std::sync::Arc;

use glam::{Vec2, Vec3};
use raylab::camera::Camera;
use raylab::color::Color;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::probe::{
    NO_PRIM, ProbeHit, ProbeRay, Search, TextureProbe, closest_hits, texture_colors,
};
use raylab::gpu::scene::GpuScene;
use raylab::gpu::shapes::SHAPES_WGSL;
use raylab::gpu::tracer::TRACER_WGSL;
use raylab::material::Material;
use raylab::mesh::Mesh;
use raylab::primitive::PrimId;
use raylab::ray::Ray;
use raylab::render::{Assembled, assemble};
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Shape, Sphere};
use raylab::texture::{Texture, TextureImage, WOOD_COLORS, Wrap};

fn gpu() -> GpuDevice {
    GpuDevice::new().unwrap_or_else(|e| panic!("these tests run on a GPU: {e}"))
}

/// A scene of `shapes` (no transform) and `meshes`, one material, ready on the CPU.
fn scene_of(shapes: Vec<Shape>, meshes: Vec<Mesh>) -> Assembled {
    let mut scene = Scene::new(RenderSettings::default(), Camera::default());
    let material = scene.add_material(Material::default());
    for shape in shapes {
        scene.add_object(shape, None, material);
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

/// Compares the GPU's hits with the CPU's: the same primitive and part, `t` within 10⁻⁴
/// relative and the normal within 10⁻³, away from grazing hits and near ties (where rounding
/// may pick the other primitive), which are counted. Returns how many hits were compared.
fn compare(assembled: &Assembled, search: Search, rays: &[ProbeRay], on_gpu: &[ProbeHit]) -> usize {
    assert_eq!(on_gpu.len(), rays.len());
    let (mut compared, mut left_out) = (0, 0);
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
            let error = (gpu_hit.t - cpu.t).abs() / cpu.t;
            assert!(
                error < 1e-4,
                "ray {i} {ray:?}: GPU {gpu_hit:?}, CPU {cpu:?} (t off by {error:e})"
            );
            let normal_error = (Vec3::from(gpu_hit.normal) - Vec3::from(cpu.normal)).length();
            assert!(
                normal_error < 1e-3,
                "ray {i} {ray:?}: GPU {gpu_hit:?}, CPU {cpu:?}"
            );
            compared += 1;
        }
    }
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
        spheres.iter().map(|s| Shape::Sphere(*s)).collect(),
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
        vec![Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap())],
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
    let assembled = scene_of(spheres, meshes);
    assert!(assembled.bvh.depth() >= 3, "a tree deep enough to walk");
    let rays = rays_towards(&mut rng, 30_000, 20.0, |rng| in_cube(rng, -12.0, 12.0));
    let scene = GpuScene::upload(&gpu, &assembled).unwrap();
    let on_gpu = closest_hits(&gpu, &scene, Search::Bvh, &rays).unwrap();
    let compared = compare(&assembled, Search::Bvh, &rays, &on_gpu);
    assert!(compared >= 10_000, "{compared} hits compared");
    let triangles = on_gpu
        .iter()
        .filter(|h| h.prim != NO_PRIM && PrimId(h.prim).kind().is_err());
    assert!(triangles.count() >= 5_000, "most hits are triangles");
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
fn tracer_module() -> naga::Module {
    let source = [SHAPES_WGSL, TRACER_WGSL].concat();
    let module = naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
    module
}

/// `(name, size, fields)` of a Rust struct shared with WGSL, for [`wgsl_layout`]'s answer.
macro_rules! rust_layout {
    ($wgsl:literal, $ty:ty, [$($field:ident),*]) => {
        (
            $wgsl,
            std::mem::size_of::<$ty>() as u32,
            vec![$((stringify!($field).to_string(), std::mem::offset_of!($ty, $field) as u32)),*],
        )
    };
}

#[test]
fn the_structs_rust_and_wgsl_share_have_the_same_layout() {
    use raylab::gpu::bvh::{GpuTriangle, GpuWideNode};
    use raylab::gpu::probe::ProbeHit;
    use raylab::gpu::scene::{
        GpuFrame, GpuLight, GpuMaterial, GpuTriangleShading, GpuVertexAttributes,
    };
    use raylab::gpu::shapes::GpuObject;
    use raylab::gpu::texture::GpuTexture;
    use raylab::gpu::tracer::{PixelSample, SampleColor};
    let module = tracer_module();
    let cases = [
        rust_layout!("Object", GpuObject, [kind, first, transform, material]),
        rust_layout!("WideNode", GpuWideNode, [min, max, first, count]),
        rust_layout!("Triangle", GpuTriangle, [p0, index, p1, pad1, p2, pad2]),
        rust_layout!("TriangleShading", GpuTriangleShading, [corners, material]),
        rust_layout!("VertexAttributes", GpuVertexAttributes, [normal, u, v, pad]),
        rust_layout!(
            "Material",
            GpuMaterial,
            [
                color,
                ambient,
                emission,
                diffuse,
                specular_color,
                specular,
                shininess,
                reflectivity,
                transparency,
                ior,
                fresnel,
                texture,
                pad
            ]
        ),
        rust_layout!(
            "Light",
            GpuLight,
            [position, kind, direction, cos_angle, color, cos_full]
        ),
        rust_layout!(
            "Frame",
            GpuFrame,
            [
                eye,
                near,
                u,
                half_height,
                v,
                width,
                n,
                height,
                background,
                max_depth,
                ambient,
                min_weight,
                flags,
                unbounded_first,
                unbounded,
                node_count,
                light_count,
                object_count,
                film_left,
                film_top,
                background_image,
                pad
            ]
        ),
        rust_layout!("PixelSample", PixelSample, [x, y, k, pad]),
        rust_layout!(
            "SampleColor",
            SampleColor,
            [
                color,
                primary_hits,
                shadow,
                reflected,
                transmitted,
                over_budget
            ]
        ),
        rust_layout!("ProbeRay", ProbeRay, [origin, t_min, dir, t_max]),
        rust_layout!("ProbeHit", ProbeHit, [normal, t, uv, prim, part]),
        rust_layout!(
            "Texture",
            GpuTexture,
            [a, kind, b, size, scale, offset, first, width, height, wrap]
        ),
        rust_layout!("TextureProbe", TextureProbe, [point, texture, uv, pad]),
    ];
    for (name, rust_size, rust_fields) in cases {
        let (wgsl_size, wgsl_fields) = wgsl_layout(&module, name);
        // WGSL names the node's boxes `lo` and `hi`, the material's padding three fields.
        let wgsl_offsets: Vec<u32> = wgsl_fields.iter().map(|f| f.1).collect();
        let rust_offsets: Vec<u32> = rust_fields.iter().map(|f| f.1).collect();
        assert_eq!(wgsl_size, rust_size, "size of {name}");
        assert!(
            wgsl_offsets.starts_with(&rust_offsets) || rust_offsets.starts_with(&wgsl_offsets),
            "fields of {name}: WGSL {wgsl_fields:?}, Rust {rust_fields:?}"
        );
    }
}

/// A `width × height` image of random texels.
fn random_image(rng: &mut Rng, width: u32, height: u32) -> Arc<TextureImage> {
    let texels = (0..width * height)
        .map(|_| [rng.u8(..), rng.u8(..), rng.u8(..)])
        .collect();
    Arc::new(TextureImage {
        width,
        height,
        texels,
    })
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
            wrap: Wrap::Repeat,
            scale: Vec2::new(2.5, 1.5),
            offset: Vec2::new(0.3, -0.2),
        },
        Texture::Image {
            image: random_image(&mut rng, 4, 6),
            wrap: Wrap::Clamp,
            scale: Vec2::new(0.8, 1.2),
            offset: Vec2::new(0.1, 0.05),
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
        None => background.sample(uv, Wrap::Clamp),
    };
    let per_texture = 10_000;
    let probes: Vec<TextureProbe> = (0..=textures.len())
        .flat_map(|texture| std::iter::repeat_n(texture, per_texture))
        .map(|texture| TextureProbe {
            point: in_cube(&mut rng, -4.0, 4.0).to_array(),
            texture: texture as u32,
            uv: [in_range(&mut rng, -2.0, 3.0), in_range(&mut rng, -2.0, 3.0)],
            pad: [0; 2],
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
        vec![Shape::Sphere(Sphere::new(Vec3::ZERO, 1.0).unwrap())],
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
