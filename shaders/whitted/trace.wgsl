// The ray tree of one eye ray: the twin of src/whitted/mod.rs (`trace_eye`, `shade`, `trace`,
// `traces_branch`) without recursion. A ray's colour is `T·(local + children) + S`, its local
// colour plus the weighted colours of its reflected and transmitted rays, seen through the
// transmittance `T` of the medium it runs through, plus the light `S` that medium scatters into
// it (`through_fog`, `through_medium`); the same sum is built front to back, each ray's `S`
// added with `throughput`, the product of the scales and transmittances on the way from the
// eye, and its local colour with its own `T` besides. The children wait on an explicit stack, reflected first, as the CPU's recursion takes
// them depth first, each with the medium it runs through (`Within`); the ray budget is checked when a child is taken, as the CPU checks it when
// it starts a child. A hit's shadow rays are cast before the next child, each adding its
// light's share of the local colour where it gets through.

// A ray of the tree still to trace.
struct Branch {
    origin: vec3<f32>,
    depth: u32,
    dir: vec3<f32>,
    weight: f32,
    throughput: vec3<f32>,
    // REFLECTIONS or TRANSMISSION: which child it is.
    kind: u32,
    // The medium it runs through (`Within`: WITHIN_FOG, WITHIN_CLEAR or a material).
    within: u32,
}

// Rays counted as the CPU counts them (`RayCounts`).
struct Counts {
    primary_hits: u32,
    from_item_buffer: u32,
    shadow: u32,
    reflected: u32,
    transmitted: u32,
    over_budget: u32,
}

// The colour seen along an eye ray, and the rays its tree traced.
struct Traced {
    color: vec3<f32>,
    counts: Counts,
}

// `Tracer::miss`: what a ray in direction `dir` that leaves the scene sees: the background
// image where it crosses it, else the background colour.
fn miss_color(dir: vec3<f32>) -> vec3<f32> {
    if frame.background_image != NO_TEXTURE {
        let image = textures[frame.background_image];
        let on_image = backdrop_uv(dir, f32(image.width) / f32(image.height));
        if on_image.found {
            return image_sample(image, on_image.uv).xyz;
        }
    }
    return frame.background;
}

// `Tracer::base_color`: the surface's colour, its texture's if it has one and textures are on,
// else the material's, times the mesh's vertex colour.
fn base_color(m: Material, surface: SurfacePoint) -> vec3<f32> {
    var color = m.color;
    if m.texture != NO_TEXTURE && (frame.flags & TEXTURES) != 0u {
        color = texture_color(m.texture, surface.uv, surface.object_point);
    }
    return color * surface.vertex_color;
}

// Whether a child ray carrying `weight` goes on: its kind is on and its weight reaches
// `min_weight` (adaptive depth control). The budget is checked when it is taken.
fn wanted(kind_on: u32, weight: f32) -> bool {
    return (frame.flags & kind_on) != 0u && weight >= frame.min_weight;
}

// Takes the next waiting child whose tree still has budget into `ray`; false when none waits.
fn next_branch(stack: ptr<function, array<Branch, TREE_STACK>>, size: ptr<function, u32>, ray: ptr<function, Branch>, counts: ptr<function, Counts>) -> bool {
    while *size > 0u {
        *size -= 1u;
        if (*counts).reflected + (*counts).transmitted >= RAY_BUDGET {
            (*counts).over_budget++;
            continue;
        }
        *ray = (*stack)[*size];
        if (*ray).kind == TRANSMISSION {
            (*counts).transmitted++;
        } else {
            (*counts).reflected++;
        }
        return true;
    }
    return false;
}

// How far an eye ray's first search looks, given the distance `item_t` of its pixel's item in
// the item buffer (0: none): a little beyond the item, or all the way without one.
fn item_far(item_t: f32) -> f32 {
    if item_t == 0.0 {
        return T_FAR;
    }
    return item_t * (1.0 + FAR_MARGIN);
}

