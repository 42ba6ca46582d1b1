// A test entry point: each ray's closest hit among a list of shapes, found by trying them all,
// for checking the shapes' WGSL against the CPU's intersection on the same rays
// (src/gpu/shapes.rs, tests/gpu_shapes.rs).

struct Ray {
    origin: vec3<f32>,
    t_min: f32,
    dir: vec3<f32>,
    t_max: f32,
}

// The closest hit's `t` and the index of its shape (0xffffffff: none; `t` is then `t_max`).
struct Hit {
    t: f32,
    object: u32,
}

@group(0) @binding(0) var<storage, read> spheres: array<Sphere>;
@group(0) @binding(1) var<storage, read> rays: array<Ray>;
@group(0) @binding(2) var<storage, read_write> hits: array<Hit>;

@compute @workgroup_size(64)
fn first_hits(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&rays) {
        return;
    }
    let ray = rays[i];
    var best = Hit(ray.t_max, 0xffffffffu);
    for (var k = 0u; k < arrayLength(&spheres); k++) {
        let hit = intersect_sphere(spheres[k], ray.origin, ray.dir, ray.t_min, best.t);
        if hit.found {
            best = Hit(hit.t, k);
        }
    }
    hits[i] = best;
}
