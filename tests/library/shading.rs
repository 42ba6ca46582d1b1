//! The Whitted shading model: shadows, mirrors, refraction through glass, total internal
//! reflection and adaptive depth control.

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::color::Color;
use raylab::light::Light;
use raylab::material::Material;
use raylab::progressive;
use raylab::ray::Ray;
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape, Sphere};
use raylab::stats::RayCounts;
use raylab::whitted::{Tracer, refract, scattering};

fn trace(scene: &Scene, ray: &Ray) -> (Color, RayCounts) {
    let bvh = Bvh::build(&scene.geometry);
    let mut counts = RayCounts::default();
    let c = Tracer::new(scene, &bvh).trace_eye(ray, &mut counts);
    (c, counts)
}

fn plane(point: Vec3, normal: Vec3) -> Shape {
    Shape::Plane(Plane { point, normal })
}

/// A floor and a sphere hanging above it, lit from straight above.
fn sphere_over_floor(blocker: Material) -> Scene {
    let mut scene = Scene::new(
        RenderSettings::default(),
        crate::common::camera(Vec3::new(0.0, 5.0, 5.0), Vec3::ZERO, 45.0),
    );
    let floor = scene.add_material(Material {
        color: Color::new(0.5, 0.6, 0.7),
        ambient: 0.3,
        diffuse: 0.9,
        ..Material::default()
    });
    let blocker = scene.add_material(blocker);
    scene.add_object(plane(Vec3::ZERO, Vec3::Y), None, floor);
    scene.add_object(
        Shape::Sphere(Sphere {
            center: Vec3::new(0.0, 2.0, 0.0),
            radius: 1.0,
        }),
        None,
        blocker,
    );
    scene.lights.push(Light::Point {
        position: Vec3::new(0.0, 10.0, 0.0),
        color: Color::ONE,
    });
    scene
}

/// An eye ray from beside the sphere down to the floor point under it.
fn ray_to_floor_under_sphere() -> Ray {
    eye_ray(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, -1.0, -5.0))
}

/// An eye ray from `eye` along `dir`. Eye rays see only beyond `t = 1` (the image plane), so the
/// direction is scaled to put the image plane a hundredth of a unit in front of the eye.
fn eye_ray(eye: Vec3, dir: Vec3) -> Ray {
    Ray::new(eye, dir.normalize() * 0.01)
}

#[test]
fn a_point_in_shadow_gets_only_ambient_light() {
    let scene = sphere_over_floor(Material::default());
    let (c, counts) = trace(&scene, &ray_to_floor_under_sphere());
    let floor = &scene.materials[0];
    let ambient_only = floor.ambient * floor.color * scene.settings.ambient;
    assert!((c - ambient_only).length() < 1e-6, "{c} != {ambient_only}");
    assert_eq!(counts.shadow, 1);
}

#[test]
fn emission_adds_to_every_hit_whatever_lights_it_and_lights_nothing_else() {
    let glow = Color::new(2.0, 1.0, 0.5);
    let lamp = Material {
        emission: glow,
        ..Material::default()
    };
    let scene = sphere_over_floor(lamp.clone());
    let dark = sphere_over_floor(Material::default());
    // The floor in the glowing ball's shadow: ambient only, as under a ball that gives off
    // nothing.
    let ray = ray_to_floor_under_sphere();
    assert_eq!(trace(&scene, &ray).0, trace(&dark, &ray).0);
    // The ball's underside, turned from the light: emission and ambient.
    let up = eye_ray(Vec3::new(0.0, 0.5, 0.0), Vec3::Y);
    let ambient = lamp.ambient * lamp.color * scene.settings.ambient;
    let (c, _) = trace(&scene, &up);
    assert!((c - (glow + ambient)).length() < 1e-6, "{c}");
    // Its top, lit head-on: emission, ambient and diffuse.
    let down = eye_ray(Vec3::new(0.0, 5.0, 0.0), -Vec3::Y);
    let (c, _) = trace(&scene, &down);
    let expected = glow + ambient + lamp.diffuse * lamp.color;
    assert!((c - expected).length() < 1e-5, "{c} != {expected}");
}

