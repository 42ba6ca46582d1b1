//! The analytic shapes (polygons, boxes, cylinders, cones, ellipsoids, paraboloids, tori) and
//! spot lights: read with their keys, and their degenerate or out-of-range values refused at the
//! object or the value.

use glam::Vec3;
use raylab::color::Color;
use raylab::light::Light;
use raylab::shapes::Shape;

use crate::harness::{assert_error, parse};

/// A spot light whose keys after `position` are `keys`, one per line from line 4.
fn spot_scene(keys: &str) -> String {
    format!("[[lights]]\ntype = \"spot\"\nposition = [0, 4, 0]\n{keys}\n")
}

#[test]
fn every_analytic_shape_type_is_read() {
    let scene = parse(
        r#"
[[objects]]
type = "polygon"
vertices = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 0.5, 0], [0, 1, 0]]
[[objects]]
type = "box"
min = [-1, -1, -1]
max = [1, 2, 3]
[[objects]]
type = "cylinder"
base = [0, 0, 0]
top = [0, 2, 0]
radius = 0.5
capped = false
[[objects]]
type = "cone"
base_radius = 1
top_radius = 0.5
[[objects]]
type = "ellipsoid"
radii = [1, 2, 3]
[[objects]]
type = "paraboloid"
radius = 1
height = 2
capped = true
"#,
    )
    .unwrap();
    let kinds: Vec<&str> = scene
        .geometry
        .objects
        .iter()
        .map(|o| match &o.shape {
            Shape::Polygon(_) => "polygon",
            Shape::Cuboid(_) => "box",
            Shape::TaperedCylinder(c) if c.is_capped() => "capped",
            Shape::TaperedCylinder(_) => "open",
            Shape::Ellipsoid(_) => "ellipsoid",
            Shape::Paraboloid(_) => "paraboloid",
            _ => "other",
        })
        .collect();
    assert_eq!(
        kinds,
        [
            "polygon",
            "box",
            "open",
            "capped",
            "ellipsoid",
            "paraboloid"
        ]
    );
}

#[test]
fn torus_is_read_with_its_keys_and_turned_by_its_transform() {
    let scene = parse(
        r#"
[[objects]]
type = "torus"
center = [1, 2, 3]
major_radius = 2
minor_radius = 0.5
transform = [ { rotate = { axis = [1, 0, 0], degrees = 90 } } ]
"#,
    )
    .unwrap();
    let object = &scene.geometry.objects[0];
    let Shape::Torus(torus) = &object.shape else {
        panic!("expected a torus, got {:?}", object.shape);
    };
    assert_eq!(torus.center, Vec3::new(1.0, 2.0, 3.0));
    assert_eq!((torus.major_radius, torus.minor_radius), (2.0, 0.5));
    assert!(object.transform.is_some());
    assert!(object.shape.is_closed());
}

#[test]
fn bad_torus_radii_are_errors_at_the_object() {
    let torus = |radii: &str| format!("\n[[objects]]\ntype = \"torus\"\n{radii}\n");
    assert_error(
        &torus("major_radius = 1\nminor_radius = 1"),
        2,
        1,
        "less than major_radius",
    );
    assert_error(
        &torus("major_radius = -1\nminor_radius = 0.5"),
        2,
        1,
        "major_radius must be a positive number",
    );
    assert_error(
        &torus("major_radius = 1\nminor_radius = 0"),
        2,
        1,
        "minor_radius must be a positive number",
    );
    assert_error(&torus("major_radius = 1"), 2, 1, "minor_radius");
    assert_error(
        &torus("major_radius = 1\nminor_radius = 0.5\nradius = 2"),
        6,
        1,
        "unexpected keys in table: radius",
    );
}

#[test]
fn degenerate_shapes_are_errors_at_the_object() {
    assert_error(
        "[[objects]]\ntype = \"cylinder\"\nbase = [0, 1, 0]\ntop = [0, 1, 0]\n",
        1,
        1,
        "axis",
    );
    assert_error(
        "[[objects]]\ntype = \"polygon\"\nvertices = [[0, 0, 0], [1, 0, 0]]\n",
        1,
        1,
        "3 vertices",
    );
    assert_error(
        "[[objects]]\ntype = \"box\"\nmin = [1, 0, 0]\nmax = [0, 1, 1]\n",
        1,
        1,
        "min",
    );
}

#[test]
fn spot_lights_are_read_with_their_cone() {
    let scene = parse(&spot_scene(
        "direction = [0, -2, 0]\nangle = 30\nfalloff = 5\ncolor = [1, 0.5, 0]\nintensity = 2",
    ))
    .unwrap();
    let [Light::Spot(spot)] = scene.lights[..] else {
        panic!("{:?}", scene.lights)
    };
    assert_eq!(spot.position, Vec3::new(0.0, 4.0, 0.0));
    assert_eq!(spot.direction, -Vec3::Y, "the direction is normalised");
    assert_eq!(spot.cos_angle, 30f32.to_radians().cos());
    assert_eq!(spot.cos_full, 25f32.to_radians().cos());
    assert_eq!(spot.color, Color::new(2.0, 1.0, 0.0));
    // Without a falloff the edge is hard.
    let hard = parse(&spot_scene("direction = [0, -1, 0]\nangle = 90")).unwrap();
    let [Light::Spot(hard)] = hard.lights[..] else {
        panic!()
    };
    assert_eq!(hard.cos_full, hard.cos_angle);
}

#[test]
fn spot_light_mistakes_are_errors_at_their_value() {
    assert_error(
        &spot_scene("direction = [0, 0, 0]\nangle = 30"),
        4,
        13,
        "expected a direction",
    );
    for (angle, column) in [("0", 9), ("-10", 9), ("90.5", 9), ("nan", 9)] {
        assert_error(
            &spot_scene(&format!("direction = [0, -1, 0]\nangle = {angle}")),
            5,
            column,
            "angle (the half-angle of its cone, in degrees) must be more than 0 and at most 90",
        );
    }
    for falloff in ["-1", "30.5", "inf"] {
        assert_error(
            &spot_scene(&format!(
                "direction = [0, -1, 0]\nangle = 30\nfalloff = {falloff}"
            )),
            6,
            11,
            "falloff (the degrees of soft edge inside its angle) must be from 0 to the angle, 30",
        );
    }
    assert_error(&spot_scene("angle = 30"), 1, 1, "missing field `direction`");
}
