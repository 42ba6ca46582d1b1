// Paraboloids of revolution opening towards +y, cut at a height and optionally capped: the twin
// of src/shapes/paraboloid.rs.

// The surface y = curvature·(x² + z²) for 0 ≤ y ≤ height, measured from `vertex`.
struct Paraboloid {
    vertex: vec3<f32>,
    radius: f32,
    height: f32,
    // height / radius²
    curvature: f32,
    capped: bool,
}

fn load_paraboloid(first: u32) -> Paraboloid {
    let w0 = shape_words[first];
    let w1 = shape_words[first + 1u];
    return Paraboloid(w0.xyz, w0.w, w1.x, w1.y, w1.z != 0.0);
}

// `Paraboloid::intersect`: the nearest of the bowl, k·(x² + z²) − y = 0 with 0 ≤ y ≤ height,
// and (when capped) the disk at y = height, solved from the point `o` of the ray nearest the
// middle of the axis (s = t − shift).
fn intersect_paraboloid(s: Paraboloid, ray_origin: vec3<f32>, d: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let origin = ray_origin - s.vertex;
    let dd = dot(d, d);
    if dd == 0.0 {
        return no_hit(); // no direction: where the Rust's `shift` is not finite
    }
    let shift = dot(vec3<f32>(0.0, 0.5 * s.height, 0.0) - origin, d) / dd;
    let o = origin + d * shift;
    let k = s.curvature;
    var nearest = no_hit();
    var t_far = t_max;

    let a = k * (d.x * d.x + d.z * d.z);
    let half_b = k * (o.x * d.x + o.z * d.z) - 0.5 * d.y;
    let c = k * (o.x * o.x + o.z * o.z) - o.y;
    let roots = solve_quadratic(a, half_b, c);
    if roots.found {
        let bowl = first_root_between_ends(roots, shift, t_min, t_far, o.y, d.y, s.height);
        if bowl.found {
            nearest = ShapeHit(bowl.t, PARABOLOID_BOWL, true);
            t_far = bowl.t;
        }
    }

    if s.capped && d.y != 0.0 {
        let cap_s = (s.height - o.y) / d.y;
        let t = cap_s + shift;
        if t > t_min && t < t_far {
            let x = o.x + d.x * cap_s;
            let z = o.z + d.z * cap_s;
            if x * x + z * z <= s.radius * s.radius {
                nearest = ShapeHit(t, PARABOLOID_CAP, true);
            }
        }
    }
    return nearest;
}

// `Paraboloid::surface`: the bowl maps cylindrically (u the angle around the axis over 2π, v
// the fraction of the height); the cap maps its disk onto [0, 1]², u along +x and v along −z.
fn paraboloid_surface(s: Paraboloid, p: vec3<f32>, part: u32) -> LocalSurface {
    let local = p - s.vertex;
    if part == PARABOLOID_CAP {
        return LocalSurface(vec3<f32>(0.0, 1.0, 0.0), disk_uv(vec2<f32>(local.x, -local.z), s.radius));
    }
    let k2 = 2.0 * s.curvature;
    let u = 0.5 + atan2(local.x, local.z) / (2.0 * PI);
    let v = clamp(local.y / s.height, 0.0, 1.0);
    return LocalSurface(vec3<f32>(k2 * local.x, -1.0, k2 * local.z), vec2<f32>(u, v));
}