#[test]
fn an_emission_texture_multiplies_the_emission_texel_by_texel() {
    // A black floor that glows through a checker texture: a point of it is the emission times
    // the checker's colour there, lights or not; with textures off, the emission alone.
    let mut scene = sphere_over_floor(Material::default());
    let checks = scene.textures.len() as u32;
    scene.textures.push(raylab::texture::Texture::Checker3d {
        a: Color::new(1.0, 0.25, 0.0),
        b: Color::new(0.0, 0.5, 1.0),
        size: 1.0,
    });
    let floor = scene.materials.len() as u32;
    scene.add_material(Material {
        color: Color::ZERO,
        ambient: 0.0,
        emission: Color::new(0.8, 0.6, 0.4),
        emission_texture: Some(checks),
        ..Material::default()
    });
    scene.geometry.objects[0].material = floor;
    let points = [Vec3::new(2.5, 0.0, 0.5), Vec3::new(3.5, 0.0, 0.5)];
    let mut seen = Vec::new();
    for p in points {
        let ray = eye_ray(p + Vec3::new(0.0, 5.0, 0.1), Vec3::new(0.0, -1.0, -0.02));
        let (glow, _) = trace(&scene, &ray);
        let texel =
            scene.textures[checks as usize].color(glam::Vec2::ZERO, ray.at(ray_floor_t(&ray)));
        assert!(
            (glow - Color::new(0.8, 0.6, 0.4) * texel)
                .abs()
                .max_element()
                < 1e-6,
            "{glow}"
        );
        seen.push(glow);
        let mut plain = scene.clone();
        plain.settings.textures = false;
        assert_eq!(trace(&plain, &ray).0, Color::new(0.8, 0.6, 0.4));
    }
    assert_ne!(seen[0], seen[1], "both checks show");
}

/// Where `ray` meets the floor y = 0.
fn ray_floor_t(ray: &Ray) -> f32 {
    -ray.origin.y / ray.dir.y
}

#[test]
fn a_lit_point_gets_lambert_diffuse_light() {
    let mut scene = sphere_over_floor(Material::default());
    scene.geometry.objects.pop(); // no blocker
    let (c, _) = trace(&scene, &ray_to_floor_under_sphere());
    let floor = &scene.materials[0];
    // Light straight above: n·l = 1.
    let expected =
        floor.ambient * floor.color * scene.settings.ambient + floor.diffuse * floor.color;
    assert!((c - expected).length() < 1e-5, "{c} != {expected}");
}

#[test]
fn a_transparent_blocker_lets_its_tinted_share_through() {
    let tint = Color::new(1.0, 0.5, 0.25);
    let glass = Material {
        color: tint,
        transparency: 0.8,
        ior: 1.0,
        ..Material::default()
    };
    let scene = sphere_over_floor(glass);
    let (c, _) = trace(&scene, &ray_to_floor_under_sphere());
    let floor = &scene.materials[0];
    let expected = floor.ambient * floor.color * scene.settings.ambient
        + floor.diffuse * floor.color * (0.8 * tint);
    assert!((c - expected).length() < 1e-5, "{c} != {expected}");
}

#[test]
fn turning_shadows_off_lights_the_point() {
    let mut scene = sphere_over_floor(Material::default());
    scene.settings.shadows = false;
    let (c, counts) = trace(&scene, &ray_to_floor_under_sphere());
    assert_eq!(counts.shadow, 0);
    let floor = &scene.materials[0];
    assert!(c.x > floor.ambient * floor.color.x * scene.settings.ambient.x + 0.1);
}

/// Matte spheres well in front of the plane z = 0, lit, on a coloured background.
fn spheres_before_the_mirror_plane(mirror: bool) -> Scene {
    let settings = RenderSettings {
        width: 40,
        height: 30,
        background: Color::new(0.1, 0.2, 0.3),
        ..RenderSettings::default()
    };
    let mut scene = Scene::new(settings, crate::common::camera(Vec3::ZERO, Vec3::Z, 40.0));
    let colors = [Color::new(0.9, 0.2, 0.1), Color::new(0.1, 0.8, 0.3)];
    for (i, color) in colors.into_iter().enumerate() {
        let m = scene.add_material(Material {
            color,
            specular: 0.4,
            ..Material::default()
        });
        scene.add_object(
            Shape::Sphere(Sphere {
                center: Vec3::new(-1.0 + 2.0 * i as f32, 0.3 * i as f32, 3.5 + i as f32),
                radius: 0.8,
            }),
            None,
            m,
        );
    }
    scene.lights.push(Light::Point {
        position: Vec3::new(3.0, 4.0, 6.0),
        color: Color::ONE,
    });
    if mirror {
        let m = scene.add_material(Material {
            ambient: 0.0,
            diffuse: 0.0,
            reflectivity: 1.0,
            ..Material::default()
        });
        scene.add_object(plane(Vec3::ZERO, Vec3::Z), None, m);
    }
    scene
}

