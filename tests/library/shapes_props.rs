//! Property tests of the analytic shapes over random rays: every reported hit lies on the surface
//! and inside the ray's `t` range, with a unit outward normal (and enough of the rays hit for
//! that to be tested); rays aimed into a shape from outside always hit it; concave polygons agree
//! with independent references (a triangulation, and a star-shaped test for a gear).

use std::cell::Cell;
use std::f32::consts::TAU;

use glam::{DVec3, Quat, Vec2, Vec3};
use proptest::prelude::*;
use raylab::ray::Ray;
use raylab::shapes::{
    Cuboid, Ellipsoid, Paraboloid, Plane, Polygon, Shape, Sphere, TaperedCylinder, Torus, Triangle,
};

/// How far off its surface a reported hit point may lie, relative to the size of the numbers
/// involved.
const SURFACE_TOLERANCE: f32 = 2e-4;

/// A closed or open solid, with its parameters kept so that the tests can check hits against
/// the surface's own equation rather than the code under test.
#[derive(Clone, Debug)]
enum Model {
    Sphere {
        center: Vec3,
        radius: f32,
    },
    Ellipsoid {
        center: Vec3,
        radii: Vec3,
    },
    Cuboid {
        min: Vec3,
        max: Vec3,
    },
    TaperedCylinder {
        base: Vec3,
        top: Vec3,
        base_radius: f32,
        top_radius: f32,
        capped: bool,
    },
    Paraboloid {
        vertex: Vec3,
        radius: f32,
        height: f32,
        capped: bool,
    },
}

impl Model {
    fn shape(&self) -> Shape {
        match *self {
            Model::Sphere { center, radius } => Shape::Sphere(Sphere { center, radius }),
            Model::Ellipsoid { center, radii } => {
                Shape::Ellipsoid(Ellipsoid::new(center, radii).unwrap())
            }
            Model::Cuboid { min, max } => Shape::Cuboid(Cuboid::new(min, max).unwrap()),
            Model::TaperedCylinder {
                base,
                top,
                base_radius,
                top_radius,
                capped,
            } => Shape::TaperedCylinder(
                TaperedCylinder::new(base, top, base_radius, top_radius, capped).unwrap(),
            ),
            Model::Paraboloid {
                vertex,
                radius,
                height,
                capped,
            } => Shape::Paraboloid(Paraboloid::new(vertex, radius, height, capped).unwrap()),
        }
    }

    fn is_closed(&self) -> bool {
        match *self {
            Model::Sphere { .. } | Model::Ellipsoid { .. } | Model::Cuboid { .. } => true,
            Model::TaperedCylinder { capped, .. } | Model::Paraboloid { capped, .. } => capped,
        }
    }

    /// About how far `p` lies from part `part` of the surface (0 on it).
    fn off_surface(&self, p: Vec3, part: u32) -> f32 {
        match *self {
            Model::Sphere { center, radius } => ((p - center).length() - radius).abs(),
            Model::Ellipsoid { center, radii } => {
                (((p - center) / radii).length() - 1.0).abs() * radii.max_element()
            }
            Model::Cuboid { min, max } => {
                let axis = (part / 2) as usize;
                let face = if part.is_multiple_of(2) {
                    min[axis]
                } else {
                    max[axis]
                };
                let outside = (min - p).max(p - max).max(Vec3::ZERO).length();
                (p[axis] - face).abs() + outside
            }
            Model::TaperedCylinder {
                base,
                top,
                base_radius,
                top_radius,
                ..
            } => {
                let height = (top - base).length();
                let axis = (top - base) / height;
                let z = (p - base).dot(axis);
                let radial = ((p - base) - axis * z).length();
                match part {
                    0 => {
                        let radius = base_radius + (top_radius - base_radius) * z / height;
                        (radial - radius).abs() + (-z).max(z - height).max(0.0)
                    }
                    1 => z.abs() + (radial - base_radius).max(0.0),
                    _ => (z - height).abs() + (radial - top_radius).max(0.0),
                }
            }
            Model::Paraboloid {
                vertex,
                radius,
                height,
                ..
            } => {
                let q = p - vertex;
                let rho2 = q.x * q.x + q.z * q.z;
                let k = height / (radius * radius);
                match part {
                    0 => {
                        let slope = (1.0 + 4.0 * k * k * rho2).sqrt();
                        (k * rho2 - q.y).abs() / slope + (-q.y).max(q.y - height).max(0.0)
                    }
                    _ => (q.y - height).abs() + (rho2.sqrt() - radius).max(0.0),
                }
            }
        }
    }

    /// The direction of the surface's outward normal at `p` on part `part`: the gradient of
    /// the part's implicit function, worked out here independently of the shapes' code.
    fn gradient(&self, p: Vec3, part: u32) -> Vec3 {
        match *self {
            Model::Sphere { center, .. } => p - center,
            Model::Ellipsoid { center, radii } => (p - center) / (radii * radii),
            Model::Cuboid { .. } => {
                let mut n = Vec3::ZERO;
                n[(part / 2) as usize] = if part.is_multiple_of(2) { -1.0 } else { 1.0 };
                n
            }
            Model::TaperedCylinder {
                base,
                top,
                base_radius,
                top_radius,
                ..
            } => {
                let axis = (top - base).normalize();
                match part {
                    // |p − axis point| − r(z): the radial direction, tilted by the taper.
                    0 => {
                        let rel = p - base;
                        let radial = (rel - axis * rel.dot(axis)).normalize_or_zero();
                        let slope = (top_radius - base_radius) / (top - base).length();
                        radial - axis * slope
                    }
                    1 => -axis,
                    _ => axis,
                }
            }
            Model::Paraboloid {
                vertex,
                radius,
                height,
                ..
            } => match part {
                0 => {
                    let q = p - vertex;
                    let k = height / (radius * radius);
                    Vec3::new(2.0 * k * q.x, -1.0, 2.0 * k * q.z)
                }
                _ => Vec3::Y,
            },
        }
    }

