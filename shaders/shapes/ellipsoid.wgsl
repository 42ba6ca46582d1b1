// Axis-aligned ellipsoids: the twin of src/shapes/ellipsoid.rs.

struct Ellipsoid {
    center: vec3<f32>,
    inv_radii: vec3<f32>,
}

fn load_ellipsoid(first: u32) -> Ellipsoid {
    return Ellipsoid(shape_words[first].xyz, shape_words[first + 1u].xyz);
}

// `Ellipsoid::intersect`: the unit sphere in a space scaled by 1 / radii about the centre,
// solved from the point `o` of the ray nearest the centre (s = t − shift).
fn intersect_ellipsoid(s: Ellipsoid, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let scaled_origin = (origin - s.center) * s.inv_radii;
    let d = dir * s.inv_radii;
    let dd = dot(d, d);
    if dd == 0.0 {
        return no_hit(); // no direction: where the Rust's `shift` is not finite
    }
    let shift = -dot(scaled_origin, d) / dd;
    let o = scaled_origin + d * shift;
    let roots = solve_quadratic(dd, dot(o, d), dot(o, o) - 1.0);
    if !roots.found {
        return no_hit();
    }
    return first_root_in(roots.t0 + shift, roots.t1 + shift, t_min, t_max);
}

// `Ellipsoid::surface`: the gradient (p − c) / r² and the sphere's texture coordinates at the
// matching point of the unit sphere.
fn ellipsoid_surface(s: Ellipsoid, p: vec3<f32>, part: u32) -> LocalSurface {
    let on_unit_sphere = (p - s.center) * s.inv_radii;
    var d = vec3<f32>(0.0, 1.0, 0.0);
    if dot(on_unit_sphere, on_unit_sphere) > 0.0 {
        d = normalize(on_unit_sphere);
    }
    return LocalSurface(on_unit_sphere * s.inv_radii, sphere_uv(d));
}
