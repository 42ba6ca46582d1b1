//! The ray tree of a pixel (`raylab::inspect`), checked node by node on scenes built by hand.
//! (`tests/library/inspect_image.rs` checks it against rendered images.) And a pixel's difference from
//! another image explained from it (`raylab::compare::explain`).

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::camera::{Camera, CameraSpec};
use raylab::color::Color;
use raylab::compare::explain::explain_pixel;
use raylab::inspect::{RayTree, trace_ray_tree};
use raylab::light::Light;
use raylab::material::Material;
use raylab::medium::{Atmosphere, Medium};
use raylab::scene::Scene;
use raylab::settings::RenderSettings;
use raylab::shapes::{Plane, Shape, Sphere};
use raylab::whitted::{RayKind, StopReason, Tracer};

/// The side of the hand-built scenes' images: odd, so the centre pixel looks straight ahead.
const SIDE: u32 = 11;
const CENTRE: u32 = SIDE / 2;

fn settings(max_depth: u32, min_weight: f32) -> RenderSettings {
    RenderSettings {
        width: SIDE,
        height: SIDE,
        max_depth,
        min_weight,
        ..RenderSettings::default()
    }
}

fn camera(eye: Vec3, look_at: Vec3, near: f32) -> Camera {
    Camera::new(CameraSpec {
        eye,
        look_at,
        up: Vec3::Y,
        view_angle: 30.0,
        near,
    })
    .unwrap()
}

fn plane(point: Vec3, normal: Vec3) -> Shape {
    Shape::Plane(Plane { point, normal })
}

fn sphere(center: Vec3, radius: f32) -> Shape {
    Shape::Sphere(Sphere { center, radius })
}

fn centre_tree(scene: &Scene) -> RayTree {
    let bvh = Bvh::build(&scene.geometry);
    trace_ray_tree(&Tracer::new(scene, &bvh), CENTRE, CENTRE)
}

fn close(a: Vec3, b: Vec3, tolerance: f32) -> bool {
    (a - b).abs().max_element() <= tolerance
}

/// A mirror at z = −5 facing the eye at the origin, a matte wall behind the eye at z = 5.
fn mirror_facing_a_wall() -> Scene {
    let mut scene = Scene::new(settings(5, 0.01), camera(Vec3::ZERO, -Vec3::Z, 1.0));
    let mirror = scene.add_material(Material {
        reflectivity: 0.8,
        ..Material::default()
    });
    let wall = scene.add_material(Material {
        color: Color::new(0.2, 0.7, 0.3),
        ..Material::default()
    });
    scene.add_object(plane(Vec3::new(0.0, 0.0, -5.0), Vec3::Z), None, mirror);
    scene.add_object(plane(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z), None, wall);
    scene.lights.push(Light::Point {
        position: Vec3::new(0.0, 2.0, 0.0),
        color: Color::ONE,
    });
    scene
}

#[test]
fn a_mirror_facing_a_wall_spawns_one_reflected_ray_that_sees_the_wall() {
    let scene = mirror_facing_a_wall();
    let tree = centre_tree(&scene);
    assert_eq!(tree.nodes.len(), 2, "{}", tree.to_text());
    let (eye, reflected) = (&tree.nodes[0], &tree.nodes[1]);

    assert_eq!((eye.kind, eye.depth, eye.parent), (RayKind::Eye, 1, None));
    assert_eq!(eye.children, vec![1]);
    let hit = eye.hit.as_ref().expect("the eye ray hits the mirror");
    assert_eq!((hit.object, hit.material), (0, 0));
    assert!(hit.label.contains("plane"), "{}", hit.label);
    assert!(
        (hit.t - 5.0).abs() < 1e-4,
        "the mirror is 5 away: {}",
        hit.t
    );
    assert!(close(hit.point, Vec3::new(0.0, 0.0, -5.0), 1e-4));
    assert!(close(hit.normal, Vec3::Z, 1e-6));
    assert!(hit.entering);
    assert_eq!(eye.shadows.len(), 1);
    assert!(!eye.shadows[0].blocked && eye.shadows[0].blockers.is_empty());

    assert_eq!(
        (reflected.kind, reflected.depth, reflected.parent),
        (RayKind::Reflected, 2, Some(0))
    );
    assert!(close(reflected.dir, Vec3::Z, 1e-5), "{}", reflected.dir);
    assert!((reflected.weight - 0.8).abs() < 1e-6);
    assert!(close(reflected.factor, Color::splat(0.8), 1e-6));
    let wall = reflected
        .hit
        .as_ref()
        .expect("the reflected ray hits the wall");
    assert_eq!((wall.object, wall.material), (1, 1));
    // Secondary rays start a little off the surface they leave.
    assert!((wall.t - 10.0).abs() < 1e-2, "{}", wall.t);
    assert!(reflected.children.is_empty() && reflected.cuts.is_empty());
    assert_eq!(
        reflected.stop, None,
        "a matte wall ends the branch by itself"
    );

    let expected = eye.local_color + 0.8 * reflected.local_color;
    assert!(
        close(tree.color, expected, 1e-6),
        "{} != {expected}",
        tree.color
    );
    assert_eq!(eye.color, tree.color);
}

