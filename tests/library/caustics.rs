//! Caustics by photon mapping, tested against physics: the power the photons store is the power
//! the light sends through its specular paths; a mirror's caustic is the light of the mirror
//! image of the lamp; a glass ball focuses where paraxial optics says; and, with caustics on,
//! shadow rays no longer pass glass that bends light.

use std::f32::consts::PI;

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::camera::Camera;
use raylab::color::Color;
use raylab::inspect::trace_ray_tree;
use raylab::light::Light;
use raylab::material::Material;
use raylab::medium::{Atmosphere, Medium};
use raylab::photon::{Photon, PhotonMap, caustic_map};
use raylab::ray::Ray;
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Polygon, Shape, Sphere};
use raylab::whitted::Tracer;

fn empty_scene() -> Scene {
    Scene::new(RenderSettings::default(), Camera::default())
}

fn diffuse() -> Material {
    Material {
        ambient: 0.0,
        ..Material::default()
    }
}

fn mirror(reflectivity: f32) -> Material {
    Material {
        diffuse: 0.0,
        ambient: 0.0,
        reflectivity,
        ..Material::default()
    }
}

fn glass(ior: f32) -> Material {
    Material {
        color: Color::ONE,
        diffuse: 0.0,
        ambient: 0.0,
        transparency: 1.0,
        ior,
        ..Material::default()
    }
}

/// The square of side `2·half` around `center` in the plane of normal `normal`.
fn square(center: Vec3, normal: Vec3, half: f32) -> Shape {
    let (s, t) = normal.any_orthonormal_pair();
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut vertices: Vec<Vec3> = corners
        .iter()
        .map(|&(a, b)| center + half * (a * s + b * t))
        .collect();
    if (vertices[1] - vertices[0])
        .cross(vertices[2] - vertices[1])
        .dot(normal)
        < 0.0
    {
        vertices.reverse();
    }
    Shape::Polygon(Polygon::new(vertices).unwrap())
}

fn plane(point: Vec3, normal: Vec3) -> Shape {
    Shape::Plane(Plane { point, normal })
}

/// A glass ball of index `ior` and radius 1 around `center`, on a diffuse floor at y = 0, lit by
/// `light`; and the floor's material.
fn ball_on_floor(ior: f32, center: Vec3, light: Light) -> (Scene, u32) {
    let mut scene = empty_scene();
    let (g, d) = (
        scene.add_material(glass(ior)),
        scene.add_material(diffuse()),
    );
    let ball = Sphere::new(center, 1.0).unwrap();
    scene.add_object(Shape::Sphere(ball), None, g);
    scene.add_object(plane(Vec3::ZERO, Vec3::Y), None, d);
    scene.lights.push(light);
    (scene, d)
}

/// Light falling straight down.
const OVERHEAD: Light = Light::Directional {
    direction: Vec3::Y,
    color: Color::ONE,
};

fn map_of(scene: &Scene, photons: u32) -> PhotonMap {
    let bvh = Bvh::build(&scene.geometry);
    caustic_map(&Tracer::new(scene, &bvh), photons).unwrap()
}

/// The power stored in the map, per unit of the light's intensity.
fn stored_power(map: &PhotonMap) -> f32 {
    map.photons().iter().map(|p| p.power.x).sum::<f32>() / map.shot() as f32
}

