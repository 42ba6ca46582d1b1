//! Fog (`[atmosphere]`): Beer–Lambert attenuation of what a ray sees, wherever it lies and
//! whatever else the scene holds, of the background and of the light reaching a surface, and
//! single scattering from point and spot lights measured against a brute-force integral of the
//! same expression, on short segments and long ones; shadowed parts of a ray gather nothing.

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
/// the eye at the origin, and the `rest` of a scene file. The background lies on the ball
/// around the box of the wall, the eye and the lights: with a point light at (0, 0, 5), the box
/// from (−5, −5, −5) to (5, 5, 5) and the ball of radius 5·√3 around the origin.
fn scene(wall: &str, rest: &str) -> Scene {
    scene_of(
        &format!(
            r#"
        [[objects]]
        type = "triangle"
        vertices = [[-5, -5, -5], [5, -5, -5], [0, 5, -5]]
        material = "wall"

        {rest}
        "#
        ),
        wall,
    )
}

/// A scene of the `objects` (and lights and atmosphere) given, with the material `wall`, seen
/// from the origin towards −z.
fn scene_of(objects: &str, wall: &str) -> Scene {
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

        {objects}
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
    // Or at the distance the file gives, or nowhere: the fog hides it.
    let at = |distance: &str| {
        let atmosphere = format!(
            "[atmosphere]\ndensity = {DENSITY}\nalbedo = 0\nbackground_distance = {distance}"
        );
        scene(AMBIENT_WALL, &format!("{light}\n{atmosphere}"))
    };
    let t20 = (-DENSITY * 20.0).exp();
    assert_close(see(&at("20"), Vec3::X), BACKGROUND * t20, 1e-5);
    assert_close(see(&at("20"), -Vec3::Z), WALL * t5, 1e-5);
    assert_eq!(see(&at("inf"), Vec3::X), Color::ZERO);
}

/// Scene-file text: a plane of the wall's material through `point` facing `normal`, in fog of
/// `density` that only absorbs.
fn plane_in_absorbing_fog(point: [f32; 3], normal: [f32; 3], density: f32) -> String {
    format!(
        r#"
        [[objects]]
        type = "plane"
        point = {point:?}
        normal = {normal:?}
        material = "wall"

        [atmosphere]
        density = {density}
        albedo = 0
        "#
    )
}

/// The wall as an infinite plane 10 units in front of the eye, with the `rest` of a scene, in
/// fog of density 0.1 that only absorbs.
fn far_wall(rest: &str) -> Scene {
    let wall = plane_in_absorbing_fog([0.0, 0.0, -10.0], [0.0, 0.0, 1.0], 0.1);
    scene_of(&format!("{wall}\n{rest}"), AMBIENT_WALL)
}

#[test]
fn a_wall_at_ten_in_fog_of_density_a_tenth_is_dimmed_by_one_over_e_whatever_else_is_there() {
    // Within the rounding of the hit points along ten units.
    let expected = WALL * (-1f32).exp();
    // The plane alone: nothing bounded, no light.
    assert_close(see(&far_wall(""), -Vec3::Z), expected, 1e-4);
    // A small ball and a light far to the side change nothing.
    let aside = r#"
        [[lights]]
        position = [40, 3, 0]

        [[objects]]
        type = "sphere"
        center = [30, 0, -2]
        radius = 0.5
        "#;
    assert_close(see(&far_wall(aside), -Vec3::Z), expected, 1e-4);
    // Seen in a mirror 2 units behind the eye, the wall facing it 8 units further: the path's
    // length is the sum, 10.
    let mirror = r#"
        [materials.mirror]
        ambient = 0
        diffuse = 0
        specular = 0
        reflectivity = 1

        [[objects]]
        type = "plane"
        point = [0, 0, 2]
        normal = [0, 0, -1]
        material = "mirror"
        "#;
    let behind = plane_in_absorbing_fog([0.0, 0.0, -6.0], [0.0, 0.0, 1.0], 0.1);
    let mirrored = scene_of(&format!("{behind}\n{mirror}"), AMBIENT_WALL);
    assert_close(see(&mirrored, Vec3::Z), expected, 1e-4);
}

