//! Spot lights: the irradiance they give a floor under them is the inverse-square law's
//! `I·cos θ / r²` inside the cone, nothing outside it and a smoothstep across its soft edge, and
//! objects in the cone cast shadows.

use std::path::Path;

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::color::Color;
use raylab::formats::toml::parse_scene;
use raylab::ray::Ray;
use raylab::scene::Scene;
use raylab::stats::RayCounts;
use raylab::whitted::Tracer;

/// Height of the spot over the floor, its intensity, half-angle and soft edge.
const HEIGHT: f32 = 4.0;
const INTENSITY: f32 = 20.0;
const ANGLE: f32 = 40.0;
const FALLOFF: f32 = 10.0;

/// A white floor that shows its irradiance (diffuse 1, no ambient or specular light) under a
/// spot pointing straight down, and a small ball, off to the side, inside the cone.
fn floor_under_spot() -> Scene {
    let text = format!(
        r#"
        [render]
        ambient = [0, 0, 0]

        [[lights]]
        type = "spot"
        position = [0, {HEIGHT}, 0]
        direction = [0, -1, 0]
        angle = {ANGLE}
        falloff = {FALLOFF}
        intensity = {INTENSITY}

        [materials.floor]
        color = [1, 1, 1]
        ambient = 0
        diffuse = 1
        specular = 0

        [[objects]]
        type = "plane"
        material = "floor"

        [[objects]]
        type = "sphere"
        center = [0, 2, -1]
        radius = 0.25
        "#
    );
    parse_scene(&text, Path::new("spot.toml"), Path::new(".")).unwrap()
}

/// The colour of the floor at `point`, seen from straight above.
fn floor_color(scene: &Scene, point: Vec3) -> Color {
    let bvh = Bvh::build(&scene.geometry);
    // Eye rays see from t = 1 on: start half a unit up and reach the floor at t = 5.
    let ray = Ray::new(point + Vec3::Y * 0.5, -Vec3::Y * 0.1);
    Tracer::new(scene, &bvh).trace_eye(&ray, &mut RayCounts::default())
}

/// `I·cos θ / r²` at the floor point `x` units from the foot of the light, θ being the angle
/// between the floor's normal and the direction to the light (which here is also the angle
/// off the spot's axis).
fn inverse_square(x: f32) -> f32 {
    let r2 = HEIGHT * HEIGHT + x * x;
    INTENSITY * (HEIGHT / r2.sqrt()) / r2
}

/// The floor point whose direction from the light is `degrees` off the spot's axis.
fn at_angle(degrees: f32) -> f32 {
    HEIGHT * degrees.to_radians().tan()
}

fn assert_close(got: f32, expected: f32, what: &str) {
    assert!(
        (got - expected).abs() <= 1e-4 * expected.max(1.0),
        "{what}: got {got}, expected {expected}"
    );
}

#[test]
fn inside_the_cone_the_floor_gets_i_cos_theta_over_r_squared() {
    let scene = floor_under_spot();
    for degrees in [0.0, 10.0, 20.0, ANGLE - FALLOFF - 0.5] {
        let x = at_angle(degrees);
        let color = floor_color(&scene, Vec3::new(x, 0.0, 0.0));
        assert_close(color.x, inverse_square(x), &format!("{degrees}° off axis"));
        assert_eq!(color.x, color.z, "white light on a white floor");
    }
}

#[test]
fn outside_the_cone_the_floor_is_dark() {
    let scene = floor_under_spot();
    for degrees in [ANGLE + 0.5, 60.0, 85.0] {
        let color = floor_color(&scene, Vec3::new(at_angle(degrees), 0.0, 0.0));
        assert_eq!(color, Color::ZERO, "{degrees}° off axis");
    }
}

#[test]
fn across_the_soft_edge_the_light_fades_by_a_smoothstep_of_the_cosine() {
    let scene = floor_under_spot();
    let (cos_outer, cos_inner) = (
        ANGLE.to_radians().cos(),
        (ANGLE - FALLOFF).to_radians().cos(),
    );
    let mut last = f32::INFINITY;
    for step in 1..10 {
        let degrees = ANGLE - FALLOFF + step as f32;
        let x = at_angle(degrees);
        let got = floor_color(&scene, Vec3::new(x, 0.0, 0.0)).x;
        let s = (degrees.to_radians().cos() - cos_outer) / (cos_inner - cos_outer);
        let expected = inverse_square(x) * s * s * (3.0 - 2.0 * s);
        assert_close(got, expected, &format!("{degrees}° off axis"));
        assert!(got > 0.0 && got < inverse_square(x), "{degrees}°: {got}");
        assert!(got < last, "the light fades outwards");
        last = got;
    }
}

#[test]
fn a_ball_in_the_cone_casts_a_shadow() {
    let scene = floor_under_spot();
    // The ball at (0, 2, -1) throws its shadow, seen from the light at height 4, to (0, 0, -2).
    let shadowed = floor_color(&scene, Vec3::new(0.0, 0.0, -2.0));
    assert_eq!(shadowed, Color::ZERO);
    let beside = floor_color(&scene, Vec3::new(0.0, 0.0, 2.0));
    assert_close(
        beside.x,
        inverse_square(2.0),
        "the point across from the shadow",
    );
}