#[test]
fn the_map_stores_the_power_the_mirror_sends_to_diffuse_surfaces() {
    // A point light of intensity I at height h over a square mirror of half-side a (below it,
    // reflectivity r), under a diffuse ceiling that catches everything reflected: the stored
    // power is I·Ω·r, Ω = 4·asin(a²/(a² + h²)) the solid angle of the square.
    let (h, a, intensity) = (2.0f32, 1.5f32, 3.0f32);
    for r in [1.0, 0.6] {
        let mut scene = empty_scene();
        let m = scene.add_material(mirror(r));
        let d = scene.add_material(diffuse());
        scene.add_object(square(Vec3::ZERO, Vec3::Y, a), None, m);
        scene.add_object(plane(Vec3::new(0.0, 4.0, 0.0), -Vec3::Y), None, d);
        scene.lights.push(Light::Point {
            position: Vec3::new(0.0, h, 0.0),
            color: Color::splat(intensity),
        });
        let map = map_of(&scene, 200_000);
        let omega = 4.0 * (a * a / (a * a + h * h)).asin();
        let expected = intensity * omega * r;
        let got = stored_power(&map);
        assert!(
            (got / expected - 1.0).abs() < 0.02,
            "r = {r}: {got} vs {expected}"
        );
    }
}

#[test]
fn a_mirror_beside_a_light_makes_the_caustic_of_its_mirror_image() {
    // A diffuse floor at y = 0, a light at (0, 3, 0) and a mirror wall at x = 2 facing it: the
    // caustic on the floor is the light of the image lamp at (4, 3, 0), E = I·cos θ / r².
    let mut scene = empty_scene();
    let (m, d) = (
        scene.add_material(mirror(1.0)),
        scene.add_material(diffuse()),
    );
    scene.add_object(plane(Vec3::ZERO, Vec3::Y), None, d);
    scene.add_object(square(Vec3::new(2.0, 4.0, 0.0), -Vec3::X, 4.0), None, m);
    let intensity = 10.0;
    scene.lights.push(Light::Point {
        position: Vec3::new(0.0, 3.0, 0.0),
        color: Color::splat(intensity),
    });
    let map = map_of(&scene, 2_000_000);
    let image = Vec3::new(4.0, 3.0, 0.0);
    let mut errors = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            let point = Vec3::new(-2.0 + i as f32, 0.0, -1.2 + 0.8 * j as f32);
            let to_image = image - point;
            let r2 = to_image.length_squared();
            let expected = intensity * (to_image.y / r2.sqrt()) / r2;
            let got = map.irradiance(point, Vec3::Y, 512).x;
            errors.push(got / expected - 1.0);
        }
    }
    // Each estimate from 512 photons is off by about 1/√512 ≈ 4.4% by chance alone; their
    // mean is not.
    let mean = errors.iter().sum::<f32>() / errors.len() as f32;
    assert!(mean.abs() < 0.03, "mean error {mean}: {errors:?}");
    assert!(errors.iter().all(|e| e.abs() < 0.15), "{errors:?}");
}

#[test]
fn a_glass_ball_focuses_light_where_paraxial_optics_says() {
    // Light straight down through a pinhole onto a glass ball of radius R and index n: the
    // near-axis rays cross the axis f = nR / (2(n − 1)) beyond the ball's centre. Each stored
    // photon's line of flight, followed back, says where it crossed.
    let (radius, center_y) = (1.0f32, 5.0f32);
    for n in [1.5f32, 1.8] {
        let mut scene = empty_scene();
        let (g, d) = (scene.add_material(glass(n)), scene.add_material(diffuse()));
        let dark = scene.add_material(Material {
            diffuse: 0.0,
            ..diffuse()
        });
        let sphere = Sphere::new(Vec3::new(0.0, center_y, 0.0), radius).unwrap();
        scene.add_object(Shape::Sphere(sphere), None, g);
        scene.add_object(plane(Vec3::ZERO, Vec3::Y), None, d);
        // The mask: a plate above the ball with a hole of radius R/10, as a ring of squares
        // is awkward; four squares leaving a square hole of half-side R/10 will do.
        let (hole, plate_y, big) = (0.1 * radius, center_y + 1.5, 3.0);
        for (cx, cz, hx, hz) in [
            (hole + big, 0.0, big, big + hole),
            (-hole - big, 0.0, big, big + hole),
            (0.0, hole + big, hole, big),
            (0.0, -hole - big, hole, big),
        ] {
            let corners = [(-hx, -hz), (-hx, hz), (hx, hz), (hx, -hz)];
            let vertices = corners
                .map(|(x, z)| Vec3::new(cx + x, plate_y, cz + z))
                .to_vec();
            scene.add_object(Shape::Polygon(Polygon::new(vertices).unwrap()), None, dark);
        }
        scene.lights.push(Light::Directional {
            direction: Vec3::Y,
            color: Color::ONE,
        });
        let map = map_of(&scene, 400_000);
        let crossings: Vec<f32> = map
            .photons()
            .iter()
            .filter(|p| p.position.y.abs() < 1e-3)
            .map(|p| {
                // Where the line p.position − s·dir comes closest to the y axis.
                let (q, d) = (p.position, p.dir);
                let s = (q.x * d.x + q.z * d.z) / (d.x * d.x + d.z * d.z);
                (q - s * d).y
            })
            .collect();
        assert!(crossings.len() > 1000, "{} photons landed", crossings.len());
        let mean = crossings.iter().sum::<f32>() / crossings.len() as f32;
        let focus = center_y - n * radius / (2.0 * (n - 1.0));
        assert!(
            (mean - focus).abs() < 0.02 * (center_y - focus),
            "n = {n}: the rays cross at {mean}, paraxial focus {focus}"
        );
    }
}

