// Axis-aligned boxes: the twin of src/shapes/cuboid.rs. The faces are the parts 2·axis (the
// `min` side) and 2·axis + 1 (the `max` side): −x, +x, −y, +y, −z, +z.

struct Cuboid {
    min: vec3<f32>,
    max: vec3<f32>,
}

fn load_cuboid(first: u32) -> Cuboid {
    return Cuboid(shape_words[first].xyz, shape_words[first + 1u].xyz);
}

// `Cuboid::intersect`: the slab test, keeping track of the faces the ray enters and leaves by;
// a ray from inside hits the face it leaves by.
fn intersect_cuboid(s: Cuboid, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    // ±FLOAT_MAX where the Rust starts the slab test from ±infinity.
    var enter = -FLOAT_MAX;
    var enter_face = 0u;
    var exit = FLOAT_MAX;
    var exit_face = 0u;
    for (var axis = 0u; axis < 3u; axis++) {
        let o = origin[axis];
        let d = dir[axis];
        let low = s.min[axis];
        let high = s.max[axis];
        if d == 0.0 {
            if o < low || o > high {
                return no_hit(); // parallel to this slab and outside it
            }
            continue;
        }
        let inv_dir = 1.0 / d;
        let t_low = (low - o) * inv_dir;
        let t_high = (high - o) * inv_dir;
        let face = 2u * axis;
        var t_in = t_high;
        var face_in = face + 1u;
        var t_out = t_low;
        var face_out = face;
        if d > 0.0 {
            t_in = t_low;
            face_in = face;
            t_out = t_high;
            face_out = face + 1u;
        }
        if t_in > enter {
            enter = t_in;
            enter_face = face_in;
        }
        if t_out < exit {
            exit = t_out;
            exit_face = face_out;
        }
    }
    if enter > exit {
        return no_hit();
    }
    if enter > t_min && enter < t_max {
        return ShapeHit(enter, enter_face, true);
    }
    if exit > t_min && exit < t_max {
        return ShapeHit(exit, exit_face, true);
    }
    return no_hit();
}

// `Cuboid::surface`: each face maps to [0, 1]² the right way round seen from outside.
fn cuboid_surface(s: Cuboid, p: vec3<f32>, part: u32) -> LocalSurface {
    let f = clamp((p - s.min) / (s.max - s.min), vec3<f32>(0.0), vec3<f32>(1.0));
    switch part {
        case 0u: {
            return LocalSurface(vec3<f32>(-1.0, 0.0, 0.0), vec2<f32>(f.z, f.y));
        }
        case 1u: {
            return LocalSurface(vec3<f32>(1.0, 0.0, 0.0), vec2<f32>(1.0 - f.z, f.y));
        }
        case 2u: {
            return LocalSurface(vec3<f32>(0.0, -1.0, 0.0), vec2<f32>(f.x, f.z));
        }
        case 3u: {
            return LocalSurface(vec3<f32>(0.0, 1.0, 0.0), vec2<f32>(f.x, 1.0 - f.z));
        }
        case 4u: {
            return LocalSurface(vec3<f32>(0.0, 0.0, -1.0), vec2<f32>(1.0 - f.x, f.y));
        }
        default: {
            return LocalSurface(vec3<f32>(0.0, 0.0, 1.0), vec2<f32>(f.x, f.y));
        }
    }
}