    /// A point well inside the solid (or inside its convex hull, for open shapes). Each shape is
    /// convex, so an outward normal at `p` points away from it.
    fn centre(&self) -> Vec3 {
        self.inside_point(Vec3::splat(0.5))
    }

    /// A point strictly inside, picked by `s` in `[0, 1]³`.
    fn inside_point(&self, s: Vec3) -> Vec3 {
        let s = Vec3::splat(0.05) + s * 0.9;
        match *self {
            Model::Sphere { center, radius } => center + ball_point(s) * radius * 0.9,
            Model::Ellipsoid { center, radii } => center + ball_point(s) * radii * 0.9,
            Model::Cuboid { min, max } => min + (max - min) * s,
            Model::TaperedCylinder {
                base,
                top,
                base_radius,
                top_radius,
                ..
            } => cylinder_point(
                (base, top),
                (base_radius, top_radius),
                (s.x, s.y, 0.9 * s.z),
            ),
            Model::Paraboloid {
                vertex,
                radius,
                height,
                ..
            } => paraboloid_point(vertex, (radius, height), (s.x, s.y, 0.9 * s.z)),
        }
    }

    /// A point on the curved part of the surface (or a face of a box), picked by `s` in
    /// `[0, 1]³`, and that part's number. It keeps clear of rims and edges.
    fn surface_point(&self, s: Vec3) -> (Vec3, u32) {
        let s = Vec3::splat(0.02) + s * 0.96;
        match *self {
            Model::Sphere { center, radius } => (center + sphere_point(s) * radius, 0),
            Model::Ellipsoid { center, radii } => (center + sphere_point(s) * radii, 0),
            Model::Cuboid { min, max } => {
                let part = ((s.z * 6.0) as u32).min(5);
                let axis = (part / 2) as usize;
                let mut fraction = Vec3::ZERO;
                fraction[(axis + 1) % 3] = s.x;
                fraction[(axis + 2) % 3] = s.y;
                fraction[axis] = (part % 2) as f32;
                (min + (max - min) * fraction, part)
            }
            Model::TaperedCylinder {
                base,
                top,
                base_radius,
                top_radius,
                ..
            } => {
                let at = (s.x, s.y, 1.0);
                (
                    cylinder_point((base, top), (base_radius, top_radius), at),
                    0,
                )
            }
            Model::Paraboloid {
                vertex,
                radius,
                height,
                ..
            } => (
                paraboloid_point(vertex, (radius, height), (s.x, s.y, 1.0)),
                0,
            ),
        }
    }
}

/// The point of a tapered cylinder at `height` (a fraction of the axis), `turn` (a fraction of a
/// turn around it) and `radial` (a fraction of the radius there).
fn cylinder_point(
    (base, top): (Vec3, Vec3),
    (base_radius, top_radius): (f32, f32),
    (height, turn, radial): (f32, f32, f32),
) -> Vec3 {
    let (e1, e2) = (top - base).normalize().any_orthonormal_pair();
    let radius = base_radius + (top_radius - base_radius) * height;
    let (sin, cos) = (turn * TAU).sin_cos();
    base + (top - base) * height + (e1 * cos + e2 * sin) * radius * radial
}

/// The point of a paraboloid at `height` (a fraction of its height), `turn` and `radial`.
fn paraboloid_point(
    vertex: Vec3,
    (top_radius, full_height): (f32, f32),
    (height, turn, radial): (f32, f32, f32),
) -> Vec3 {
    let rho = top_radius * height.sqrt() * radial;
    let (sin, cos) = (turn * TAU).sin_cos();
    vertex + Vec3::new(rho * cos, full_height * height, rho * sin)
}

/// A point of the unit sphere, picked by `s` in `[0, 1]²`.
fn sphere_point(s: Vec3) -> Vec3 {
    let z = 2.0 * s.x - 1.0;
    let ring = (1.0 - z * z).max(0.0).sqrt();
    let angle = s.y * TAU;
    Vec3::new(ring * angle.cos(), ring * angle.sin(), z)
}

/// A point of the unit ball, picked by `s` in `[0, 1]³`.
fn ball_point(s: Vec3) -> Vec3 {
    sphere_point(s) * s.z
}

/// Numbers in `[low, high]`, drawn as integers: proptest's own `f32` range sampler trips a debug
/// assertion on rare seeds.
fn float_in(low: f32, high: f32) -> impl Strategy<Value = f32> {
    const STEPS: u32 = 1 << 24;
    (0..=STEPS).prop_map(move |i| low + (high - low) * (i as f32 / STEPS as f32))
}