#[test]
fn photons_are_the_same_whatever_the_thread_count() {
    let light = Light::Point {
        position: Vec3::new(1.0, 5.0, 0.0),
        color: Color::ONE,
    };
    let (scene, _) = ball_on_floor(1.5, Vec3::Y, light);
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| map_of(&scene, 20_000))
    };
    let (one, two) = (on(1), on(2));
    assert!(!one.is_empty());
    assert_eq!(one.photons(), two.photons());
}

#[test]
fn with_caustics_on_shadow_rays_no_longer_pass_glass_that_bends_light() {
    // A floor point behind a glass ball, seen from above: with caustics off the light passes
    // the ball (tinted by nothing: clear glass); with them on, only the photons would bring it,
    // and an empty map brings none. Glass of index 1 still lets it through.
    for (ior, passes_with_caustics) in [(1.5, false), (1.0, true)] {
        let light = Light::Point {
            position: Vec3::new(0.0, 6.0, 0.0),
            color: Color::ONE,
        };
        let (mut scene, _) = ball_on_floor(ior, Vec3::new(0.0, 3.0, 0.0), light);
        scene.settings.ambient = Color::ZERO;
        let bvh = Bvh::build(&scene.geometry);
        let tracer = Tracer::new(&scene, &bvh);
        let ray = Ray::new(Vec3::new(0.3, 2.0, 4.0), Vec3::new(0.0, -1.0, -2.0));
        let shade = |tracer: &Tracer| tracer.trace_eye(&ray, &mut Default::default());
        assert!(shade(&tracer).x > 0.5, "ior {ior}: lit through the glass");
        let empty = PhotonMap::default();
        let lit = shade(&tracer.with_caustics(Some(&empty))).x > 0.5;
        assert_eq!(lit, passes_with_caustics, "ior {ior}");
    }
}

#[test]
fn the_caustic_under_a_glass_ball_is_brighter_than_the_light_without_it() {
    // Light focused by the ball lands on a small spot: far more irradiance than the bare light.
    let (scene, _) = ball_on_floor(1.5, Vec3::new(0.0, 1.5, 0.0), OVERHEAD);
    let map = map_of(&scene, 100_000);
    let focus = map.irradiance(Vec3::ZERO, Vec3::Y, 64).x;
    assert!(
        focus > 10.0,
        "the focus gets {focus} times the light's irradiance"
    );
    // Energy: the light the ball intercepts, a disc of radius 1 (π), all lands on the floor
    // (this glass reflects nothing).
    assert!(
        (stored_power(&map) / PI - 1.0).abs() < 0.02,
        "{}",
        stored_power(&map)
    );
}

