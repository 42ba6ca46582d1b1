// The debug views that look at the eye ray's first hit: the twin of `first_hit_color` and
// `id_color` in src/inspect/view_color.rs. The heat maps of the whole ray tree are drawn on the
// CPU only.

// `id_color`: a colour for `id`, distinct from its neighbours' (a hash), never near black.
fn id_color(id: u32) -> vec3<f32> {
    let h = hash((id * 0x9e3779b9u) ^ 0x5bd1e995u);
    let channels = (vec3<u32>(h, h >> 8u, h >> 16u) & vec3<u32>(0xffu));
    return 0.15 + 0.85 * vec3<f32>(channels) / 255.0;
}

// `Geometry::part_id`: the object's id (a mesh's or an instance's for its triangles), with a
// CSG solid's leaf told apart.
fn part_id(hit: Hit) -> u32 {
    if hit.instance != NO_INSTANCE {
        return refs[hit.instance + 4u];
    }
    if (hit.prim & OBJECT_BIT) == 0u {
        return triangles[hit.slot].object;
    }
    let object = hit.prim & ~OBJECT_BIT;
    if objects[object].kind == SHAPE_CSG {
        return object ^ (((hit.part >> CSG_PART_BITS) + 1u) << 20u);
    }
    return object;
}

// `first_hit_color`: the colour of the first hit `hit` with surface `surface` in the frame's view.
fn view_color(hit: Hit, surface: SurfacePoint) -> vec3<f32> {
    switch frame.view {
        case VIEW_NORMALS: {
            return surface.normal * 0.5 + 0.5;
        }
        case VIEW_DEPTH: {
            // `depth_grey`: white near, black far.
            let depth = dot(surface.point - frame.eye, -frame.n);
            let position = (depth - frame.depth_near) / (frame.depth_far - frame.depth_near);
            return vec3<f32>(1.0 - clamp(position, 0.0, 1.0));
        }
        case VIEW_UV: {
            // `rem_euclid(1.0)`, exact as Rust's.
            return vec3<f32>(surface.uv - floor(surface.uv), 0.0);
        }
        case VIEW_OBJECT: {
            return id_color(part_id(hit));
        }
        case VIEW_MATERIAL, default: {
            return id_color(surface.material);
        }
    }
}