fn vec3_in(range: f32) -> impl Strategy<Value = Vec3> {
    (
        float_in(-range, range),
        float_in(-range, range),
        float_in(-range, range),
    )
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn unit_cube() -> impl Strategy<Value = Vec3> {
    (float_in(0.0, 1.0), float_in(0.0, 1.0), float_in(0.0, 1.0))
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn unit_vector() -> impl Strategy<Value = Vec3> {
    unit_cube().prop_map(sphere_point)
}

fn rotation() -> impl Strategy<Value = Quat> {
    (unit_vector(), float_in(0.0, TAU)).prop_map(|(axis, angle)| Quat::from_axis_angle(axis, angle))
}

/// Scale factors for ray directions, which need not be unit length.
fn dir_scale() -> impl Strategy<Value = f32> {
    prop_oneof![Just(1.0f32), float_in(0.05, 20.0)]
}

fn t_range() -> impl Strategy<Value = (f32, f32)> {
    let t_min = prop_oneof![Just(0.0f32), Just(1e-4f32), float_in(0.0, 3.0)];
    let span = prop_oneof![Just(f32::INFINITY), float_in(0.1, 30.0)];
    (t_min, span).prop_map(|(t_min, span)| (t_min, t_min + span))
}

fn radius() -> impl Strategy<Value = f32> {
    float_in(0.2, 3.0)
}

fn any_model() -> impl Strategy<Value = Model> {
    prop_oneof![
        (vec3_in(3.0), radius()).prop_map(|(center, radius)| Model::Sphere { center, radius }),
        (vec3_in(3.0), radius(), radius(), radius()).prop_map(|(center, x, y, z)| {
            Model::Ellipsoid {
                center,
                radii: Vec3::new(x, y, z),
            }
        }),
        (vec3_in(3.0), radius(), radius(), radius()).prop_map(|(min, x, y, z)| Model::Cuboid {
            min,
            max: min + Vec3::new(x, y, z),
        }),
        (
            vec3_in(3.0),
            unit_vector(),
            float_in(0.3, 4.0),
            prop_oneof![Just(0.0f32), radius()],
            radius(),
            any::<bool>(),
            any::<bool>(),
        )
            .prop_map(|(base, axis, length, r0, r1, capped, swap)| {
                let (base_radius, top_radius) = if swap { (r1, r0) } else { (r0, r1) };
                Model::TaperedCylinder {
                    base,
                    top: base + axis * length,
                    base_radius,
                    top_radius,
                    capped,
                }
            }),
        (vec3_in(3.0), radius(), radius(), any::<bool>()).prop_map(
            |(vertex, radius, height, capped)| Model::Paraboloid {
                vertex,
                radius,
                height,
                capped,
            }
        ),
    ]
}

/// A ray from somewhere around the scene towards somewhere near `target`, so that many rays hit.
fn ray_towards(target: Vec3, origin: Vec3, jitter: Vec3, scale: f32) -> Ray {
    let aim = target + jitter;
    let dir = (aim - origin).normalize_or(Vec3::X) * scale;
    Ray::new(origin, dir)
}

#[test]
fn hits_lie_on_the_surface_inside_the_t_range_with_unit_outward_normals() {
    let hits = &HitCount::default();
    proptest!(|(
        model in any_model(),
        origin in vec3_in(8.0),
        jitter in vec3_in(3.0),
        scale in dir_scale(),
        (t_min, t_max) in t_range(),
    )| {
        let shape = model.shape();
        prop_assert_eq!(shape.is_closed(), model.is_closed());
        let ray = ray_towards(model.centre(), origin, jitter, scale);
        if let Some(hit) = hits.record(shape.intersect(&ray, t_min, t_max)) {
            prop_assert!(hit.t > t_min && hit.t < t_max, "{hit:?} outside ({t_min}, {t_max})");
            let p = ray.at(hit.t);
            let tolerance = SURFACE_TOLERANCE * (1.0 + origin.abs().max_element());
            let off = model.off_surface(p, hit.part);
            prop_assert!(off < tolerance, "{p} is {off} off part {}", hit.part);
            let bounds = shape.bounds().unwrap();
            let slack = Vec3::splat(tolerance);
            prop_assert!(p.cmpge(bounds.min - slack).all() && p.cmple(bounds.max + slack).all());
            let surface = shape.surface(p, hit.part);
            // The normal alone (shading without textures) is the surface's, bit for bit.
            prop_assert_eq!(shape.normal(p, hit.part).to_array(), surface.normal.to_array());
            let n = surface.normal.normalize();
            prop_assert!((n.length() - 1.0).abs() < 1e-5, "normal {}", surface.normal);
            prop_assert!(n.dot(p - model.centre()) > 0.0, "normal {n} at {p} points in");
            let expected = model.gradient(p, hit.part).normalize();
            prop_assert!(n.dot(expected) > 0.999, "normal {n} at {p}, expected {expected}");
            let uv = surface.uv;
            prop_assert!(uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all(), "uv {uv}");
        }
    });
    hits.assert_at_least(0.05);
}

#[test]
fn sphere_hits_lie_on_it_with_unit_outward_normals() {
    let hits = &HitCount::default();
    proptest!(|(
        center in vec3_in(3.0),
        radius in radius(),
        origin in vec3_in(8.0),
        jitter in vec3_in(3.0),
        scale in dir_scale(),
        (t_min, t_max) in t_range(),
    )| {
        let sphere = Sphere { center, radius };
        let ray = ray_towards(center, origin, jitter, scale);
        if let Some(hit) = hits.record(sphere.intersect(&ray, t_min, t_max)) {
            prop_assert!(hit.t > t_min && hit.t < t_max);
            let p = ray.at(hit.t);
            let tolerance = SURFACE_TOLERANCE * (1.0 + origin.abs().max_element());
            prop_assert!(((p - center).length() - radius).abs() < tolerance, "{p}");
            let n = sphere.surface(p, hit.part).normal;
            prop_assert!((n.length() - 1.0).abs() < 1e-3, "{n}");
            prop_assert!(n.dot(p - center) > 0.0);
        }
    });
    hits.assert_at_least(0.1);
}

#[test]
fn plane_hits_lie_on_it_with_its_unit_normal() {
    let hits = &HitCount::default();
    proptest!(|(
        point in vec3_in(3.0),
        normal in unit_vector(),
        origin in vec3_in(8.0),
        dir in unit_vector(),
        scale in dir_scale(),
        (t_min, t_max) in t_range(),
    )| {
        let plane = Plane { point, normal };
        let ray = Ray::new(origin, dir * scale);
        if let Some(hit) = hits.record(plane.intersect(&ray, t_min, t_max)) {
            prop_assert!(hit.t > t_min && hit.t < t_max);
            let p = ray.at(hit.t);
            let tolerance = SURFACE_TOLERANCE * (1.0 + p.abs().max_element());
            prop_assert!((p - point).dot(normal).abs() < tolerance, "{p}");
            let n = plane.surface(p, hit.part).normal;
            prop_assert!((n.length() - 1.0).abs() < 1e-5 && n.dot(normal) > 0.9999);
        }
    });
    hits.assert_at_least(0.1);
}

/// How many of a property's cases hit. A property checked only on the hits must also see
/// enough of them: an intersector that never hits would pass it.
#[derive(Default)]
struct HitCount {
    cases: Cell<u32>,
    hits: Cell<u32>,
}

impl HitCount {
    /// Counts one case and whether it hit; gives the hit back.
    fn record<T>(&self, hit: Option<T>) -> Option<T> {
        self.cases.set(self.cases.get() + 1);
        self.hits.set(self.hits.get() + u32::from(hit.is_some()));
        hit
    }

    /// Fails unless at least `share` of the cases hit. The shares asserted are far below those
    /// seen, so that proptest's 256 random cases are always enough.
    fn assert_at_least(&self, share: f64) {
        let (hits, cases) = (self.hits.get(), self.cases.get());
        assert!(
            f64::from(hits) >= share * f64::from(cases),
            "only {hits} of {cases} rays hit; expected at least {:.0}%",
            share * 100.0
        );
    }
}

proptest! {
    #[test]
    fn rays_aimed_inside_from_outside_always_hit(
        model in any_model().prop_filter("closed", Model::is_closed),
        pick in unit_cube(),
        from in unit_vector(),
        scale in dir_scale(),
    ) {
        let shape = model.shape();
        let target = model.inside_point(pick);
        let bounds = shape.bounds().unwrap();
        let origin = target + from * ((bounds.max - bounds.min).length() + 1.0);
        let ray = Ray::new(origin, (target - origin) * scale);
        let hit = shape.intersect(&ray, 0.0, f32::INFINITY);
        prop_assert!(hit.is_some(), "{ray:?} aimed at {target} missed");
        prop_assert!(hit.unwrap().t < 1.0 / scale, "hit after the target");
    }

    #[test]
    fn rays_aimed_at_the_surface_from_outside_hit_it_no_later(
        model in any_model(),
        pick in unit_cube(),
        from in unit_vector(),
        scale in dir_scale(),
    ) {
        let shape = model.shape();
        let (target, part) = model.surface_point(pick);
        let normal = shape.surface(target, part).normal.normalize();
        // Tilt grazing directions towards the normal's side: |from · normal| ≥ 1/6.
        let from = (from + normal * 0.2f32.copysign(from.dot(normal))).normalize();
        let bounds = shape.bounds().unwrap();
        let origin = target + from * ((bounds.max - bounds.min).length() + 1.0);
        let ray = Ray::new(origin, (target - origin) * scale);
        let hit = shape.intersect(&ray, 0.0, f32::INFINITY);
        prop_assert!(hit.is_some(), "{ray:?} aimed at {target} missed");
        prop_assert!(hit.unwrap().t <= (1.0 + 1e-4) / scale, "hit after the target");
    }

    #[test]
    fn regular_polygon_hits_lie_in_its_plane_and_rays_aimed_inside_hit(
        sides in 3usize..16,
        radius in radius(),
        turn in rotation(),
        shift in vec3_in(3.0),
        pick in unit_cube(),
        offset in offset_from_plane(),
        scale in dir_scale(),
    ) {
        let place = |q: Vec2| turn * q.extend(0.0) + shift;
        let vertices = (0..sides)
            .map(|i| place(Vec2::from_angle(i as f32 * TAU / sides as f32) * radius))
            .collect();
        let polygon = Polygon::new(vertices).unwrap();
        let normal = turn * Vec3::Z;
        // A point inside the inscribed circle is inside the polygon.
        let inscribed = radius * (std::f32::consts::PI / sides as f32).cos();
        let target = Vec2::from_angle(pick.x * TAU) * inscribed * 0.95 * pick.y;
        let origin = place(target) + turn * offset;
        let ray = Ray::new(origin, (place(target) - origin) * scale);
        let hit = polygon.intersect(&ray, 0.0, f32::INFINITY);
        prop_assert!(hit.is_some(), "{ray:?} missed");
        let hit = hit.unwrap();
        prop_assert!((hit.t * scale - 1.0).abs() < 1e-4, "t = {}", hit.t);
        let p = ray.at(hit.t);
        prop_assert!((p - shift).dot(normal).abs() < SURFACE_TOLERANCE * (1.0 + shift.length()));
        let surface = polygon.surface(p, hit.part);
        prop_assert!((surface.normal.length() - 1.0).abs() < 1e-5);
        prop_assert!(surface.normal.dot(normal) > 0.9999, "{} vs {normal}", surface.normal);
        prop_assert!(surface.uv.cmpge(Vec2::ZERO).all() && surface.uv.cmple(Vec2::ONE).all());
    }

    #[test]
    fn concave_l_shape_agrees_with_its_triangulation(
        turn in rotation(),
        shift in vec3_in(3.0),
        target in (float_in(-0.5, 2.5), float_in(-0.5, 2.5)).prop_map(|(x, y)| Vec2::new(x, y)),
        offset in offset_from_plane(),
        scale in dir_scale(),
    ) {
        let place = |q: Vec2| turn * q.extend(0.0) + shift;
        prop_assume!(L_SEGMENTS.iter().all(|&(a, b)| {
            segment_distance(target, L_SHAPE[a], L_SHAPE[b]) > 1e-3
        }));
        let polygon = Polygon::new(L_SHAPE.iter().map(|&q| place(q)).collect()).unwrap();
        let triangles = L_TRIANGLES.map(|corners| Triangle::new(corners.map(|i| place(L_SHAPE[i])), 0));
        let origin = place(target) + turn * offset;
        let ray = Ray::new(origin, (place(target) - origin) * scale);
        let polygon_hit = polygon.intersect(&ray, 0.0, f32::INFINITY);
        let triangle_hit = triangles.iter().find_map(|t| t.intersect(&ray, 0.0, f32::INFINITY));
        prop_assert_eq!(polygon_hit.is_some(), triangle_hit.is_some(), "at {}", target);
        if let (Some(a), Some(b)) = (polygon_hit, triangle_hit) {
            prop_assert!((a.t - b.t).abs() <= 1e-4 * a.t, "{} vs {}", a.t, b.t);
        }
    }

    #[test]
    fn gear_agrees_with_a_star_shaped_test(
        turn in rotation(),
        shift in vec3_in(3.0),
        target in (float_in(-1.1, 1.1), float_in(-1.1, 1.1)).prop_map(|(x, y)| Vec2::new(x, y)),
        offset in offset_from_plane(),
        scale in dir_scale(),
    ) {
        let gear = gear_outline();
        let reference = star_shaped_inside(&gear, target);
        prop_assume!(reference.is_some()); // too close to an edge to call
        let place = |q: Vec2| turn * q.extend(0.0) + shift;
        let polygon = Polygon::new(gear.iter().map(|&q| place(q)).collect()).unwrap();
        let origin = place(target) + turn * offset;
        let ray = Ray::new(origin, (place(target) - origin) * scale);
        let hit = polygon.intersect(&ray, 0.0, f32::INFINITY);
        prop_assert_eq!(hit.is_some(), reference.unwrap(), "at {}", target);
    }
}

/// Where a ray starts, relative to the point it aims at in a polygon's plane (the local `xy`
/// plane): at least 0.5 off the plane, so that it does not graze it.
fn offset_from_plane() -> impl Strategy<Value = Vec3> {
    (
        float_in(-5.0, 5.0),
        float_in(-5.0, 5.0),
        float_in(0.5, 5.0),
        any::<bool>(),
    )
        .prop_map(|(x, y, z, below)| Vec3::new(x, y, if below { -z } else { z }))
}

/// An L: the square `[0, 2]²` without its top-right quarter, counter-clockwise.
const L_SHAPE: [Vec2; 6] = [
    Vec2::new(0.0, 0.0),
    Vec2::new(2.0, 0.0),
    Vec2::new(2.0, 1.0),
    Vec2::new(1.0, 1.0),
    Vec2::new(1.0, 2.0),
    Vec2::new(0.0, 2.0),
];

/// The L cut into triangles by hand, fanning out from its first corner.
const L_TRIANGLES: [[usize; 3]; 4] = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]];