/// A glass ball of radius 1 at the origin, without reflection, seen from `eye`.
fn glass_ball(eye: Vec3, look_at: Vec3) -> Scene {
    let mut scene = Scene::new(settings(5, 0.0), camera(eye, look_at, 0.05));
    let glass = scene.add_material(crate::common::clear_glass());
    scene.add_object(sphere(Vec3::ZERO, 1.0), None, glass);
    scene.lights.push(Light::Point {
        position: Vec3::new(0.0, 5.0, 5.0),
        color: Color::ONE,
    });
    scene
}

#[test]
fn a_glass_ball_is_entered_and_left_by_transmitted_rays() {
    let scene = glass_ball(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO);
    let tree = centre_tree(&scene);
    let kinds: Vec<_> = tree.nodes.iter().map(|n| (n.kind, n.depth)).collect();
    assert_eq!(
        kinds,
        [
            (RayKind::Eye, 1),
            (RayKind::Transmitted, 2),
            (RayKind::Transmitted, 3)
        ],
        "{}",
        tree.to_text()
    );
    let front = tree.nodes[0].hit.as_ref().unwrap();
    assert!(front.entering && close(front.point, Vec3::Z, 1e-4));
    let back = tree.nodes[1].hit.as_ref().unwrap();
    assert!(!back.entering, "the second hit is on the inside");
    assert!(close(back.point, -Vec3::Z, 1e-4), "{}", back.point);
    assert!(close(back.normal, Vec3::Z, 1e-4), "turned to face the ray");
    assert!(
        (back.t - 2.0).abs() < 1e-2,
        "through the diameter: {}",
        back.t
    );
    let out = &tree.nodes[2];
    assert!(out.hit.is_none() && out.stop == Some(StopReason::Miss));
    assert_eq!(out.local_color, scene.settings.background);
    assert!((out.weight - 0.81).abs() < 1e-6);
    assert!(close(out.factor, Color::splat(0.81), 1e-6));
}

#[test]
fn a_grazing_ray_inside_a_glass_ball_is_totally_reflected() {
    // From inside, 0.8 above the centre, looking along −z: the ray meets the surface at
    // (0, 0.8, −0.6), 53° from the normal, past glass's critical angle of 41.8°.
    let eye = Vec3::new(0.0, 0.8, 0.0);
    let scene = glass_ball(eye, eye - Vec3::Z);
    let tree = centre_tree(&scene);
    let first = &tree.nodes[0];
    let hit = first.hit.as_ref().unwrap();
    assert!(!hit.entering);
    assert!(
        close(hit.point, Vec3::new(0.0, 0.8, -0.6), 1e-4),
        "{}",
        hit.point
    );
    assert_eq!(first.cuts.len(), 1, "{}", tree.to_text());
    assert_eq!(first.cuts[0].branch, RayKind::Transmitted);
    assert_eq!(first.cuts[0].reason, StopReason::TotalInternalReflection);
    let child = &tree.nodes[first.children[0]];
    assert_eq!(
        child.kind,
        RayKind::Reflected,
        "the transmitted share is reflected"
    );
    assert!((child.weight - 0.9).abs() < 1e-6);
    // The mirror direction about the normal (0, 0.8, −0.6).
    let normal = Vec3::new(0.0, -0.8, 0.6);
    let mirrored = -Vec3::Z - 2.0 * (-Vec3::Z).dot(normal) * normal;
    assert!(
        close(child.dir, mirrored, 1e-4),
        "{} != {mirrored}",
        child.dir
    );
}