#[test]
fn the_inspector_shows_the_caustic_light_at_each_diffuse_hit() {
    let (mut scene, d) = ball_on_floor(1.5, Vec3::new(0.0, 1.5, 0.0), OVERHEAD);
    scene.settings.ambient = Color::ZERO;
    scene.settings.width = 64;
    scene.settings.height = 64;
    // Looking down at the focus under the ball, from beside it.
    scene.camera = Camera::new(raylab::camera::CameraSpec {
        eye: Vec3::new(3.0, 0.5, 0.0),
        look_at: Vec3::ZERO,
        ..Default::default()
    })
    .unwrap();
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let map = caustic_map(&tracer, 50_000).unwrap();
    let tree = trace_ray_tree(&tracer.with_caustics(Some(&map)), 32, 32);
    let eye = &tree.nodes[0];
    let caustic = eye.caustic.expect("the floor gathers caustic photons");
    assert!(
        caustic.x > 3.0,
        "brighter than the bare light (1): {caustic}"
    );
    // The floor's local colour is its diffuse share of the caustic: no light reaches it
    // directly through the glass, and there is no ambient light.
    let material = &scene.materials[d as usize];
    let expected = material.diffuse * material.color * caustic;
    assert!((eye.local_color - expected).length() < 1e-3 * expected.length());
    assert!(
        tree.to_text().contains("caustic irradiance"),
        "{}",
        tree.to_text()
    );
    // Without caustics, no such line.
    let plain = trace_ray_tree(&tracer, 32, 32);
    assert_eq!(plain.nodes[0].caustic, None);
}

#[test]
fn a_directional_lights_photons_cross_the_fog_its_light_crosses() {
    // Light falling straight down onto a mirror at 45° round the origin, which sends it along
    // +x to a diffuse wall at x = 3, in fog that only absorbs with the background (and so the
    // directional light) 20 units along every ray. A photon stored at height y on the wall
    // left the mirror at x = −y: it crossed 20 units of fog down to the mirror and 3 + y to
    // the wall.
    let sigma = 0.05;
    let mut scene = empty_scene();
    let m = scene.add_material(mirror(1.0));
    let d = scene.add_material(diffuse());
    let facing = Vec3::new(1.0, 1.0, 0.0).normalize();
    scene.add_object(square(Vec3::ZERO, facing, 0.5), None, m);
    scene.add_object(plane(Vec3::new(3.0, 0.0, 0.0), -Vec3::X), None, d);
    scene.lights.push(OVERHEAD);
    let clear = map_of(&scene, 20_000);
    scene.atmosphere = Atmosphere {
        medium: Medium {
            density: sigma,
            albedo: 0.0,
            color: Color::ONE,
        },
        background_distance: Some(20.0),
    };
    let foggy = map_of(&scene, 20_000);
    assert!(clear.len() > 1000, "{} photons stored", clear.len());
    // The same photons (the fog changes no path), dimmed, within the rounding of the hits.
    let mut clear_photons = clear.photons().to_vec();
    let mut foggy_photons = foggy.photons().to_vec();
    let by_place = |a: &Photon, b: &Photon| {
        a.position
            .to_array()
            .partial_cmp(&b.position.to_array())
            .unwrap()
    };
    clear_photons.sort_by(by_place);
    foggy_photons.sort_by(by_place);
    assert_eq!(clear_photons.len(), foggy_photons.len());
    for (clear, foggy) in clear_photons.iter().zip(&foggy_photons) {
        assert_eq!(clear.position, foggy.position);
        let path = 20.0 + 3.0 + clear.position.y;
        let expected = clear.power.x * (-sigma * path).exp();
        assert!(
            (foggy.power.x - expected).abs() <= 1e-4 * expected,
            "at {}: {} vs {expected}",
            clear.position,
            foggy.power.x
        );
    }
}
