// The BVH's walk: the twin of `Bvh::walk` in src/bvh/traverse.rs over the nodes of one of the
// layouts src/gpu/bvh.rs makes (the CPU's eight-wide nodes, `wide_node.wgsl`, or two-wide ones,
// `binary_node.wgsl`: each gives `Node`, its `WIDTH` and its children), the leaves' tests of
// src/bvh/leaf.rs, and the closest-hit and shadow searches built on them (`Bvh::closest_hit`,
// `Bvh::any_hit`). The unbounded objects (planes) are tested first, against every ray. A leaf
// of instances puts them on the stack; walking into one (src/bvh/instances.rs) moves the ray
// into its model's space and goes down the model's tree, until the stack is back where it was.

// A child of a node, as the layout gives it (`node_child`): its box, and an interior child's
// node or a leaf's entries (count 0: no child in this slot).
struct NodeChild {
    lo: vec3<f32>,
    hi: vec3<f32>,
    first: u32,
    count: u32,
}

// The closest hit found so far along a ray: `Hit` in src/primitive.rs.
struct Hit {
    t: f32,
    prim: u32,
    part: u32,
    // For a triangle: where it lies in `triangles` and `triangle_shading`.
    slot: u32,
    bary: vec2<f32>,
    found: bool,
    // Where the record of the instance whose triangle it is starts in `refs` (NO_INSTANCE: the
    // world's own).
    instance: u32,
}

// A ray with what its box and triangle tests need, prepared once.
struct WalkRay {
    origin: vec3<f32>,
    dir: vec3<f32>,
    // `RayBoxTest::inv_dir`: ±0 components give the largest float of their sign.
    inv_dir: vec3<f32>,
    sheared: ShearedRay,
}

fn walk_ray(origin: vec3<f32>, dir: vec3<f32>) -> WalkRay {
    var inv_dir = vec3<f32>(0.0);
    for (var axis = 0u; axis < 3u; axis++) {
        if dir[axis] == 0.0 {
            inv_dir[axis] = copysign(T_FAR, dir[axis]);
        } else {
            inv_dir[axis] = 1.0 / dir[axis];
        }
    }
    return WalkRay(origin, dir, inv_dir, shear_ray(origin, dir));
}

// The slab test of a child's box (`Aabb::entry`): the entry distance, or -1 for a miss.
fn enter_box(lo: vec3<f32>, hi: vec3<f32>, ray: WalkRay, t_min: f32, t_max: f32) -> f32 {
    let t0 = (lo - ray.origin) * ray.inv_dir;
    let t1 = (hi - ray.origin) * ray.inv_dir;
    let near_axes = min(t0, t1);
    let far_axes = max(t0, t1);
    let near = max(max(max(near_axes.x, near_axes.y), near_axes.z), t_min);
    let far = min(min(min(far_axes.x, far_axes.y), far_axes.z), t_max);
    if near <= far {
        return near;
    }
    return -1.0;
}

// Whether a loop of this invocation ended without reaching its end: the driver cut the work
// short. A GPU driver may bound the loop iterations a shader runs (Mesa's llvmpipe and lavapipe
// end every loop once an invocation has run 65535 iterations in all); the renderer then traces
// the sample again on the CPU. Set where a loop that only ends by `return` or `break` falls
// through.
var<private> cut_short: bool;

// What a walk found: the closest hit, or the product of the tints of what the shadow ray met
// and the sum of the optical depths of the media inside what it passed (`Tracer::tints`).
struct WalkResult {
    hit: Hit,
    passed: vec3<f32>,
    depth: f32,
}

// Meets the primitive of `hit` along the ray `world` (in the world): the closest search keeps it
// and shrinks the ray's range, the shadow search takes its tint. Returns whether the walk can
// stop (nothing gets through); where light passes, a shadow search adds the primitive's optical
// depth after.
fn meet(hit: Hit, world: WalkRay, find: u32, result: ptr<function, WalkResult>, t_max: ptr<function, f32>) -> bool {
    if find == FIND_CLOSEST {
        (*result).hit = hit;
        *t_max = hit.t;
        return false;
    }
    (*result).passed *= tint(world.origin, world.dir, hit);
    return all((*result).passed == vec3<f32>(0.0));
}

