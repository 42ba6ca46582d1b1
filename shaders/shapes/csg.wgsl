// Boolean objects (CSG): the twin of src/shapes/csg.rs (`Csg::intersect`, `Csg::surface`).
// Every operand says where the line of the ray is inside it, as spans along the whole line
// (`shape_crossings`); the postfix program combines the spans with fixed-size stacks, and the
// first boundary of the result in (t_min, t_max) is the hit. Every leaf is traced, where the
// CPU skips those whose box the ray misses in (t_min, t_max): that changes nothing inside it.
//
// The shape words of a node (`push_csg` in src/gpu/shapes.rs writes them): a header with the
// numbers of leaves and of steps; one record per leaf (its shape's kind, or-ed with
// `CSG_COMPLEMENTED` where it is subtracted an odd number of times, where its numbers start,
// where its transform to the node's space starts, its material); then the steps, four to a
// word: a leaf's index, or `CSG_COMBINE` or-ed with the operation.

struct CsgLeaf {
    kind: u32,
    first: u32,
    transform: u32,
    material: u32,
    complemented: bool,
}

fn load_csg_leaf(first: u32, index: u32) -> CsgLeaf {
    let w = bitcast<vec4<u32>>(shape_words[first + 1u + index]);
    return CsgLeaf(w.x & ~CSG_COMPLEMENTED, w.y, w.z, w.w, (w.x & CSG_COMPLEMENTED) != 0u);
}

// The leaf a hit's `part` belongs to.
fn csg_leaf_of(first: u32, part: u32) -> CsgLeaf {
    return load_csg_leaf(first, part >> CSG_PART_BITS);
}

// Where the ray enters or leaves a solid: the ray parameter and the CSG part.
struct CsgBoundary {
    t: f32,
    part: u32,
}

// A stretch of the line inside a solid.
struct CsgSpan {
    enter: CsgBoundary,
    exit: CsgBoundary,
}

// `CsgOperation::contains`: whether a point inside `a` or not and inside `b` or not is inside
// the result.
fn csg_contains(operation: u32, in_a: bool, in_b: bool) -> bool {
    switch operation {
        case CSG_UNION: {
            return in_a || in_b;
        }
        case CSG_INTERSECTION: {
            return in_a && in_b;
        }
        case CSG_DIFFERENCE, default: {
            return in_a && !in_b;
        }
    }
}

// Boundary `i` (enter, exit, enter…) of the list of spans starting at `start` of `spans`.
fn csg_boundary(spans: ptr<function, array<CsgSpan, CSG_MAX_SPANS>>, start: u32, i: u32) -> CsgBoundary {
    let span = (*spans)[start + i / 2u];
    if i % 2u == 0u {
        return span.enter;
    }
    return span.exit;
}

// `combine`: sweeps along the boundaries of the lists `a..b` and `b..end` of `stack` (each
// sorted and disjoint) and writes to `out` the spans where `operation` says the ray is inside
// the result; returns how many. Boundaries at the same `t` are taken together, the first of
// them (`a`'s before `b`'s) standing for them all.
fn csg_combine(operation: u32, stack: ptr<function, array<CsgSpan, CSG_MAX_SPANS>>, a: u32, b: u32, end: u32, out: ptr<function, array<CsgSpan, CSG_MAX_SPANS>>) -> u32 {
    let a_end = 2u * (b - a);
    let b_end = 2u * (end - b);
    var i = 0u;
    var j = 0u;
    var inside = false;
    var entered = false;
    var enter = CsgBoundary(0.0, 0u);
    var count = 0u;
    while i < a_end || j < b_end {
        // The nearest boundary not yet passed: `a`'s where they are at the same `t`.
        var first: CsgBoundary;
        if i < a_end && (j >= b_end || csg_boundary(stack, a, i).t <= csg_boundary(stack, b, j).t) {
            first = csg_boundary(stack, a, i);
            i++;
        } else {
            first = csg_boundary(stack, b, j);
            j++;
        }
        while i < a_end && csg_boundary(stack, a, i).t <= first.t {
            i++;
        }
        while j < b_end && csg_boundary(stack, b, j).t <= first.t {
            j++;
        }
        // Boundaries alternate enter, exit: an odd count passed means inside.
        let now = csg_contains(operation, i % 2u == 1u, j % 2u == 1u);
        if now != inside {
            inside = now;
            if entered {
                (*out)[count] = CsgSpan(enter, first);
                count++;
                entered = false;
            } else {
                enter = first;
                entered = true;
            }
        }
    }
    return count;
}

// `Csg::intersect` of the node whose words start at `first`: the first boundary of the result
// in (t_min, t_max).
fn intersect_csg(first: u32, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let header = bitcast<vec4<u32>>(shape_words[first]);
    let leaf_count = header.x;
    let step_count = header.y;
    let steps = first + 1u + leaf_count;
    var stack: array<CsgSpan, CSG_MAX_SPANS>;
    var combined: array<CsgSpan, CSG_MAX_SPANS>;
    // Where each pending list starts in `stack`.
    var starts: array<u32, CSG_MAX_LISTS>;
    var lists = 0u;
    var top = 0u;
    for (var k = 0u; k < step_count; k++) {
        let step = bitcast<u32>(shape_words[steps + k / 4u][k % 4u]);
        if (step & CSG_COMBINE) == 0u {
            starts[lists] = top;
            lists++;
            let leaf = load_csg_leaf(first, step);
            let ray = ray_to_object(leaf.transform, origin, dir);
            let c = shape_crossings(leaf.kind, leaf.first, ray.origin, ray.dir);
            let base = step << CSG_PART_BITS;
            for (var i = 0u; i + 1u < c.count; i += 2u) {
                stack[top] = CsgSpan(
                    CsgBoundary(c.t[i], base | c.part[i]),
                    CsgBoundary(c.t[i + 1u], base | c.part[i + 1u]),
                );
                top++;
            }
        } else {
            lists--;
            let b = starts[lists];
            let a = starts[lists - 1u];
            let count = csg_combine(step & ~CSG_COMBINE, &stack, a, b, top, &combined);
            for (var i = 0u; i < count; i++) {
                stack[a + i] = combined[i];
            }
            top = a + count;
        }
    }
    for (var i = 0u; i < top; i++) {
        let span = stack[i];
        if span.enter.t > t_min && span.enter.t < t_max {
            return ShapeHit(span.enter.t, span.enter.part, true);
        }
        if span.exit.t > t_min && span.exit.t < t_max {
            return ShapeHit(span.exit.t, span.exit.part, true);
        }
    }
    return no_hit();
}

// `Csg::surface`: the surface of the leaf that `part` names at the node-space point `p`, its
// normal facing out of the result.
fn csg_surface(first: u32, p: vec3<f32>, part: u32) -> LocalSurface {
    let leaf = csg_leaf_of(first, part);
    let leaf_part = part & ((1u << CSG_PART_BITS) - 1u);
    var leaf_point = p;
    if leaf.transform != NO_TRANSFORM {
        leaf_point = point_to_object(load_transform(leaf.transform), p);
    }
    var local = plain_shape_surface(leaf.kind, leaf.first, leaf_point, leaf_part);
    if leaf.transform != NO_TRANSFORM {
        local.normal = normalize(load_transform(leaf.transform).normal_to_world * local.normal);
    }
    if leaf.complemented {
        local.normal = -local.normal;
    }
    return local;
}

// `Object::material_at` for a CSG object: the material of the leaf that `part` names.
fn csg_material(first: u32, part: u32) -> u32 {
    return csg_leaf_of(first, part).material;
}
