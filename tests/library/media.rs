//! Media inside objects (a material's `medium`): what an eye ray sees through an absorbing
//! ball is dimmed by `exp(−σ·chord)`, a shadow ray through a ball, a box, a closed mesh or a
//! hollow CSG ball by `exp(−σ·length inside)`, the caustic photons behind an absorbing slab by
//! `exp(−σ·thickness)`, and the light a smoky ball scatters into a ray matches a brute-force
//! integral of the single-scattering expression.

use std::f64::consts::PI;
use std::path::Path;

use glam::{DVec3, Vec3};
use raylab::bvh::Bvh;
use raylab::color::Color;
use raylab::formats::toml::parse_scene;
use raylab::photon::caustic_map;
use raylab::ray::Ray;
use raylab::scene::Scene;
use raylab::stats::RayCounts;
use raylab::whitted::Tracer;

const BACKGROUND: Color = Color::new(0.2, 0.4, 0.8);

/// A scene with the eye at the origin, no ambient light, and `body`.
fn scene(body: &str) -> Scene {
    let text = format!(
        r#"
        [render]
        background = [0.2, 0.4, 0.8]
        ambient = [0, 0, 0]
        fog_steps = 256

        [camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]

        {body}
        "#
    );
    parse_scene(&text, Path::new("media.toml"), Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// `[materials.smoke]`: clear, colourless glass of index `ior` that reflects nothing and shows
/// no colour of its own, filled with a medium of `density` and `albedo`.
fn smoke(ior: f32, density: f32, albedo: f32) -> String {
    format!(
        "[materials.smoke]\ncolor = [1, 1, 1]\nambient = 0\ndiffuse = 0\nspecular = 0\n\
         transparency = 1\nior = {ior}\nmedium = {{ density = {density}, albedo = {albedo}, \
         color = [1, 0.8, 0.6] }}\n"
    )
}

/// The colour the ray from `origin` along `dir` sees (eye rays see from `t = 1` on).
fn see(scene: &Scene, origin: Vec3, dir: Vec3) -> Color {
    let bvh = Bvh::build(&scene.geometry);
    let ray = Ray::new(origin, dir * 0.01);
    Tracer::new(scene, &bvh).trace_eye(&ray, &mut RayCounts::default())
}

fn assert_close(got: Color, expected: Color, relative: f32) {
    let error = (got - expected).abs().max_element();
    assert!(
        error <= relative * expected.max_element(),
        "got {got}, expected {expected}"
    );
}

/// The length of the chord the line from the origin along `dir` cuts from the ball of
/// `radius` around `center`.
fn chord(dir: DVec3, center: DVec3, radius: f64) -> f64 {
    let dir = dir.normalize();
    let miss = center - center.dot(dir) * dir;
    2.0 * (radius * radius - miss.length_squared()).sqrt()
}

const BALL: &str =
    "[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, -5]\nradius = 2\nmaterial = \"smoke\"";

#[test]
fn the_background_through_an_absorbing_ball_is_dimmed_by_exp_minus_sigma_chord() {
    let sigma = 0.3;
    let ball = scene(&format!("{}\n{BALL}", smoke(1.0, sigma, 0.0)));
    for y in [0.0, 1.0, 1.8] {
        let dir = DVec3::new(0.0, y, -5.0);
        let length = chord(dir, DVec3::new(0.0, 0.0, -5.0), 2.0);
        let got = see(&ball, Vec3::ZERO, dir.as_vec3());
        let expected = BACKGROUND * (-(sigma as f64) * length).exp() as f32;
        // The transmitted ray starts a hair inside the surface (`offset_origin`: 2·10⁻⁴ of the
        // point's size), so it runs about 10⁻³ less far inside than the chord.
        assert_close(got, expected, 1e-3);
    }
    // Beside the ball, and through a ball of clear glass, the background is as it is.
    assert_eq!(
        see(&ball, Vec3::ZERO, Vec3::new(0.0, 2.5, -5.0)),
        BACKGROUND
    );
    let clear = scene(&format!("{}\n{BALL}", smoke(1.0, 0.0, 0.0)));
    assert_eq!(see(&clear, Vec3::ZERO, -Vec3::Z), BACKGROUND);
}

/// A white floor lit by a point light straight above the floor point (0.3, 0, 0.2), with
/// `blocker` (of material `smoke`, made by `smoke`) in between; the colour of that point seen
/// from the side, below any blocker: the light the shadow ray lets through.
fn lit_floor(blocker: &str, density: f32) -> Color {
    let scene = scene(&format!(
        r#"
        {smoke}
        [materials.floor]
        color = [1, 1, 1]
        ambient = 0
        diffuse = 1
        specular = 0

        [[lights]]
        position = [0.3, 10, 0.2]

        [[objects]]
        type = "triangle"
        vertices = [[-20, 0, 20], [20, 0, 20], [0, 0, -20]]
        material = "floor"

        [[objects]]
        material = "smoke"
        {blocker}
        "#,
        smoke = smoke(1.5, density, 0.0),
    ));
    see(&scene, Vec3::new(5.3, 0.5, 0.2), Vec3::new(-5.0, -0.5, 0.0))
}

#[test]
fn a_shadow_ray_is_dimmed_by_the_length_it_travels_inside_each_blocker() {
    let sigma = 0.4;
    // The shadow ray runs up the line x = 0.3, z = 0.2, at 0.13 squared from the y axis.
    let off = 0.13f64;
    let ball = "type = \"sphere\"\ncenter = [0, 2, 0]\nradius = 1";
    let box_ = "type = \"box\"\nmin = [-1, 1, -1]\nmax = [1, 3, 1]";
    // The same box as a closed mesh, its faces wound counter-clockwise seen from outside.
    let mesh = r#"type = "mesh"
        positions = [[-1, 1, -1], [1, 1, -1], [1, 1, 1], [-1, 1, 1],
                     [-1, 3, -1], [1, 3, -1], [1, 3, 1], [-1, 3, 1]]
        faces = [[0, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6], [3, 2, 6], [3, 6, 7],
                 [0, 5, 1], [0, 4, 5], [1, 5, 6], [1, 6, 2], [0, 3, 7], [0, 7, 4]]"#;
    let hollow = r#"type = "csg"
        operation = "difference"
        children = [{ type = "sphere", center = [0, 2, 0], radius = 1 },
                    { type = "sphere", center = [0, 2, 0], radius = 0.5 }]"#;
    let cases = [
        (ball, 2.0 * (1.0 - off).sqrt()),
        (box_, 2.0),
        (mesh, 2.0),
        (hollow, 2.0 * ((1.0 - off).sqrt() - (0.25 - off).sqrt())),
    ];
    for (blocker, length) in cases {
        // Clear glass lets all the light through: the floor shows the light's white.
        assert_close(lit_floor(blocker, 0.0), Color::ONE, 1e-5);
        let expected = (-(sigma as f64) * length).exp() as f32;
        assert_close(lit_floor(blocker, sigma), Color::splat(expected), 1e-4);
    }
}

#[test]
fn caustic_photons_through_an_absorbing_slab_lose_exp_minus_sigma_thickness() {
    // A directional light straight down through a glass slab 0.5 thick at normal incidence:
    // every photon stored on the floor below has travelled 0.5 inside.
    let stored_power = |density: f32| {
        let scene = scene(&format!(
            r#"
            {smoke}
            [[lights]]
            type = "directional"
            direction = [0, 1, 0]

            [[objects]]
            type = "plane"
            point = [0, 0, 0]
            normal = [0, 1, 0]

            [[objects]]
            type = "box"
            min = [-1, 1, -1]
            max = [1, 1.5, 1]
            material = "smoke"
            "#,
            smoke = smoke(1.5, density, 0.0),
        ));
        let bvh = Bvh::build(&scene.geometry);
        let map = caustic_map(&Tracer::new(&scene, &bvh), 20_000).unwrap();
        assert!(map.len() > 1000, "only {} photons stored", map.len());
        map.photons().iter().map(|p| p.power.x).sum::<f32>()
    };
    let ratio = stored_power(0.8) / stored_power(0.0);
    let expected = (-0.8f32 * 0.5).exp();
    // Less the hair the refracted photon starts inside the slab (`offset_origin`).
    assert!(
        (ratio - expected).abs() < 1e-3 * expected,
        "{ratio} vs {expected}"
    );
}

#[test]
fn single_scattering_in_a_smoky_ball_matches_a_brute_force_integral() {
    // The ball of radius 2 around (0, 0, −5), a point light of intensity 3 beside it; the eye
    // ray along −z runs inside from s = 3 to s = 7, towards a black background.
    let (sigma, albedo) = (0.5, 0.8);
    let mut scene = scene(&format!(
        "{}\n{BALL}\n[[lights]]\nposition = [1, 3, -5]\nintensity = 3",
        smoke(1.0, sigma as f32, albedo as f32)
    ));
    scene.settings.background = Color::ZERO;
    let got = see(&scene, Vec3::ZERO, -Vec3::Z);
    // T(s − 3) · σ_s · colour · 1/(4π) · 3 · T_light, T_light over the distance from the point
    // to where the segment towards the light leaves the ball; by the midpoint rule.
    let (center, light) = (DVec3::new(0.0, 0.0, -5.0), DVec3::new(1.0, 3.0, -5.0));
    let steps = 1_000_000;
    let ds = 4.0 / steps as f64;
    let mut sum = 0.0;
    for k in 0..steps {
        let s = 3.0 + (k as f64 + 0.5) * ds;
        let point = DVec3::new(0.0, 0.0, -s);
        let to_light = (light - point).normalize();
        // The far root of |point + u·to_light − center|² = 4.
        let oc = point - center;
        let b = oc.dot(to_light);
        let inside = -b + (b * b - (oc.length_squared() - 4.0)).sqrt();
        sum += (-sigma * (s - 3.0)).exp() * 3.0 * (-sigma * inside).exp() * ds;
    }
    let expected = (sum * sigma * albedo / (4.0 * PI) * DVec3::new(1.0, 0.8, 0.6)).as_vec3();
    assert!(
        expected.x > 0.01,
        "the smoke should glow visibly: {expected}"
    );
    assert_close(got, expected, 2e-3);
}