#[test]
fn a_mirror_shows_what_a_mirrored_camera_sees() {
    // Camera A stands between the spheres and the mirror z = 0, looking at the mirror; camera B
    // stands at the mirror image of A's eye, in the scene without the mirror, looking at the
    // spheres. B's image is A's, flipped left to right.
    let mut a = spheres_before_the_mirror_plane(true);
    a.camera = crate::common::camera(Vec3::new(0.5, 0.5, 2.0), Vec3::new(0.0, 0.5, 0.0), 60.0);
    let mut b = spheres_before_the_mirror_plane(false);
    b.camera = crate::common::camera(Vec3::new(0.5, 0.5, -2.0), Vec3::new(0.0, 0.5, 0.0), 60.0);
    let render = |scene: &Scene| {
        let bvh = Bvh::build(&scene.geometry);
        progressive::render_image(&Tracer::new(scene, &bvh)).0
    };
    let (image_a, image_b) = (render(&a), render(&b));
    let (w, h) = (40, 30);
    let mut sphere_pixels = 0;
    for y in 0..h {
        for x in 0..w {
            let pa = image_a[y * w + x];
            let pb = image_b[y * w + (w - 1 - x)];
            assert!(
                (pa - pb).abs().max_element() < 1e-3,
                "({x}, {y}): {pa} vs {pb}"
            );
            sphere_pixels += (pa != a.settings.background) as usize;
        }
    }
    assert!(
        sphere_pixels > 50,
        "the spheres are in view ({sphere_pixels} pixels)"
    );
}

/// The mirror's material in `scene` (the last one added), its reflection tinted by `tint`.
fn tinted(mut scene: Scene, tint: Color) -> Scene {
    let last = scene.materials.len() - 1;
    scene.materials[last].reflection_color = tint;
    scene
}

#[test]
fn a_tinted_mirror_multiplies_what_it_reflects_by_its_colour() {
    // The mirror reflects everything and scatters nothing: each pixel of it is what it
    // reflects, times the tint, channel by channel.
    let mut white = spheres_before_the_mirror_plane(true);
    white.camera = crate::common::camera(Vec3::new(0.5, 0.5, 2.0), Vec3::new(0.0, 0.5, 0.0), 60.0);
    let tint = Color::new(1.0, 0.75, 0.25);
    let gold = tinted(white.clone(), tint);
    let render = |scene: &Scene| {
        let bvh = Bvh::build(&scene.geometry);
        progressive::render_image(&Tracer::new(scene, &bvh)).0
    };
    let (plain, golden) = (render(&white), render(&gold));
    for (p, g) in plain.iter().zip(&golden) {
        assert!(
            (*p * tint - *g).abs().max_element() < 1e-5,
            "{p} × {tint} ≠ {g}"
        );
    }
    let tinted_pixels = plain.iter().zip(&golden).filter(|(p, g)| p != g).count();
    assert!(tinted_pixels > 600, "{tinted_pixels} pixels tinted");
}

#[test]
fn the_light_fresnel_takes_from_transmission_is_reflected_untinted() {
    // Glass that reflects nothing of its own (kr 0) but Fresnel's share: its tint does not
    // touch that share, so a black tint changes nothing.
    let mut scene = spheres_before_the_mirror_plane(false);
    scene.camera = crate::common::camera(Vec3::new(0.5, 0.5, -2.0), Vec3::new(0.0, 0.5, 0.0), 60.0);
    let glass = scene.add_material(Material {
        fresnel: true,
        ..crate::common::clear_glass()
    });
    scene.add_object(plane(Vec3::new(0.0, 0.0, 1.0), Vec3::Z), None, glass);
    let render = |scene: &Scene| {
        let bvh = Bvh::build(&scene.geometry);
        progressive::render_image(&Tracer::new(scene, &bvh)).0
    };
    let black = tinted(scene.clone(), Color::ZERO);
    assert_eq!(render(&scene), render(&black));
    // And the glass does reflect: without Fresnel the image changes.
    let mut plain = scene.clone();
    let last = plain.materials.len() - 1;
    plain.materials[last].fresnel = false;
    assert_ne!(render(&scene), render(&plain));
}

#[test]
fn snell_law_bends_rays_and_a_slab_shifts_them_sideways() {
    let d = Vec3::new(1.0, -1.0, 0.0).normalize(); // 45° incidence on the floor y = 0
    let inside = refract(d, Vec3::Y, 1.0 / 1.5).unwrap();
    let sin_i = d.x;
    let sin_t = inside.x;
    assert!((sin_i / sin_t - 1.5).abs() < 1e-5, "n1 sin θi = n2 sin θt");
    // Through a slab of thickness 2 between y = 0 and y = −2, the ray leaves parallel to how
    // it came in, shifted sideways by thickness · sin(θi − θt) / cos θt.
    let out = refract(inside, Vec3::Y, 1.5).unwrap();
    assert!((out - d).length() < 1e-5, "leaves parallel");
    let (theta_i, theta_t) = (sin_i.asin(), sin_t.asin());
    let expected_shift = 2.0 * (theta_i - theta_t).sin() / theta_t.cos();
    // Measured: where the bent ray leaves (y = −2) against the straight line, perpendicular
    // to the ray.
    let exit = inside * (2.0 / -inside.y);
    let straight = d * (2.0 / -d.y);
    let shift = (exit - straight).cross(d).length();
    assert!(
        (shift - expected_shift).abs() < 1e-5,
        "{shift} vs {expected_shift}"
    );
}

