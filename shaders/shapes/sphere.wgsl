// Spheres: the twin of `Sphere::intersect` in src/shapes/sphere.rs, step for step, so that the
// GPU finds the same crossings as the CPU.

struct Sphere {
    center: vec3<f32>,
    radius: f32,
}

// A crossing of a ray with a shape: `found` is false where there is none in the range asked.
struct ShapeHit {
    t: f32,
    found: bool,
}

// The first of the sorted roots (t0, t1) in (t_min, t_max): `first_root_in` in
// src/shapes/quadratic.rs.
fn first_root_in(t0: f32, t1: f32, t_min: f32, t_max: f32) -> ShapeHit {
    if t0 > t_min && t0 < t_max {
        return ShapeHit(t0, true);
    }
    if t1 > t_min && t1 < t_max {
        return ShapeHit(t1, true);
    }
    return ShapeHit(0.0, false);
}

// `x` with the sign bit of `s`, as Rust's `f32::copysign` (which tells −0 from +0).
fn copysign(x: f32, s: f32) -> f32 {
    return bitcast<f32>((bitcast<u32>(x) & 0x7fffffffu) | (bitcast<u32>(s) & 0x80000000u));
}

// Solves |o + d·t − c|² = r² with the discriminant computed as r² − |f|², f = oc − (oc·d / d·d)·d,
// which stays accurate for spheres far from the ray's origin.
fn intersect_sphere(s: Sphere, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let oc = origin - s.center;
    let a = dot(dir, dir);
    let half_b = dot(oc, dir);
    let c = dot(oc, oc) - s.radius * s.radius;
    let f = oc - (half_b / a) * dir;
    let disc = a * (s.radius * s.radius - dot(f, f));
    if disc < 0.0 {
        return ShapeHit(0.0, false);
    }
    let q = -(half_b + copysign(sqrt(disc), half_b));
    var t0 = 0.0;
    var t1 = 0.0;
    if q != 0.0 {
        t0 = q / a;
        t1 = c / q;
        if t0 > t1 {
            let swap = t0;
            t0 = t1;
            t1 = swap;
        }
    }
    return first_root_in(t0, t1, t_min, t_max);
}
