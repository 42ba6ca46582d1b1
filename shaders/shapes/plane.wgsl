// Infinite planes: the twin of src/shapes/plane.rs.

struct Plane {
    point: vec3<f32>,
    // Unit normal: the side it points to is the plane's front.
    normal: vec3<f32>,
}

fn load_plane(first: u32) -> Plane {
    return Plane(shape_words[first].xyz, shape_words[first + 1u].xyz);
}

// `Plane::intersect`; a ray parallel to the plane misses it.
fn intersect_plane(s: Plane, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let denom = dot(s.normal, dir);
    if denom == 0.0 {
        return no_hit();
    }
    let t = dot(s.normal, s.point - origin) / denom;
    if t > t_min && t < t_max {
        return ShapeHit(t, 0u, true);
    }
    return no_hit();
}

// `Plane::crossings`: as a CSG operand the plane is the half-space behind it, which the line
// is inside from where it crosses the plane going backwards, or up to where it crosses going
// forwards; everywhere or nowhere when it runs parallel.
fn plane_crossings(s: Plane, origin: vec3<f32>, dir: vec3<f32>) -> Crossings {
    let denom = dot(s.normal, dir);
    let height = dot(s.normal, origin - s.point);
    var crossings = Crossings(vec4<f32>(-FLOAT_MAX, FLOAT_MAX, 0.0, 0.0), vec4<u32>(0u), 2u);
    if denom == 0.0 {
        if !(height < 0.0) {
            crossings.count = 0u;
        }
    } else if denom < 0.0 {
        crossings.t.x = -height / denom;
    } else {
        crossings.t.y = -height / denom;
    }
    return crossings;
}

// `Plane::surface`: planar mapping, distances along the two `tangent_axes`.
fn plane_surface(s: Plane, p: vec3<f32>, part: u32) -> LocalSurface {
    let axes = tangent_axes(s.normal);
    let d = p - s.point;
    return LocalSurface(s.normal, vec2<f32>(dot(d, axes[0]), dot(d, axes[1])));
}

// `tangent_axes`: two unit axes spanning the plane orthogonal to the unit vector `n`; for a
// horizontal plane (n = +Y), +X and −Z.
fn tangent_axes(n: vec3<f32>) -> array<vec3<f32>, 2> {
    var helper = vec3<f32>(0.0, 0.0, 1.0);
    if abs(n.y) < 0.999 {
        helper = vec3<f32>(0.0, 1.0, 0.0);
    }
    var s = normalize(cross(helper, n));
    if abs(n.y) >= 0.999 {
        s = -s * sign(n.y);
    }
    return array<vec3<f32>, 2>(s, cross(n, s));
}