/// Every edge of the triangulation: the L's outline and the three diagonals.
const L_SEGMENTS: [(usize, usize); 9] = [
    (0, 1),
    (1, 2),
    (2, 3),
    (3, 4),
    (4, 5),
    (5, 0),
    (0, 2),
    (0, 3),
    (0, 4),
];

fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let along = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    (p - (a + ab * along)).length()
}

/// A gear's outline, counter-clockwise: 36 teeth of four vertices each, 0.8 at the roots and 1
/// at the tips.
fn gear_outline() -> Vec<Vec2> {
    (0..144)
        .map(|i| {
            let radius = if i % 4 == 1 || i % 4 == 2 { 1.0 } else { 0.8 };
            Vec2::from_angle(i as f32 * TAU / 144.0) * radius
        })
        .collect()
}

/// Whether `q` is inside a polygon that is star-shaped about the origin with vertices in order of
/// angle: inside the triangle formed by the origin and the edge crossing `q`'s direction.
/// `None` when `q` lies too close to an edge to tell.
fn star_shaped_inside(outline: &[Vec2], q: Vec2) -> Option<bool> {
    let n = outline.len();
    let step = TAU / n as f32;
    let angle = q.y.atan2(q.x).rem_euclid(TAU);
    let sector = ((angle / step) as usize).min(n - 1);
    let edge = |i: usize| (outline[i % n], outline[(i + 1) % n]);
    let near_edge = [sector + n - 1, sector, sector + 1]
        .into_iter()
        .any(|i| segment_distance(q, edge(i).0, edge(i).1) < 1e-3);
    if near_edge {
        return None;
    }
    let (a, b) = edge(sector);
    Some((b - a).perp_dot(q - a) > 0.0)
}