/// A floor, a ball between it and the light above, and the eye looking at the floor under the
/// ball from the side.
fn ball_over_floor(ball: Material) -> Scene {
    let eye = Vec3::new(0.0, 0.5, 6.0);
    let mut scene = Scene::new(settings(5, 0.01), camera(eye, Vec3::ZERO, 1.0));
    let floor = scene.add_material(Material::default());
    let ball = scene.add_material(ball);
    scene.add_object(plane(Vec3::ZERO, Vec3::Y), None, floor);
    scene.add_object(sphere(Vec3::new(0.0, 2.0, 0.0), 0.5), None, ball);
    scene.lights.push(Light::Point {
        position: Vec3::new(0.0, 6.0, 0.0),
        color: Color::ONE,
    });
    scene
}

#[test]
fn a_shadow_ray_is_blocked_by_the_ball_between_the_floor_and_the_light() {
    let scene = ball_over_floor(Material::default());
    let tree = centre_tree(&scene);
    let eye = &tree.nodes[0];
    assert_eq!(eye.hit.as_ref().unwrap().object, 0, "the floor");
    let shadow = &eye.shadows[0];
    assert!(shadow.blocked);
    assert!(close(shadow.dir, Vec3::Y, 1e-3), "{}", shadow.dir);
    assert!((shadow.distance - 6.0).abs() < 1e-3);
    assert_eq!(shadow.light_color, Color::ZERO);
    assert_eq!(shadow.blockers.len(), 1, "{}", tree.to_text());
    let blocker = &shadow.blockers[0];
    assert_eq!(blocker.object, 1);
    assert!(blocker.label.starts_with("sphere"), "{}", blocker.label);
    assert!(
        (blocker.t - 1.5).abs() < 1e-3,
        "the ball's underside: {}",
        blocker.t
    );
    assert_eq!(blocker.transmittance_after, [0.0; 3]);
}

#[test]
fn a_blocked_light_adds_nothing_but_shows_the_diffuse_term_it_would_add() {
    let scene = ball_over_floor(Material::default());
    let tree = centre_tree(&scene);
    let eye = &tree.nodes[0];
    let share = &eye.lights[0];
    assert_eq!((share.diffuse, share.specular), (Color::ZERO, Color::ZERO));
    // Lambert's term under a light straight above the floor, at the floor's point seen by the
    // centre pixel: diffuse × cos θ × colour, cos θ = 6 / distance.
    let m = Material::default();
    let point = eye.hit.as_ref().unwrap().point;
    let cos = (Vec3::new(0.0, 6.0, 0.0) - point).normalize().y;
    let expected = m.diffuse * cos * m.color;
    assert!(close(share.unshadowed_diffuse, expected, 1e-5), "{share:?}");
    assert!(
        tree.to_text().contains("(unshadowed: diffuse"),
        "{}",
        tree.to_text()
    );
}

