//! Fog (`[atmosphere]`): Beer–Lambert attenuation of what a ray sees, of the background and of
//! the light reaching a surface, and single scattering from a point light measured against a
//! brute-force integral of the same expression; shadowed parts of a ray gather nothing.

use std::f64::consts::PI;
use std::path::Path;

use glam::{DVec3, Vec3};
use raylab::bvh::Bvh;
use raylab::color::Color;
use raylab::formats::toml::parse_scene;
use raylab::ray::Ray;
use raylab::scene::Scene;
use raylab::stats::RayCounts;
use raylab::whitted::Tracer;

const DENSITY: f32 = 0.3;
/// The colour of the background and of the wall, which is lit by ambient light only.
const BACKGROUND: Color = Color::new(0.2, 0.4, 0.8);
const WALL: Color = Color::new(0.5, 0.25, 1.0);

/// A wall, the triangle (−5, −5, −5), (5, −5, −5), (0, 5, −5) facing +z, five units in front of
/// the eye at the origin, and the `rest` of a scene file. The fog fills the ball around the box
/// of the wall, the eye and the lights: with a point light at (0, 0, 5), the box from
/// (−5, −5, −5) to (5, 5, 5) and the ball of radius 5·√3 around the origin.
fn scene(wall: &str, rest: &str) -> Scene {
    let text = format!(
        r#"
        [render]
        background = [0.2, 0.4, 0.8]
        ambient = [1, 1, 1]
        fog_steps = 64

        [camera]
        eye = [0, 0, 0]
        look_at = [0, 0, -1]

        [materials.wall]
        {wall}

        [[objects]]
        type = "triangle"
        vertices = [[-5, -5, -5], [5, -5, -5], [0, 5, -5]]
        material = "wall"

        {rest}
        "#
    );
    parse_scene(&text, Path::new("fog.toml"), Path::new(".")).unwrap_or_else(|e| panic!("{e}"))
}

/// The wall shows `WALL` by ambient light alone.
const AMBIENT_WALL: &str = "color = [0.5, 0.25, 1]\nambient = 1\ndiffuse = 0\nspecular = 0";
/// The wall reflects nothing: all a ray towards it brings back is what the fog scatters.
const BLACK_WALL: &str = "ambient = 0\ndiffuse = 0\nspecular = 0";

/// The colour an eye ray from the origin along `dir` sees.
fn see(scene: &Scene, dir: Vec3) -> Color {
    let bvh = Bvh::build(&scene.geometry);
    // Eye rays see from t = 1 on; the fog starts at the eye.
    let ray = Ray::new(Vec3::ZERO, dir * 0.01);
    Tracer::new(scene, &bvh).trace_eye(&ray, &mut RayCounts::default())
}

fn assert_close(got: Color, expected: Color, relative: f32) {
    let error = (got - expected).abs().max_element();
    assert!(
        error <= relative * expected.max_element(),
        "got {got}, expected {expected}"
    );
}

#[test]
fn what_lies_at_distance_d_is_dimmed_by_exp_minus_sigma_d() {
    let light = "[[lights]]\nposition = [0, 0, 5]";
    let clear = scene(AMBIENT_WALL, light);
    assert_eq!(see(&clear, -Vec3::Z), WALL);
    assert_eq!(see(&clear, Vec3::X), BACKGROUND);
    // albedo = 0: the fog only absorbs.
    let foggy = scene(
        AMBIENT_WALL,
        &format!("{light}\n[atmosphere]\ndensity = {DENSITY}\nalbedo = 0"),
    );
    let t5 = (-DENSITY * 5.0).exp();
    assert_close(see(&foggy, -Vec3::Z), WALL * t5, 1e-5);
    // The background, seen through the fog up to where the ray leaves the ball, 5·√3 away in
    // every direction.
    let t_ball = (-DENSITY * 5.0 * 3f32.sqrt()).exp();
    for dir in [Vec3::X, Vec3::ONE, Vec3::new(-1.0, 2.0, 0.5)] {
        assert_close(see(&foggy, dir), BACKGROUND * t_ball, 1e-5);
    }
}

#[test]
fn light_reaching_a_surface_is_dimmed_on_its_way_from_the_light() {
    // A white wall lit head-on by a light 10 units away, seen from 5 units away.
    let lit_wall = "color = [1, 1, 1]\nambient = 0\ndiffuse = 1\nspecular = 0";
    let light = "[[lights]]\nposition = [0, 0, 5]\nintensity = 2";
    let foggy = scene(
        lit_wall,
        &format!("{light}\n[atmosphere]\ndensity = {DENSITY}\nalbedo = 0"),
    );
    let expected = 2.0 * (-DENSITY * (10.0 + 5.0)).exp();
    assert_close(see(&foggy, -Vec3::Z), Color::splat(expected), 1e-5);
}