// Tests the `count` objects listed in `refs` from `first`; returns whether the walk can stop.
//
// A shadow ray's walk also adds up the optical depth `σ·length` of the media inside the objects
// it passes (`Tracer::optical_depth`). The crossings come in no particular order, but the length
// inside an object is the sum of `+t` at each crossing out of it and `−t` at each crossing into
// it (a ray that starts inside has only the crossing out); inside, the medium is that of the
// surface the ray entered by (the one it leaves by, if it starts inside). An object is met
// once, at its first crossing in range, so its later crossings are found by intersecting it
// again past each one, by the same call as the first: the compiler copies the shapes at each
// call.
fn visit_objects(first: u32, count: u32, ray: WalkRay, t_min: f32, find: u32, result: ptr<function, WalkResult>, t_max: ptr<function, f32>) -> bool {
    var i = first;
    // While the crossings of object `i` are followed: how many were taken, where the next is
    // looked for, and whether the ray is inside, where it entered and the density there.
    var crossings = 0u;
    var search_from = t_min;
    var inside = false;
    var entered_at = 0.0;
    var inside_density = 0.0;
    while i < first + count {
        let index = refs[i];
        let o = objects[index];
        let h = intersect_object(o, ray.origin, ray.dir, search_from, *t_max);
        let at = Hit(h.t, index | OBJECT_BIT, h.part, 0u, vec2<f32>(0.0), true, NO_INSTANCE);
        var follow = h.found && crossings < MAX_CROSSINGS;
        if crossings == 0u && h.found {
            if meet(at, ray, find, result, t_max) {
                return true;
            }
            // A CSG solid's operands may differ in material; any other object has one.
            follow = find == FIND_SHADOW && (o.kind == SHAPE_CSG || materials[o.material].medium_density != 0.0);
        }
        if follow {
            let density = materials[material_of(at)].medium_density;
            let normal = object_surface(o, ray.origin, ray.dir, h.t, h.part).normal;
            if dot(ray.dir, normal) > 0.0 {
                var start = 0.0;
                var inside_at = density;
                if inside {
                    start = entered_at;
                    inside_at = inside_density;
                }
                (*result).depth += inside_at * (h.t - start) * length(ray.dir);
                inside = false;
            } else {
                inside = true;
                entered_at = h.t;
                inside_density = density;
            }
            crossings++;
            search_from = h.t;
            continue;
        }
        i++;
        crossings = 0u;
        search_from = t_min;
        inside = false;
    }
    return false;
}

// Tests the `count` triangles from `first` against `ray`, in the space of `instance`'s model
// (NO_INSTANCE: the world's); returns whether the walk can stop. A shadow ray's walk adds the
// optical depth of a mesh's medium at each triangle it passes, along the ray in the world.
fn visit_triangles(first: u32, count: u32, ray: WalkRay, world: WalkRay, instance: u32, t_min: f32, find: u32, result: ptr<function, WalkResult>, t_max: ptr<function, f32>) -> bool {
    var first_triangle = 0u;
    if instance != NO_INSTANCE {
        first_triangle = refs[instance + 1u];
    }
    for (var i = first; i < first + count; i++) {
        let tri = triangles[i];
        let h = intersect_triangle(tri, ray.sheared, t_min, *t_max);
        if !h.found {
            continue;
        }
        let hit = Hit(h.t, first_triangle + tri.index, 0u, i, h.bary, true, instance);
        if meet(hit, world, find, result, t_max) {
            return true;
        }
        if find == FIND_SHADOW {
            (*result).depth += triangle_optical_depth(world.origin, world.dir, hit);
        }
    }
    return false;
}

// The walk: the unbounded objects, then the tree, nearest child first for the closest hit (a
// hit prunes what lies beyond it), in slot order for a shadow ray (which must meet everything
// in its range unless something opaque stops it). The unbounded objects are visited as a leaf
// of their own before the root, so that each kind of leaf is tested at one place only.
fn walk(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max_in: f32, find: u32) -> WalkResult {
    return walk_from(origin, dir, t_min, t_max_in, find, NO_INSTANCE);
}

