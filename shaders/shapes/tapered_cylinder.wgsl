// Tapered cylinders (cylinders, cones and truncated cones, optionally capped): the twin of
// src/shapes/tapered_cylinder.rs. Work is done in a local frame: z along the axis (0 at the
// base, `height` at the top), x and y across it.

struct TaperedCylinder {
    base: vec3<f32>,
    height: f32,
    // Unit vectors of the local frame (frame_x × frame_y = axis).
    frame_x: vec3<f32>,
    base_radius: f32,
    frame_y: vec3<f32>,
    top_radius: f32,
    axis: vec3<f32>,
    // Change of radius per unit of height.
    slope: f32,
    capped: bool,
}

fn load_tapered_cylinder(first: u32) -> TaperedCylinder {
    let w0 = shape_words[first];
    let w1 = shape_words[first + 1u];
    let w2 = shape_words[first + 2u];
    let w3 = shape_words[first + 3u];
    let capped = shape_words[first + 4u].x != 0.0;
    return TaperedCylinder(w0.xyz, w0.w, w1.xyz, w1.w, w2.xyz, w2.w, w3.xyz, w3.w, capped);
}

// `TaperedCylinder::local_point`: `p` in the local frame.
fn tapered_local_point(s: TaperedCylinder, p: vec3<f32>) -> vec3<f32> {
    let rel = p - s.base;
    return vec3<f32>(dot(rel, s.frame_x), dot(rel, s.frame_y), dot(rel, s.axis));
}

// `TaperedCylinder::intersect`: the nearest of the side (x² + y² = (r₀ + slope·z)² for
// 0 ≤ z ≤ height) and, when capped, the end disks, solved from the point `o` of the ray nearest
// the middle of the axis (s = t − shift).
fn intersect_tapered_cylinder(s: TaperedCylinder, ray_origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let d = vec3<f32>(dot(dir, s.frame_x), dot(dir, s.frame_y), dot(dir, s.axis));
    let origin = tapered_local_point(s, ray_origin);
    let dd = dot(d, d);
    if dd == 0.0 {
        return no_hit(); // no direction: where the Rust's `shift` is not finite
    }
    let shift = dot(vec3<f32>(0.0, 0.0, 0.5 * s.height) - origin, d) / dd;
    let o = origin + d * shift;
    var nearest = no_hit();
    var t_far = t_max;

    let radius_at_o = s.base_radius + s.slope * o.z;
    let a = d.x * d.x + d.y * d.y - s.slope * s.slope * d.z * d.z;
    let half_b = o.x * d.x + o.y * d.y - s.slope * radius_at_o * d.z;
    let c = o.x * o.x + o.y * o.y - radius_at_o * radius_at_o;
    let roots = solve_quadratic(a, half_b, c);
    if roots.found {
        let side = first_root_between_ends(roots, shift, t_min, t_far, o.z, d.z, s.height);
        if side.found {
            nearest = ShapeHit(side.t, TAPERED_SIDE, true);
            t_far = side.t;
        }
    }

    if s.capped && d.z != 0.0 {
        for (var part = TAPERED_BASE_CAP; part <= TAPERED_TOP_CAP; part++) {
            var z = 0.0;
            var radius = s.base_radius;
            if part == TAPERED_TOP_CAP {
                z = s.height;
                radius = s.top_radius;
            }
            if radius == 0.0 {
                continue; // a cone's apex
            }
            let cap_s = (z - o.z) / d.z;
            let t = cap_s + shift;
            if t > t_min && t < t_far {
                let x = o.x + d.x * cap_s;
                let y = o.y + d.y * cap_s;
                if x * x + y * y <= radius * radius {
                    nearest = ShapeHit(t, part, true);
                    t_far = t;
                }
            }
        }
    }
    return nearest;
}

// `TaperedCylinder::normal`: the outward normal at `p` on part `part` (not of unit length on
// the side).
fn tapered_cylinder_normal(s: TaperedCylinder, p: vec3<f32>, part: u32) -> vec3<f32> {
    if part == TAPERED_BASE_CAP {
        return -s.axis;
    }
    if part == TAPERED_TOP_CAP {
        return s.axis;
    }
    // The gradient of √(x² + y²) − r₀ − slope·z; at a cone's apex any radial direction will do.
    let local = tapered_local_point(s, p);
    var radial = vec2<f32>(1.0, 0.0);
    let across = vec2<f32>(local.x, local.y);
    if dot(across, across) > 0.0 {
        radial = normalize(across);
    }
    return s.frame_x * radial.x + s.frame_y * radial.y - s.axis * s.slope;
}

// `TaperedCylinder::surface`: the side maps cylindrically (u the angle around the axis over 2π,
// v the fraction of the height); each cap maps its disk onto [0, 1]².
fn tapered_cylinder_surface(s: TaperedCylinder, p: vec3<f32>, part: u32) -> LocalSurface {
    let local = tapered_local_point(s, p);
    var uv: vec2<f32>;
    if part == TAPERED_BASE_CAP {
        uv = disk_uv(vec2<f32>(-local.x, local.y), s.base_radius);
    } else if part == TAPERED_TOP_CAP {
        uv = disk_uv(vec2<f32>(local.x, local.y), s.top_radius);
    } else {
        let u = 0.5 + atan2(local.y, local.x) / (2.0 * PI);
        let v = clamp(local.z / s.height, 0.0, 1.0);
        uv = vec2<f32>(u, v);
    }
    return LocalSurface(tapered_cylinder_normal(s, p, part), uv);
}

// `disk_uv`: the texture coordinates of the point `q` (in the disk's plane, from its centre) on
// a disk of radius `radius`, mapped onto [0, 1]².
fn disk_uv(q: vec2<f32>, radius: f32) -> vec2<f32> {
    var scale = 0.0;
    if radius > 0.0 {
        scale = 0.5 / radius;
    }
    return clamp(vec2<f32>(0.5) + q * scale, vec2<f32>(0.0), vec2<f32>(1.0));
}