/// Finite numbers of any size from 1e-30 to 1e30, either sign, and zero.
fn wild_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(0.0f32),
        8 => (any::<bool>(), float_in(1.0, 10.0), -30i32..30)
            .prop_map(|(negative, mantissa, exponent)| {
                let x = mantissa * 10f32.powi(exponent);
                if negative { -x } else { x }
            }),
    ]
}

fn wild_vec3() -> impl Strategy<Value = Vec3> {
    (wild_f32(), wild_f32(), wild_f32()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// Any shape the constructors accept from wild parameters (and the errors they give).
fn wild_shape() -> impl Strategy<Value = Result<Shape, String>> {
    prop_oneof![
        (wild_vec3(), wild_vec3())
            .prop_map(|(center, radii)| Ellipsoid::new(center, radii).map(Shape::Ellipsoid)),
        (wild_vec3(), wild_vec3()).prop_map(|(min, max)| Cuboid::new(min, max).map(Shape::Cuboid)),
        (
            wild_vec3(),
            wild_vec3(),
            wild_f32(),
            wild_f32(),
            any::<bool>()
        )
            .prop_map(|(base, top, r0, r1, capped)| {
                TaperedCylinder::new(base, top, r0, r1, capped).map(Shape::TaperedCylinder)
            }),
        (wild_vec3(), wild_f32(), wild_f32(), any::<bool>()).prop_map(
            |(vertex, radius, height, capped)| {
                Paraboloid::new(vertex, radius, height, capped).map(Shape::Paraboloid)
            }
        ),
        (wild_vec3(), wild_f32(), wild_f32())
            .prop_map(|(center, major, minor)| Torus::new(center, major, minor).map(Shape::Torus)),
        prop::collection::vec(wild_vec3(), 0..7).prop_map(|v| Polygon::new(v).map(Shape::Polygon)),
        // Planar polygons, so that some get past the constructor.
        (
            prop::collection::vec((wild_f32(), wild_f32()), 3..7),
            wild_f32()
        )
            .prop_map(|(points, z)| {
                let vertices = points.iter().map(|&(x, y)| Vec3::new(x, y, z)).collect();
                Polygon::new(vertices).map(Shape::Polygon)
            }),
    ]
}

#[test]
fn wild_finite_input_never_panics_and_hits_stay_in_range() {
    // Most wild shapes are refused, and only the rest count: more cases than usual.
    let hits = &HitCount::default();
    proptest!(ProptestConfig::with_cases(2048), |(
        shape in wild_shape(),
        origin in wild_vec3(),
        dir in wild_vec3(),
        aimed in any::<bool>(),
        t_min in prop_oneof![Just(0.0f32), wild_f32().prop_map(f32::abs)],
        t_max in prop_oneof![Just(f32::INFINITY), wild_f32().prop_map(f32::abs)],
        part in any::<u32>(),
    )| {
        match shape {
            Err(message) => prop_assert!(!message.is_empty()),
            Ok(shape) => {
                let bounds = shape.bounds().unwrap();
                prop_assert!(!bounds.is_empty());
                // Half the rays aim at the middle of the shape's box, so that some hit.
                let dir = if aimed { bounds.center() - origin } else { dir };
                let ray = Ray::new(origin, dir);
                if let Some(hit) = hits.record(shape.intersect(&ray, t_min, t_max)) {
                    prop_assert!(hit.t > t_min && hit.t < t_max, "{hit:?}");
                    shape.surface(ray.at(hit.t), hit.part);
                }
                shape.surface(origin, part);
            }
        }
    });
    hits.assert_at_least(0.03);
}

proptest! {
    #[test]
    fn rays_starting_on_the_surface_leave_it_or_cross_to_the_far_side(
        model in any_model(),
        pick in unit_cube(),
        from in unit_vector(),
        scale in dir_scale(),
    ) {
        let shape = model.shape();
        let (start, part) = model.surface_point(pick);
        let normal = model.gradient(start, part).normalize();
        let outward = (from + normal * 0.2f32.copysign(from.dot(normal))).normalize();
        let outward = outward * outward.dot(normal).signum();
        // Every shape is convex, so a ray leaving it does not come back.
        let leaving = Ray::new(start, outward * scale);
        let again = shape.intersect(&leaving, 1e-4, f32::INFINITY);
        prop_assert!(again.is_none(), "{leaving:?} hit again: {again:?}");
        if model.is_closed() {
            let entering = Ray::new(start, -outward * scale);
            let far_side = shape.intersect(&entering, 1e-4, f32::INFINITY);
            prop_assert!(far_side.is_some(), "{entering:?} did not come out");
            let hit = far_side.unwrap();
            let p = entering.at(hit.t);
            let tolerance = SURFACE_TOLERANCE * (1.0 + start.abs().max_element());
            prop_assert!(model.off_surface(p, hit.part) < tolerance, "{p}");
            prop_assert!(shape.surface(p, hit.part).normal.normalize().is_finite());
        }
    }
}

// ---- the torus: not convex, so checked against a numerical root search ----------------------

/// A torus at one of the scales from 1e-3 to 1e3, with a random ray aimed at a point of its box.
#[derive(Clone, Debug)]
struct TorusCase {
    torus: Torus,
    ray: Ray,
}

fn torus_case() -> impl Strategy<Value = TorusCase> {
    (
        prop_oneof![Just(1e-3f32), Just(1.0f32), Just(1e3f32)],
        vec3_in(3.0),
        float_in(0.5, 3.0),
        float_in(0.05, 0.95),
        vec3_in(8.0),
        unit_cube(),
        dir_scale(),
    )
        .prop_map(|(scale, center, major, tube, origin, aim, dir_scale)| {
            let torus = Torus::new(center * scale, major * scale, tube * major * scale).unwrap();
            let bounds = torus.bounds();
            let target = bounds.min + (bounds.max - bounds.min) * aim;
            let origin = (center + origin) * scale;
            let ray = Ray::new(origin, (target - origin).normalize_or(Vec3::X) * dir_scale);
            TorusCase { torus, ray }
        })
}

/// How far inside (negative) or outside the tube `p` is, squared: `(ρ − R)² + y² − r²`, from the
/// tube's own definition rather than the quartic the shape solves.
fn tube_function(torus: &Torus, p: DVec3) -> f64 {
    let q = p - torus.center.as_dvec3();
    let rho = q.x.hypot(q.z);
    (rho - f64::from(torus.major_radius)).powi(2) + q.y * q.y
        - f64::from(torus.minor_radius).powi(2)
}

/// Every `t` where the ray's line crosses the tube within the torus's bounding sphere, found by
/// sampling the tube function at `samples` points and bisecting each change of sign; and the
/// sample spacing.
fn sampled_crossings(torus: &Torus, ray: &Ray, samples: u32) -> (Vec<f64>, f64) {
    let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
    let reach = f64::from(torus.major_radius + torus.minor_radius) * 1.01;
    let t_mid = (torus.center.as_dvec3() - o).dot(d) / d.length_squared();
    let half = reach / d.length();
    let (t_lo, step) = (t_mid - half, 2.0 * half / f64::from(samples));
    let g = |t: f64| tube_function(torus, o + d * t);
    let mut found = Vec::new();
    let mut a = t_lo;
    for i in 1..=samples {
        let b = t_lo + step * f64::from(i);
        if (g(a) > 0.0) != (g(b) > 0.0) {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if (g(mid) > 0.0) == (g(lo) > 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            found.push(0.5 * (lo + hi));
        }
        a = b;
    }
    (found, step)
}

#[test]
fn torus_crossings_agree_with_a_dense_root_search() {
    let hits = &HitCount::default();
    proptest!(|(case in torus_case())| {
        let TorusCase { torus, ray } = case;
        let crossings = torus.crossings(&ray);
        hits.record(crossings.first());
        let (sampled, step) = sampled_crossings(&torus, &ray, 20_000);
        let size = f64::from(torus.major_radius + torus.minor_radius);
        let tolerance = 1e-5 * (size + ray.origin.abs().max_element() as f64)
            / ray.dir.as_dvec3().length();
        prop_assert!(crossings.is_sorted() && crossings.len().is_multiple_of(2), "{crossings:?}");
        // Every crossing the search finds is found, at the same place...
        for &t in &sampled {
            prop_assert!(
                crossings.iter().any(|&c| (f64::from(c) - t).abs() < tolerance),
                "sampled crossing {t} missing from {crossings:?}"
            );
        }
        // ...and any other crossing is one of a pair too close for the samples to see.
        for (i, &c) in crossings.iter().enumerate() {
            let c = f64::from(c);
            if !sampled.iter().any(|&t| (c - t).abs() < tolerance) {
                let partner = crossings
                    .iter()
                    .enumerate()
                    .any(|(j, &other)| j != i && (f64::from(other) - c).abs() < 2.0 * step);
                prop_assert!(partner, "crossing {c} not in {sampled:?}");
            }
        }
        // The first hit is the first crossing in range.
        let first = crossings.iter().copied().find(|&t| t > 1e-4);
        let hit = torus.intersect(&ray, 1e-4, f32::INFINITY).map(|h| h.t);
        prop_assert_eq!(hit.is_some(), first.is_some(), "{:?} vs {:?}", hit, first);
        if let (Some(hit), Some(first)) = (hit, first) {
            prop_assert!(f64::from((hit - first).abs()) < tolerance, "{hit} vs {first}");
        }
        for &t in &crossings {
            let p = ray.at(t);
            let s = torus.surface(p, 0);
            prop_assert!((s.normal.length() - 1.0).abs() < 1e-5, "normal {}", s.normal);
            let q = (p - torus.center).as_dvec3();
            let rho = q.x.hypot(q.z);
            let ring = DVec3::new(q.x / rho, 0.0, q.z / rho) * f64::from(torus.major_radius);
            let expected = (q - ring).normalize().as_vec3();
            prop_assert!(s.normal.dot(expected) > 0.999, "normal {} at {p}, expected {expected}", s.normal);
            prop_assert!(s.uv.cmpge(Vec2::ZERO).all() && s.uv.cmple(Vec2::ONE).all(), "uv {}", s.uv);
        }
    });
    hits.assert_at_least(0.3);
}

/// A point on a torus at `turn` around the ring and `around` the tube (fractions of a turn,
/// `around` = 0 on the outer equator), and the outward normal there.
fn torus_point(torus: &Torus, turn: f32, around: f32) -> (Vec3, Vec3) {
    let (sin_t, cos_t) = (turn * TAU).sin_cos();
    let (sin_a, cos_a) = (around * TAU).sin_cos();
    let radial = Vec3::new(cos_t, 0.0, sin_t);
    let normal = radial * cos_a + Vec3::Y * sin_a;
    (
        torus.center + radial * torus.major_radius + normal * torus.minor_radius,
        normal,
    )
}

proptest! {
    #[test]
    fn rays_just_inside_a_grazing_line_on_the_outer_half_hit_near_the_touch(
        scale in prop_oneof![Just(1e-3f32), Just(1.0f32), Just(1e3f32)],
        tube in float_in(0.1, 0.95),
        turn in float_in(0.0, 1.0),
        around in float_in(-0.15, 0.15),
        heading in float_in(0.0, TAU),
        depth in float_in(1e-4, 1e-3),
    ) {
        // On the outer half the surface is convex: a ray tangent to it there, moved a little
        // into the tube, crosses the tube twice close to where it touched.
        let torus = Torus::new(Vec3::new(0.5, -1.0, 2.0) * scale, scale, tube * scale).unwrap();
        let (touch, normal) = torus_point(&torus, turn, around);
        let (e1, e2) = normal.any_orthonormal_pair();
        let along = e1 * heading.cos() + e2 * heading.sin();
        let inside = touch - normal * (depth * torus.minor_radius);
        let ray = Ray::new(inside - along * 5.0 * scale, along);
        let crossings = torus.crossings(&ray);
        let near = crossings
            .iter()
            .filter(|&&t| (ray.at(t) - touch).length() < 0.5 * torus.minor_radius)
            .count();
        prop_assert_eq!(near, 2, "{:?} around {}", crossings, touch);
        let outside = touch + normal * (depth * torus.minor_radius);
        let missing = Ray::new(outside - along * 5.0 * scale, along);
        prop_assert!(
            torus.crossings(&missing).iter().all(|&t| (missing.at(t) - touch).length() > 1e-3 * torus.minor_radius),
            "{:?}", torus.crossings(&missing)
        );
    }

    #[test]
    fn rays_skimming_the_inner_equator_through_the_hole_cross_four_times(
        scale in prop_oneof![Just(1e-3f32), Just(1.0f32), Just(1e3f32)],
        tube in float_in(0.05, 0.9),
        turn in float_in(0.0, TAU),
        gap in float_in(1e-4, 1e-2),
        dir_scale in dir_scale(),
    ) {
        // A horizontal line at distance R − r − gap from the axis passes through the hole,
        // inside the tube on both sides of where it skims the inner equator.
        let torus = Torus::new(Vec3::new(-1.0, 0.5, 3.0) * scale, scale, tube * scale).unwrap();
        let (sin, cos) = turn.sin_cos();
        let (out, along) = (Vec3::new(cos, 0.0, sin), Vec3::new(-sin, 0.0, cos));
        let closest = torus.center + out * (torus.major_radius - torus.minor_radius * (1.0 + gap));
        let ray = Ray::new(closest - along * 3.0 * scale, along * dir_scale);
        let crossings = torus.crossings(&ray);
        prop_assert_eq!(crossings.len(), 4, "{:?}", crossings);
        let middle = ray.at(0.5 * (crossings[1] + crossings[2]));
        prop_assert!((middle - closest).length() < 1e-3 * scale, "{} vs {}", middle, closest);
        prop_assert!(crossings[1] < crossings[2]);
    }

    #[test]
    fn rays_along_the_axis_miss_and_rays_from_inside_the_tube_leave_once(
        scale in prop_oneof![Just(1e-3f32), Just(1.0f32), Just(1e3f32)],
        tube in float_in(0.05, 0.95),
        start in unit_cube(),
        dir in unit_vector(),
    ) {
        let torus = Torus::new(Vec3::new(2.0, 1.0, -1.0) * scale, scale, tube * scale).unwrap();
        let axis = Ray::new(torus.center + Vec3::Y * 3.0 * scale, -Vec3::Y);
        prop_assert!(torus.crossings(&axis).is_empty());
        // A point inside the tube: its first hit lies ahead, and an odd number of crossings do.
        let (surface, normal) = torus_point(&torus, start.x, start.y);
        let tube_centre = surface - normal * torus.minor_radius;
        let inside = surface.lerp(tube_centre, 0.1 + 0.8 * start.z);
        let ray = Ray::new(inside, dir);
        prop_assert!(tube_function(&torus, inside.as_dvec3()) < 0.0);
        let ahead = torus.crossings(&ray).iter().filter(|&&t| t > 0.0).count();
        prop_assert!(!ahead.is_multiple_of(2), "{ahead} crossings ahead");
        let hit = torus.intersect(&ray, 0.0, f32::INFINITY);
        prop_assert!(hit.is_some());
    }
}
