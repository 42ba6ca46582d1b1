// Test entry points that check the GPU's parts against the CPU's on the same input
// (src/gpu/probe.rs): each ray's closest hit among all objects tried one by one (the shapes'
// WGSL against `Geometry::intersect`), and through the BVH (against `Bvh::closest_hit`), with
// the surface there; and the colours of textures at given points (against `Texture::color`).
// Bind group 1 holds the input and the results.

struct ProbeRay {
    origin: vec3<f32>,
    t_min: f32,
    dir: vec3<f32>,
    t_max: f32,
}

// A ray's closest hit: `t` (the ray's `t_max` for none), the `PrimId` (0xffffffff: none), the
// part, and the unit world normal and texture coordinates there.
struct ProbeHit {
    normal: vec3<f32>,
    t: f32,
    uv: vec2<f32>,
    prim: u32,
    part: u32,
}

@group(1) @binding(WORK_INPUT) var<storage, read> probe_rays: array<ProbeRay>;
@group(1) @binding(WORK_OUTPUT) var<storage, read_write> probe_hits: array<ProbeHit>;

fn probe_result(ray: ProbeRay, hit: Hit) -> ProbeHit {
    if !hit.found {
        return ProbeHit(vec3<f32>(0.0), ray.t_max, vec2<f32>(0.0), 0xffffffffu, 0u);
    }
    let s = surface_at(ray.origin, ray.dir, hit);
    return ProbeHit(s.normal, hit.t, s.uv, hit.prim, hit.part);
}

@compute @workgroup_size(WORKGROUP)
fn probe_objects(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&probe_rays) {
        return;
    }
    let ray = probe_rays[i];
    var best = Hit(ray.t_max, 0u, 0u, 0u, vec2<f32>(0.0), false, NO_INSTANCE);
    for (var k = 0u; k < frame.object_count; k++) {
        let h = intersect_object(objects[k], ray.origin, ray.dir, ray.t_min, best.t);
        if h.found {
            best = Hit(h.t, k | OBJECT_BIT, h.part, 0u, vec2<f32>(0.0), true, NO_INSTANCE);
        }
    }
    probe_hits[i] = probe_result(ray, best);
}

@compute @workgroup_size(WORKGROUP)
fn probe_bvh(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&probe_rays) {
        return;
    }
    let ray = probe_rays[i];
    probe_hits[i] = probe_result(ray, closest_hit(ray.origin, ray.dir, ray.t_min, ray.t_max));
}

// A point of a texture to colour: texture coordinates `uv` and the object point, for
// `texture_color` (against `Texture::color`).
struct TextureProbe {
    point: vec3<f32>,
    texture: u32,
    uv: vec2<f32>,
    pad0: u32,
    pad1: u32,
}

@group(1) @binding(WORK_INPUT) var<storage, read> texture_probes: array<TextureProbe>;
@group(1) @binding(WORK_OUTPUT) var<storage, read_write> texture_colors: array<vec4<f32>>;

@compute @workgroup_size(WORKGROUP)
fn probe_textures(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&texture_probes) {
        return;
    }
    let probe = texture_probes[i];
    texture_colors[i] = vec4<f32>(texture_color(probe.texture, probe.uv, probe.point), 0.0);
}
