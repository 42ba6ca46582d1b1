// Spheres: the twin of src/shapes/sphere.rs, step for step, so that the GPU finds the same
// crossings as the CPU.

struct Sphere {
    center: vec3<f32>,
    radius: f32,
}

fn load_sphere(first: u32) -> Sphere {
    let w = shape_words[first];
    return Sphere(w.xyz, w.w);
}

// `Sphere::intersect`: solves |o + d·t − c|² = r² with the discriminant computed as r² − |f|²,
// f = oc − (oc·d / d·d)·d, which stays accurate for spheres far from the ray's origin.
fn intersect_sphere(s: Sphere, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let oc = origin - s.center;
    let a = dot(dir, dir);
    let half_b = dot(oc, dir);
    let c = dot(oc, oc) - s.radius * s.radius;
    let f = oc - (half_b / a) * dir;
    let disc = a * (s.radius * s.radius - dot(f, f));
    if disc < 0.0 {
        return no_hit();
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

// `Sphere::surface`: the normal, and the spherical mapping (`sphere_uv`): u around the vertical
// axis, v from the south pole (0) to the north pole (1).
fn sphere_surface(s: Sphere, p: vec3<f32>, part: u32) -> LocalSurface {
    let n = (p - s.center) / s.radius;
    var d = vec3<f32>(0.0, 1.0, 0.0);
    if dot(n, n) > 0.0 {
        d = normalize(n);
    }
    return LocalSurface(n, sphere_uv(d));
}

// `sphere_uv`: the texture coordinates of the unit direction `d` from a sphere's centre.
fn sphere_uv(d: vec3<f32>) -> vec2<f32> {
    let u = 0.5 + atan2(d.x, d.z) / (2.0 * PI);
    let v = 0.5 + asin(clamp(d.y, -1.0, 1.0)) / PI;
    return vec2<f32>(u, v);
}