#[test]
fn a_glass_slab_in_a_scene_refracts_the_eye_ray_twice() {
    // Two planes make a slab: the eye ray enters through the top (front face) and leaves through
    // the bottom (back face), then hits nothing: two transmitted rays.
    let mut scene = Scene::new(
        RenderSettings::default(),
        crate::common::camera(Vec3::new(0.0, 5.0, 1.0), Vec3::ZERO, 45.0),
    );
    let glass = scene.add_material(Material {
        transparency: 1.0,
        ior: 1.5,
        ..Material::default()
    });
    scene.add_object(plane(Vec3::ZERO, Vec3::Y), None, glass);
    scene.add_object(plane(Vec3::new(0.0, -2.0, 0.0), -Vec3::Y), None, glass);
    let (_, counts) = trace(
        &scene,
        &eye_ray(Vec3::new(0.0, 5.0, 0.0), Vec3::new(1.0, -1.0, 0.3)),
    );
    assert_eq!(counts.transmitted, 2);
}

#[test]
fn total_internal_reflection_past_the_critical_angle() {
    let glass = Material {
        transparency: 0.9,
        reflectivity: 0.05,
        ior: 1.5,
        ..Material::default()
    };
    let critical = (1.0f32 / 1.5).asin();
    // Leaving the glass: the normal facing the ray points back into the glass (−Y here).
    let inside_ray = |angle: f32| Vec3::new(angle.sin(), angle.cos(), 0.0);
    let below = scattering(&glass, inside_ray(critical - 0.01), -Vec3::Y, false);
    assert!(below.refracted.is_some());
    assert_eq!((below.reflect, below.transmit), (0.05, 0.9));
    let past = scattering(&glass, inside_ray(critical + 0.01), -Vec3::Y, false);
    assert!(past.refracted.is_none());
    assert!((past.reflect - 0.95).abs() < 1e-6 && past.transmit == 0.0);
    // Entering, there is no critical angle.
    let grazing = scattering(
        &glass,
        Vec3::new(0.999, -0.0447, 0.0).normalize(),
        Vec3::Y,
        true,
    );
    assert!(grazing.refracted.is_some());
}

#[test]
fn fresnel_reflects_more_at_grazing_angles() {
    let glass = Material {
        transparency: 1.0,
        ior: 1.5,
        fresnel: true,
        ..Material::default()
    };
    let head_on = scattering(&glass, -Vec3::Y, Vec3::Y, true);
    let grazing = scattering(
        &glass,
        Vec3::new(0.995, -0.0998, 0.0).normalize(),
        Vec3::Y,
        true,
    );
    assert!((head_on.reflect - 0.04).abs() < 1e-3, "{}", head_on.reflect);
    assert!(grazing.reflect > 0.5);
    assert!(
        (grazing.reflect + grazing.transmit - 1.0).abs() < 1e-5,
        "energy is split"
    );
}

/// Two facing half mirrors; the eye ray bounces between them.
fn facing_mirrors(max_depth: u32, min_weight: f32) -> (Scene, Ray) {
    let settings = RenderSettings {
        max_depth,
        min_weight,
        ..RenderSettings::default()
    };
    let mut scene = Scene::new(settings, crate::common::camera(Vec3::ZERO, Vec3::X, 45.0));
    let half_mirror = scene.add_material(Material {
        reflectivity: 0.5,
        ..Material::default()
    });
    scene.add_object(plane(Vec3::new(0.0, 0.0, -1.0), Vec3::Z), None, half_mirror);
    scene.add_object(plane(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z), None, half_mirror);
    (scene, eye_ray(Vec3::ZERO, Vec3::new(0.1, 0.0, -1.0)))
}

#[test]
fn recursion_stops_at_max_depth() {
    for max_depth in [1, 2, 5, 10] {
        let (scene, ray) = facing_mirrors(max_depth, 0.0);
        let (_, counts) = trace(&scene, &ray);
        // The eye ray is depth 1; each bounce adds one level.
        assert_eq!(
            counts.reflected,
            max_depth as u64 - 1,
            "max_depth {max_depth}"
        );
    }
}

#[test]
fn adaptive_depth_stops_where_the_weight_falls_below_the_threshold() {
    // Weights along the tree: 0.5, 0.25, 0.125, 0.0625 …
    for (min_weight, expected) in [(0.3, 1), (0.2, 2), (0.1, 3), (0.06, 4), (0.0, 9)] {
        let (scene, ray) = facing_mirrors(10, min_weight);
        let (_, counts) = trace(&scene, &ray);
        assert_eq!(counts.reflected, expected, "min_weight {min_weight}");
    }
}