// `Tracer::trace_eye`: the colour seen by the eye ray from the eye along `dir`, whose first hit
// is searched for only up to `item_t`, the distance of its pixel's item in the item buffer (0:
// none), and again all the way if none is found there.
//
// Every ray of the tree, shadow rays included, is cast by the one `walk` of the loop below: a
// GPU compiler copies a function at each place it is called, and the walk holds every shape.
// Each turn casts the next shadow ray of the medium the last ray ran through or of the hit
// being shaded, or, once those are done, the next ray of the tree, or the same ray again past
// the cut-away point it hit (`Tracer::past_cut_outs`).
fn trace_eye(dir: vec3<f32>, item_t: f32) -> Traced {
    var counts = Counts(0u, 0u, 0u, 0u, 0u, 0u);
    var color = vec3<f32>(0.0);
    var stack: array<Branch, TREE_STACK>;
    var size = 0u;
    var ray = Branch(frame.eye, 1u, dir, 1.0, vec3<f32>(1.0), 0u, WITHIN_FOG);
    // Whether `ray` is still to cast (the eye ray is), the light scattered into the last ray
    // still to gather, and the hit being shaded (none yet).
    var ray_waits = true;
    var in_scatter: InScatter;
    var shading: Shading;
    shading.next_light = frame.light_count;
    // How far the eye ray's search looks.
    var eye_far = item_far(item_t);
    // Where `ray`'s search goes on past the cut-away points it met (0: from its start), and how
    // many it passed.
    var past = 0.0;
    var cut_outs = 0u;
    // Whether the loop ended by its own `break` (see `cut_short`).
    var finished = false;
    loop {
        // The ray to cast: a shadow ray, or the tree's next ray, which the eye ray alone
        // starts at the image plane.
        var shadow = next_scatter_ray(&in_scatter);
        if !shadow.found {
            shadow = next_shadow_ray(&shading);
        }
        var origin = shadow.origin;
        var ray_dir = shadow.dir;
        var t_min = 0.0;
        var t_max = shadow.distance;
        var find = FIND_SHADOW;
        if shadow.found {
            if (frame.flags & SHADOWS) == 0u {
                color += shadow.light;
                continue;
            }
            counts.shadow++;
        } else {
            if !ray_waits && !next_branch(&stack, &size, &ray, &counts) {
                finished = true;
                break;
            }
            ray_waits = false;
            origin = ray.origin;
            ray_dir = ray.dir;
            t_max = T_FAR;
            if ray.depth == 1u {
                t_min = EYE_RAY_T_MIN;
                t_max = eye_far;
            }
            if cut_outs > 0u {
                t_min = past;
                t_max = T_FAR;
            }
            find = FIND_CLOSEST;
        }
        let found = walk(origin, ray_dir, t_min, t_max, find);
        if find == FIND_SHADOW {
            color += shadow.light * shadow_transmittance(found);
            continue;
        }
        let hit = found.hit;
        // The surface at the hit, if there is one.
        var surface: SurfacePoint;
        if hit.found {
            surface = surface_at(ray.origin, ray.dir, hit);
            let cuts = (frame.flags & CUT_OUTS) != 0u;
            if cuts && cut_outs < MAX_CUT_OUTS && cut_away_uv(materials[surface.material], surface.uv) {
                // Past the cut-away point, all the way.
                past = hit.t;
                cut_outs++;
                ray_waits = true;
                continue;
            }
        }
        if ray.depth == 1u && !hit.found && eye_far < T_FAR && cut_outs == 0u {
            // Nothing up to the item (rounding put its primitive elsewhere): the eye ray again,
            // all the way.
            eye_far = T_FAR;
            ray_waits = true;
            continue;
        }
        cut_outs = 0u;
        // A debug view shows the eye ray's first hit alone (black where it misses).
        let viewing = frame.view != VIEW_SHADED;
        var throughput = ray.throughput;
        if !viewing {
            var t_end = T_FAR;
            if hit.found {
                t_end = hit.t;
            }
            let passage = through_medium(ray.within, ray.origin, ray.dir, t_end, ray.throughput);
            in_scatter = passage.in_scatter;
            // What the ray meets, and its children, are seen through the medium.
            throughput *= passage.transmittance;
        }
        if !hit.found {
            if !viewing {
                color += throughput * miss_color(ray.dir);
            }
            continue;
        }
        if ray.depth == 1u {
            counts.primary_hits++;
            if eye_far < T_FAR {
                counts.from_item_buffer++;
            }
        }
        if viewing {
            color = view_color(hit, surface);
            finished = true;
            break;
        }
        // `Tracer::shade`: the shadowless part of the local colour now, its lights by the turns
        // to come, and the children onto the stack.
        let m = materials[surface.material];
        let unit_dir = normalize(ray.dir);
        // Face the normals towards the side the ray came from.
        let entering = dot(unit_dir, surface.geometric_normal) < 0.0;
        var side = -1.0;
        if entering {
            side = 1.0;
        }
        let normal = surface.normal * side;
        let geometric_normal = surface.geometric_normal * side;
        shading = Shading(m, base_color(m, surface), surface, normal, geometric_normal, unit_dir, throughput, 0u);
        color += throughput * shadowless_color(shading);
        if ray.depth < frame.max_depth {
            let s = scattering(m, unit_dir, normal, entering);
            let base = shading.base;
            // The transmitted child waits below the reflected one, which goes first.
            let transmit_weight = ray.weight * s.transmit;
            if s.refracted.found && s.transmit > 0.0 && wanted(TRANSMISSION, transmit_weight) {
                stack[size] = Branch(offset_origin(surface.point, -geometric_normal), ray.depth + 1u, s.refracted.dir, transmit_weight, throughput * (s.transmit * base), TRANSMISSION, after_crossing(surface.material, entering));
                size++;
            }
            let reflect_weight = ray.weight * s.reflect;
            if s.reflect > 0.0 && wanted(REFLECTIONS, reflect_weight) {
                stack[size] = Branch(offset_origin(surface.point, geometric_normal), ray.depth + 1u, mirror(unit_dir, normal), reflect_weight, throughput * s.reflect_color, REFLECTIONS, ray.within);
                size++;
            }
        }
    }
    if !finished {
        cut_short = true;
    }
    return Traced(color, counts);
}