// The walk, from the scene's root (`only` NO_INSTANCE), or into the instance whose record starts
// at `only` in `refs` alone (the item buffer's proxy of an instance).
fn walk_from(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max_in: f32, find: u32, only: u32) -> WalkResult {
    var result = WalkResult(Hit(t_max_in, 0u, 0u, 0u, vec2<f32>(0.0), false, NO_INSTANCE), vec3<f32>(1.0), 0.0);
    let world = walk_ray(origin, dir);
    var ray = world;
    // The instance whose model's tree the walk is in (NO_INSTANCE: the scene's), and the size of
    // the stack when it went in: the entries below are the scene's.
    var instance = NO_INSTANCE;
    var instance_base = 0u;
    var t_max = min(t_max_in, T_FAR);
    var stack_first: array<u32, WALK_STACK>;
    var stack_count: array<u32, WALK_STACK>;
    var stack_t: array<f32, WALK_STACK>;
    var size = 0u;
    var next_first = frame.unbounded_first;
    var next_count = frame.unbounded;
    if only != NO_INSTANCE {
        next_first = only;
        next_count = INSTANCE_ENTRY;
    } else if frame.node_count != 0u {
        stack_first[0] = 0u;
        stack_count[0] = INTERIOR;
        stack_t[0] = t_min;
        size = 1u;
    }
    loop {
        if next_count == INSTANCE_ENTRY {
            // Into the instance: its model's tree, with the ray in the model's space (its
            // direction not renormalised, so that `t` means the same point).
            instance = next_first;
            instance_base = size;
            let object_ray = ray_to_object(refs[instance + 2u], origin, dir);
            ray = walk_ray(object_ray.origin, object_ray.dir);
            next_first = refs[refs[instance]];
            next_count = INTERIOR;
            continue;
        }
        if next_count != INTERIOR {
            var stop = false;
            if (next_count & TRIANGLE_LEAF) != 0u {
                stop = visit_triangles(next_first, next_count & ~TRIANGLE_LEAF, ray, world, instance, t_min, find, &result, &t_max);
            } else if (next_count & INSTANCE_LEAF) != 0u {
                // The leaf's instances wait on the stack, the first on top.
                let n = next_count & ~INSTANCE_LEAF;
                for (var k = n; k > 0u; k--) {
                    stack_first[size] = next_first + (k - 1u) * INSTANCE_WORDS;
                    stack_count[size] = INSTANCE_ENTRY;
                    stack_t[size] = t_min;
                    size++;
                }
            } else {
                stop = visit_objects(next_first, next_count, ray, t_min, find, &result, &t_max);
            }
            if stop {
                return result;
            }
        } else {
            let node = nodes[next_first];
            let base = size;
            var entered = 0u;
            for (var k = 0u; k < WIDTH; k++) {
                let child = node_child(node, k);
                if child.count == 0u {
                    continue;
                }
                let t = enter_box(child.lo, child.hi, ray, t_min, t_max);
                if t < 0.0 {
                    continue;
                }
                entered++;
                // Pushed farthest first (an insertion sort of at most eight) for the closest
                // hit, so the nearest comes off first; in slot order for shadows.
                var i = size;
                size++;
                if find == FIND_CLOSEST {
                    while i > base && stack_t[i - 1u] < t {
                        stack_first[i] = stack_first[i - 1u];
                        stack_count[i] = stack_count[i - 1u];
                        stack_t[i] = stack_t[i - 1u];
                        i--;
                    }
                }
                stack_first[i] = child.first;
                stack_count[i] = child.count;
                stack_t[i] = t;
            }
            if entered > 0u {
                // The nearest (or, for shadows, the last slot entered) is visited next.
                size--;
                next_first = stack_first[size];
                next_count = stack_count[size];
                continue;
            }
        }
        // Pop the next child still nearer than the best hit so far; out of the instance, back
        // into the world, where the scene's entries begin.
        var found_next = false;
        while size > 0u {
            if size == instance_base && instance != NO_INSTANCE {
                instance = NO_INSTANCE;
                ray = world;
            }
            size--;
            if stack_t[size] < t_max {
                next_first = stack_first[size];
                next_count = stack_count[size];
                found_next = true;
                break;
            }
        }
        if !found_next {
            return result;
        }
    }
    cut_short = true;
    return result;
}

// `Bvh::closest_hit`: the closest hit along the ray with `t` in (t_min, t_max).
fn closest_hit(origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> Hit {
    return walk(origin, dir, t_min, t_max, FIND_CLOSEST).hit;
}