#[test]
fn a_directional_lights_light_is_dimmed_from_where_it_enters_the_fog() {
    // Without point lights the fog fills the ball around the box from the wall (z = −5) to the
    // eye (z = 0), centred at z = −2.5 with radius √(10² + 10² + 5²) / 2 = 7.5: light from
    // straight ahead crosses ten units of it, from z = 5, to reach the wall, and the wall is
    // seen through five more.
    let lit_wall = "color = [1, 1, 1]\nambient = 0\ndiffuse = 1\nspecular = 0";
    let light = "[[lights]]\ntype = \"directional\"\ndirection = [0, 0, 1]";
    let foggy = scene(
        lit_wall,
        &format!("{light}\n[atmosphere]\ndensity = {DENSITY}\nalbedo = 0"),
    );
    let expected = (-DENSITY * (10.0 + 5.0)).exp();
    assert_close(see(&foggy, -Vec3::Z), Color::splat(expected), 1e-5);
}

/// The light scattered towards the origin by the fog along the ray to the black wall, with
/// nothing in the way of the light, which sends `arriving(point)` to each point (before the fog
/// between): the integral of `T(s) · σ_s · colour · 1/(4π) · arriving · T_light(s)` over the
/// five units, `T_light` over the distance from the point to the light at `light`, by the
/// midpoint rule with a million steps, in double precision.
fn brute_force_single_scattering(
    light: DVec3,
    arriving: impl Fn(DVec3) -> f64,
    albedo: f64,
    color: DVec3,
) -> Vec3 {
    let sigma = DENSITY as f64;
    let steps = 1_000_000;
    let ds = 5.0 / steps as f64;
    let mut sum = 0.0;
    for k in 0..steps {
        let s = (k as f64 + 0.5) * ds;
        let point = DVec3::new(0.0, 0.0, -s);
        let to_light = (light - point).length();
        sum += (-sigma * s).exp() * arriving(point) * (-sigma * to_light).exp() * ds;
    }
    (sum * sigma * albedo / (4.0 * PI) * color).as_vec3()
}

fn single_scattering_scene(light: &str, extra: &str) -> Scene {
    scene(
        BLACK_WALL,
        &format!(
            r#"
            [[lights]]
            {light}

            [atmosphere]
            density = {DENSITY}
            albedo = 0.8
            color = [1, 0.8, 0.6]

            {extra}
            "#
        ),
    )
}

const POINT_LIGHT: &str = "position = [1, 2, -2]\nintensity = 3";

#[test]
fn single_scattering_from_a_point_light_matches_a_brute_force_integral() {
    let got = see(&single_scattering_scene(POINT_LIGHT, ""), -Vec3::Z);
    let light = DVec3::new(1.0, 2.0, -2.0);
    let expected = brute_force_single_scattering(light, |_| 3.0, 0.8, DVec3::new(1.0, 0.8, 0.6));
    assert!(expected.x > 0.01, "the fog should glow visibly: {expected}");
    assert_close(got, expected, 2e-3);
}

#[test]
fn single_scattering_from_a_spot_light_close_to_the_ray_matches_a_brute_force_integral() {
    // Pointing down from 0.3 above the ray, wide enough that the whole ray is in the full cone:
    // the light arriving peaks sharply, as 1/r², where the ray passes under it.
    let spot = "type = \"spot\"\nposition = [0, 0.3, -2.5]\ndirection = [0, -1, 0]\nangle = 89\nintensity = 3";
    let got = see(&single_scattering_scene(spot, ""), -Vec3::Z);
    let light = DVec3::new(0.0, 0.3, -2.5);
    let inverse_square = |point: DVec3| 3.0 / (light - point).length_squared();
    let expected =
        brute_force_single_scattering(light, inverse_square, 0.8, DVec3::new(1.0, 0.8, 0.6));
    assert_close(got, expected, 2e-3);
}

#[test]
fn a_shadowed_segment_scatters_nothing_into_the_ray() {
    let open = see(&single_scattering_scene(POINT_LIGHT, ""), -Vec3::Z);
    // A slab between the light and the whole ray: every sample point is in shadow.
    let slab = |z_min: f32| {
        format!(
            "[[objects]]\ntype = \"box\"\nmin = [-5, 1, {z_min}]\nmax = [5, 1.2, 1]\nmaterial = \"wall\""
        )
    };
    let shadowed = see(&single_scattering_scene(POINT_LIGHT, &slab(-5.0)), -Vec3::Z);
    assert_eq!(shadowed, Color::ZERO);
    // A slab over the far half only leaves the near half lit: a beam.
    let half = see(&single_scattering_scene(POINT_LIGHT, &slab(-2.5)), -Vec3::Z);
    assert!(
        half.x > 0.0 && half.x < open.x,
        "open {open}, half shadowed {half}"
    );
}

#[test]
fn a_scene_without_atmosphere_has_no_fog() {
    let scene = scene(AMBIENT_WALL, "[[lights]]\nposition = [0, 0, 5]");
    let bvh = Bvh::build(&scene.geometry);
    assert!(Tracer::new(&scene, &bvh).fog.is_none());
    let thin = scene_with_density(0.0);
    assert!(
        Tracer::new(&thin, &Bvh::build(&thin.geometry))
            .fog
            .is_none()
    );
}

fn scene_with_density(density: f32) -> Scene {
    scene(
        AMBIENT_WALL,
        &format!("[[lights]]\nposition = [0, 0, 5]\n[atmosphere]\ndensity = {density}"),
    )
}