#[test]
fn a_fogged_floor_darkens_steadily_towards_the_horizon() {
    let floor = plane_in_absorbing_fog([0.0, -1.0, 0.0], [0.0, 1.0, 0.0], 0.05);
    let scene = scene_of(&floor, AMBIENT_WALL);
    // Rays ever closer to the horizon meet the floor ever further away: 1/sin of the angle.
    let mut previous = f32::INFINITY;
    for k in 0..40 {
        let slope = 0.5 * 0.85f32.powi(k);
        let seen = see(&scene, Vec3::new(0.0, -slope, -1.0)).x;
        let distance = (1.0 + slope * slope).sqrt() / slope;
        let expected = WALL.x * (-0.05 * distance).exp();
        assert!(seen < previous, "ray {k}: {seen} after {previous}");
        assert!(
            (seen - expected).abs() <= 1e-4 * WALL.x,
            "ray {k}: {seen}, expected {expected}"
        );
        previous = seen;
    }
    assert!(
        previous < 1e-3 * WALL.x,
        "near the horizon the floor is hidden: {previous}"
    );
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
    // Without point lights the backdrop is the ball around the box from the wall (z = −5) to
    // the eye (z = 0), centred at z = −2.5 with radius √(10² + 10² + 5²) / 2 = 7.5: light from
    // straight ahead crosses ten units of fog, from z = 5, to reach the wall, and the wall is
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

/// The light scattered towards the origin by fog of density `sigma` along the ray down −z to a
/// black wall `length` away, with nothing in the way of the light, which sends `arriving(point)` to each
/// point (before the fog between): the integral of `T(s) · σ_s · colour · 1/(4π) · arriving ·
/// T_light(s)` over the ray, `T_light` over the distance from the point to the light at
/// `light`, by the midpoint rule with a million steps, in double precision.
fn brute_force_single_scattering(
    sigma: f64,
    length: f64,
    light: DVec3,
    arriving: impl Fn(DVec3) -> f64,
    albedo: f64,
    color: DVec3,
) -> Vec3 {
    let steps = 1_000_000;
    let ds = length / steps as f64;
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
    let color = DVec3::new(1.0, 0.8, 0.6);
    let expected = brute_force_single_scattering(DENSITY as f64, 5.0, light, |_| 3.0, 0.8, color);
    assert!(expected.x > 0.01, "the fog should glow visibly: {expected}");
    assert_close(got, expected, 2e-3);
}

/// A fog thin enough that light crosses a hundred units of it.
const LONG_DENSITY: f32 = 0.03;

/// [`single_scattering_scene`] with the black wall an infinite plane 100 units away, in fog of
/// density [`LONG_DENSITY`].
fn long_single_scattering_scene(light: &str) -> Scene {
    let objects = format!(
        r#"
        [[objects]]
        type = "plane"
        point = [0, 0, -100]
        normal = [0, 0, 1]
        material = "wall"

        [[lights]]
        {light}

        [atmosphere]
        density = {LONG_DENSITY}
        albedo = 0.8
        color = [1, 0.8, 0.6]
        "#
    );
    scene_of(&objects, BLACK_WALL)
}

#[test]
fn single_scattering_along_a_hundred_units_matches_a_brute_force_integral() {
    let color = DVec3::new(1.0, 0.8, 0.6);
    // A point light beside the start of the ray, and one far down it.
    for position in [DVec3::new(1.0, 2.0, -2.0), DVec3::new(0.0, 1.0, -60.0)] {
        let light = format!(
            "position = [{}, {}, {}]\nintensity = 3",
            position.x, position.y, position.z
        );
        let got = see(&long_single_scattering_scene(&light), -Vec3::Z);
        let expected = brute_force_single_scattering(
            LONG_DENSITY as f64,
            100.0,
            position,
            |_| 3.0,
            0.8,
            color,
        );
        assert!(expected.x > 1e-4, "the fog should glow: {expected}");
        assert_close(got, expected, 5e-3);
    }
    // A spot light pointing down at the ray 40 units along it.
    let spot = "type = \"spot\"\nposition = [0, 0.5, -40]\ndirection = [0, -1, 0]\nangle = 89\nintensity = 3";
    let got = see(&long_single_scattering_scene(spot), -Vec3::Z);
    let light = DVec3::new(0.0, 0.5, -40.0);
    let inverse_square = |point: DVec3| 3.0 / (light - point).length_squared();
    let expected = brute_force_single_scattering(
        LONG_DENSITY as f64,
        100.0,
        light,
        inverse_square,
        0.8,
        color,
    );
    assert_close(got, expected, 5e-3);
}

#[test]
fn single_scattering_from_a_spot_light_close_to_the_ray_matches_a_brute_force_integral() {
    // Pointing down from 0.3 above the ray, wide enough that the whole ray is in the full cone:
    // the light arriving peaks sharply, as 1/r², where the ray passes under it.
    let spot = "type = \"spot\"\nposition = [0, 0.3, -2.5]\ndirection = [0, -1, 0]\nangle = 89\nintensity = 3";
    let got = see(&single_scattering_scene(spot, ""), -Vec3::Z);
    let light = DVec3::new(0.0, 0.3, -2.5);
    let inverse_square = |point: DVec3| 3.0 / (light - point).length_squared();
    let expected = brute_force_single_scattering(
        DENSITY as f64,
        5.0,
        light,
        inverse_square,
        0.8,
        DVec3::new(1.0, 0.8, 0.6),
    );
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
