// Objects: an analytic shape, picked by its kind, placed in the world by its transform. The twin
// of `Geometry::intersect_prepared` and `Geometry::surface_with` for objects in
// src/primitive.rs and of `Shape::intersect`, `Shape::surface` and `Shape::crossings` in
// src/shapes/mod.rs. Every shape's numbers and every transform are read from `shape_words`
// (src/gpu/shapes.rs writes them).

// WGSL's twin of `GpuObject`.
struct Object {
    kind: u32,
    first: u32,
    transform: u32,
    material: u32,
}

// A crossing of a ray with a shape: `found` is false where there is none in the range asked;
// `part` says which part of the shape was hit (a face of a box, a cap of a cylinder).
struct ShapeHit {
    t: f32,
    part: u32,
    found: bool,
}

fn no_hit() -> ShapeHit {
    return ShapeHit(0.0, 0u, false);
}

// The surface at a hit point, in object space: the outward normal (any length) and the texture
// coordinates.
struct LocalSurface {
    normal: vec3<f32>,
    uv: vec2<f32>,
}

// The nearest hit of the shape `kind` whose numbers start at `first`, with `t` in (t_min, t_max).
fn intersect_shape(kind: u32, first: u32, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    if kind == SHAPE_CSG {
        return intersect_csg(first, origin, dir, t_min, t_max);
    }
    return intersect_plain_shape(kind, first, origin, dir, t_min, t_max);
}

// Normal and texture coordinates at the object-space point `p` of part `part`.
fn shape_surface(kind: u32, first: u32, p: vec3<f32>, part: u32) -> LocalSurface {
    if kind == SHAPE_CSG {
        return csg_surface(first, p, part);
    }
    return plain_shape_surface(kind, first, p, part);
}

// An affine transform: `object_from_world` by its columns (three axes, the translation) and
// the matrix that takes normals to the world.
struct Transform {
    object_from_world: mat3x3<f32>,
    translation: vec3<f32>,
    normal_to_world: mat3x3<f32>,
}

fn load_transform(first: u32) -> Transform {
    let w = first;
    return Transform(
        mat3x3<f32>(shape_words[w].xyz, shape_words[w + 1u].xyz, shape_words[w + 2u].xyz),
        shape_words[w + 3u].xyz,
        mat3x3<f32>(shape_words[w + 4u].xyz, shape_words[w + 5u].xyz, shape_words[w + 6u].xyz),
    );
}

// A ray in an object's space; the direction is not renormalised, so `t` means the same point.
struct ObjectRay {
    origin: vec3<f32>,
    dir: vec3<f32>,
}

// `Affine3A::transform_point3` of `object_from_world`, summed in glam's order so that both find
// the same point.
fn point_to_object(tr: Transform, p: vec3<f32>) -> vec3<f32> {
    let m = tr.object_from_world;
    return m[0] * p.x + m[1] * p.y + m[2] * p.z + tr.translation;
}

// `Transform::ray_to_object` for the transform that starts at `transform` in the shape words,
// or the ray itself where there is none (`NO_TRANSFORM`).
fn ray_to_object(transform: u32, origin: vec3<f32>, dir: vec3<f32>) -> ObjectRay {
    if transform == NO_TRANSFORM {
        return ObjectRay(origin, dir);
    }
    let tr = load_transform(transform);
    let m = tr.object_from_world;
    return ObjectRay(point_to_object(tr, origin), m[0] * dir.x + m[1] * dir.y + m[2] * dir.z);
}

// Where the line of a ray crosses the surface of a closed solid, in increasing `t`: entry, exit,
// entry, exit… (the first `count`; `t` is ±FLOAT_MAX where the ray never leaves a half-space)
// and the part of each crossing. The twin of `Crossings`.
struct Crossings {
    t: vec4<f32>,
    part: vec4<u32>,
    count: u32,
}

// `Shape::crossings` of a convex solid (`Shape::is_convex`): a line crosses it at most twice:
// it enters at the first hit on the whole line and leaves at the next one (both found by one
// call, which the compiler copies once). A line that only touches the surface does not go in.
fn convex_crossings(kind: u32, first: u32, origin: vec3<f32>, dir: vec3<f32>) -> Crossings {
    var crossings = Crossings(vec4<f32>(0.0), vec4<u32>(0u), 0u);
    var search_from = -FLOAT_MAX;
    for (var k = 0u; k < 2u; k++) {
        let h = intersect_plain_shape(kind, first, origin, dir, search_from, FLOAT_MAX);
        if !h.found {
            break;
        }
        crossings.t[k] = h.t;
        crossings.part[k] = h.part;
        search_from = h.t;
        if k == 1u {
            crossings.count = 2u;
        }
    }
    return crossings;
}

// The nearest hit of the object `o` along the world ray, with `t` in (t_min, t_max).
fn intersect_object(o: Object, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let ray = ray_to_object(o.transform, origin, dir);
    return intersect_shape(o.kind, o.first, ray.origin, ray.dir, t_min, t_max);
}

// The surface of an object at a hit, for the shading: the hit point in the object's own space,
// the unit world normal and the texture coordinates.
struct ObjectSurface {
    object_point: vec3<f32>,
    normal: vec3<f32>,
    uv: vec2<f32>,
}

// The surface of object `o` where the world ray meets it at `t`, on part `part`.
fn object_surface(o: Object, origin: vec3<f32>, dir: vec3<f32>, t: f32, part: u32) -> ObjectSurface {
    let ray = ray_to_object(o.transform, origin, dir);
    let object_point = ray.origin + ray.dir * t;
    let local = shape_surface(o.kind, o.first, object_point, part);
    var normal = normalize(local.normal);
    if o.transform != NO_TRANSFORM {
        normal = normalize(load_transform(o.transform).normal_to_world * local.normal);
    }
    return ObjectSurface(object_point, normal, local.uv);
}