#[test]
fn every_hits_terms_add_up_to_its_local_colour() {
    for name in ["default", "glass", "shadows", "mirrors", "textures"] {
        let path = format!("{}/assets/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let mut scene = raylab::formats::load_any(&path).unwrap();
        (scene.settings.width, scene.settings.height) = (24, 18);
        let bvh = Bvh::build(&scene.geometry);
        let tracer = Tracer::new(&scene, &bvh);
        for (x, y) in (0..24)
            .step_by(3)
            .flat_map(|x| (0..18).step_by(3).map(move |y| (x, y)))
        {
            let tree = trace_ray_tree(&tracer, x, y);
            for node in &tree.nodes {
                let Some(hit) = &node.hit else { continue };
                let lights: Color = node.lights.iter().map(|l| l.diffuse + l.specular).sum();
                let sum = hit.emission + hit.ambient + lights;
                assert!(
                    close(sum, node.local_color, 1e-5),
                    "{name} ({x}, {y}): {sum} against {}\n{}",
                    node.local_color,
                    tree.to_text()
                );
            }
        }
    }
}

#[test]
fn a_transparent_ball_tints_the_shadow_ray_instead_of_blocking_it() {
    let tint = Color::new(1.0, 0.5, 0.25);
    let scene = ball_over_floor(Material {
        color: tint,
        transparency: 0.8,
        ..Material::default()
    });
    let tree = centre_tree(&scene);
    let shadow = &tree.nodes[0].shadows[0];
    assert!(!shadow.blocked);
    assert_eq!(shadow.blockers.len(), 1);
    let passed = 0.8 * tint;
    assert!(
        close(shadow.light_color, passed, 1e-6),
        "{}",
        shadow.light_color
    );
    assert!(close(
        Vec3::from(shadow.blockers[0].transmittance_after),
        passed,
        1e-6
    ));
}

/// Two facing half mirrors (z = ±1), the eye between them looking slantwise at one.
fn facing_mirrors(max_depth: u32, min_weight: f32) -> Scene {
    let look_at = Vec3::new(0.1, 0.0, -1.0);
    let mut scene = Scene::new(
        settings(max_depth, min_weight),
        camera(Vec3::ZERO, look_at, 0.01),
    );
    let half_mirror = scene.add_material(Material {
        reflectivity: 0.5,
        ..Material::default()
    });
    scene.add_object(plane(Vec3::new(0.0, 0.0, -1.0), Vec3::Z), None, half_mirror);
    scene.add_object(plane(Vec3::new(0.0, 0.0, 1.0), -Vec3::Z), None, half_mirror);
    scene
}

#[test]
fn adaptive_depth_cuts_the_branch_whose_weight_falls_below_min_weight() {
    // Weights down the tree: 1, 0.5, 0.25, then 0.125 < 0.2 is not traced.
    let tree = centre_tree(&facing_mirrors(10, 0.2));
    let weights: Vec<f32> = tree.nodes.iter().map(|n| n.weight).collect();
    assert_eq!(weights, [1.0, 0.5, 0.25], "{}", tree.to_text());
    let last = tree.nodes.last().unwrap();
    assert!(last.children.is_empty());
    assert_eq!(last.cuts.len(), 1);
    let cut = last.cuts[0];
    assert_eq!(
        (cut.branch, cut.reason),
        (RayKind::Reflected, StopReason::MinWeight)
    );
    assert!((cut.weight - 0.125).abs() < 1e-6);
}

#[test]
fn the_depth_limit_stops_the_branch_at_max_depth() {
    let tree = centre_tree(&facing_mirrors(3, 0.0));
    assert_eq!(tree.nodes.len(), 3, "{}", tree.to_text());
    let last = &tree.nodes[2];
    assert_eq!(last.depth, 3);
    assert_eq!(last.stop, Some(StopReason::MaxDepth));
    assert!(tree.nodes[..2].iter().all(|n| n.stop.is_none()));
}

#[test]
fn switched_off_reflections_are_cut_and_said_so() {
    let mut scene = facing_mirrors(10, 0.0);
    scene.settings.reflections = false;
    let tree = centre_tree(&scene);
    assert_eq!(tree.nodes.len(), 1);
    assert_eq!(tree.nodes[0].cuts[0].reason, StopReason::Disabled);
}

#[test]
fn in_fog_each_ray_outside_objects_shows_its_transmittance_and_in_scattered_light() {
    let mut scene = glass_ball(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO);
    let density = 0.2;
    scene.atmosphere = Atmosphere {
        medium: Medium {
            density,
            albedo: 0.5,
            color: Color::ONE,
        },
        background_distance: None,
    };
    let tree = centre_tree(&scene);
    let fogs: Vec<_> = tree.nodes.iter().map(|n| n.fog).collect();
    let [Some(eye), None, Some(leaving)] = fogs[..] else {
        panic!("fog outside the ball only: {}", tree.to_text());
    };
    // From the eye at z = 5 to the ball's front at z = 1.
    assert!((eye.transmittance - (-density * 4.0).exp()).abs() < 1e-4);
    assert!(eye.in_scattered.min_element() > 0.0);
    // The ray leaving the glass at z = −1 runs through fog again, to the edge of the fog's
    // ball around the box from (−1, −1, −1) to (1, 5, 5) (the glass's, the light's and the
    // eye's): centre (0, 2, 2), radius √76 / 2, which it leaves √15 − 3 further on.
    let beyond = 15f32.sqrt() - 3.0;
    assert!((leaving.transmittance - (-density * beyond).exp()).abs() < 1e-4);
    assert!(leaving.in_scattered.min_element() > 0.0);
    assert!(tree.to_text().contains("fog: transmittance"));
    // The fog's share is in the contributions, which still add up to the pixel.
    assert!(close(tree.sum_of_contributions(), tree.color, 1e-5));
    // The glass ray's colour reaches the pixel through the eye ray's fog.
    let inside = &tree.nodes[1];
    assert!(close(
        inside.factor,
        eye.transmittance * 0.9 * Color::ONE,
        1e-5
    ));
}

#[test]
fn a_hits_emission_is_shown_and_is_part_of_its_local_colour() {
    let mut scene = Scene::new(settings(1, 0.0), camera(Vec3::ZERO, -Vec3::Z, 1.0));
    let glow = Color::new(0.5, 0.25, 0.0);
    let lamp = scene.add_material(Material {
        emission: glow,
        ambient: 0.0,
        ..Material::default()
    });
    scene.add_object(plane(Vec3::new(0.0, 0.0, -5.0), Vec3::Z), None, lamp);
    let tree = centre_tree(&scene);
    let eye = &tree.nodes[0];
    assert_eq!(eye.hit.as_ref().map(|hit| hit.emission), Some(glow));
    assert_eq!(eye.local_color, glow, "no light: the emission alone");
    let text = tree.to_text();
    assert!(text.contains("emission (0.5000, 0.2500, 0.0000)"), "{text}");
}

#[test]
fn a_wall_alone_in_fog_shows_the_transmittance_of_its_distance() {
    // Only an infinite plane 10 units ahead: nothing bounded, no light.
    let mut scene = Scene::new(settings(1, 0.0), camera(Vec3::ZERO, -Vec3::Z, 1.0));
    let wall = scene.add_material(Material::default());
    scene.add_object(plane(Vec3::new(0.0, 0.0, -10.0), Vec3::Z), None, wall);
    scene.atmosphere = Atmosphere {
        medium: Medium {
            density: 0.1,
            albedo: 0.0,
            color: Color::ONE,
        },
        background_distance: None,
    };
    let tree = centre_tree(&scene);
    let fog = tree.nodes[0].fog.expect("the eye ray runs through fog");
    assert!(
        (fog.transmittance - (-1f32).exp()).abs() < 1e-4,
        "{}",
        tree.to_text()
    );
    assert!(
        tree.to_text().contains("fog: transmittance 0.3679"),
        "{}",
        tree.to_text()
    );
}

/// The levels raylab would write for the linear colour `c`.
fn levels(c: Color) -> [u8; 3] {
    c.to_array().map(raylab::color::srgb8)
}

#[test]
fn a_brighter_pixel_where_raylabs_shadow_ray_is_blocked_is_put_down_to_that_shadow_ray() {
    let scene = ball_over_floor(Material::default());
    let tree = centre_tree(&scene);
    let share = &tree.nodes[0].lights[0];
    let yours = levels(tree.color + share.unshadowed_diffuse);
    let e = explain_pixel(&tree, yours, levels(tree.color));
    let removed = share.unshadowed_diffuse.element_sum() / 3.0;
    let expected = format!(
        "raylab's shadow ray to light 0 is blocked by sphere #1, and the diffuse term it \
         removes is {removed:.2}"
    );
    let sentence = e.accounted_for.unwrap();
    assert!(
        sentence.starts_with("your pixel is brighter by"),
        "{sentence}"
    );
    assert!(sentence.ends_with(&expected), "{sentence}");
    assert!(e.first_hit.starts_with("plane #0"), "{}", e.first_hit);
}

#[test]
fn a_darker_pixel_on_a_mirror_is_put_down_to_the_reflected_ray() {
    let scene = mirror_facing_a_wall();
    let tree = centre_tree(&scene);
    let eye = &tree.nodes[0];
    let e = explain_pixel(&tree, levels(eye.contribution), levels(tree.color));
    let sentence = e.accounted_for.unwrap();
    assert!(
        sentence.starts_with("your pixel is darker by"),
        "{sentence}"
    );
    assert!(
        sentence.contains("raylab's reflected ray, which sees plane #1, adds"),
        "{sentence}"
    );
    assert!(
        e.terms.iter().any(|t| t.what == "reflected ray"),
        "{:?}",
        e.terms
    );
}

#[test]
fn an_equal_pixel_needs_no_explanation() {
    let tree = centre_tree(&ball_over_floor(Material::default()));
    let e = explain_pixel(&tree, levels(tree.color), levels(tree.color));
    assert_eq!(e.accounted_for, None);
    assert_eq!(e.brighter_by, 0.0);
}
