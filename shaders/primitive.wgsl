// What a hit met, in the world: the twin of `Geometry::surface_with` and `Geometry::material`
// in src/primitive.rs, for objects and mesh triangles alike.

// `SurfacePoint`: everything the shading needs to know about the surface at a hit.
struct SurfacePoint {
    point: vec3<f32>,
    object_point: vec3<f32>,
    // Unit shading normal, out of the surface's front.
    normal: vec3<f32>,
    // Unit geometric normal, on the same side as `normal`.
    geometric_normal: vec3<f32>,
    uv: vec2<f32>,
    // The mesh's vertex colour here (`Mesh::color`), white on objects and meshes without.
    vertex_color: vec3<f32>,
    material: u32,
}

// The material at `hit`: a CSG operand's own, or the object's; an instance's, where it has one,
// else its mesh's.
fn material_of(hit: Hit) -> u32 {
    if hit.instance != NO_INSTANCE && refs[hit.instance + 3u] != NO_MATERIAL {
        return refs[hit.instance + 3u];
    }
    if (hit.prim & OBJECT_BIT) != 0u {
        let o = objects[hit.prim & ~OBJECT_BIT];
        if o.kind == SHAPE_CSG {
            return csg_material(o.first, hit.part);
        }
        return o.material;
    }
    return triangle_shading[hit.slot].material & MATERIAL_BITS;
}

// The surface at `hit` along the ray.
fn surface_at(origin: vec3<f32>, dir: vec3<f32>, hit: Hit) -> SurfacePoint {
    let point = origin + dir * hit.t;
    if (hit.prim & OBJECT_BIT) != 0u {
        let o = objects[hit.prim & ~OBJECT_BIT];
        let s = object_surface(o, origin, dir, hit.t, hit.part);
        return SurfacePoint(point, s.object_point, s.normal, s.normal, s.uv, vec3<f32>(1.0), material_of(hit));
    }
    return triangle_surface(point, hit);
}

// The texture coordinates at `hit`, a mesh triangle's: its corners' blended, or the
// barycentric coordinates where its mesh has none.
fn triangle_uv(hit: Hit) -> vec2<f32> {
    let shading = triangle_shading[hit.slot];
    if (shading.material & HAS_UVS) == 0u {
        return hit.bary;
    }
    let a0 = vertex_attributes[shading.corners.x];
    let a1 = vertex_attributes[shading.corners.y];
    let a2 = vertex_attributes[shading.corners.z];
    let b0 = 1.0 - hit.bary.x - hit.bary.y;
    return vec2<f32>(a0.u, a0.v) * b0 + vec2<f32>(a1.u, a1.v) * hit.bary.x + vec2<f32>(a2.u, a2.v) * hit.bary.y;
}

// The texture coordinates at `hit` along the ray (`surface_at(…).uv`, without the rest).
fn hit_uv(origin: vec3<f32>, dir: vec3<f32>, hit: Hit) -> vec2<f32> {
    if (hit.prim & OBJECT_BIT) != 0u {
        let o = objects[hit.prim & ~OBJECT_BIT];
        return object_surface(o, origin, dir, hit.t, hit.part).uv;
    }
    return triangle_uv(hit);
}

// The surface at `hit`, a mesh triangle's, whose point is `point`: its corners are in the leaf
// copy, its shading record beside it says which mesh vertices they are (`Mesh::shading`). An
// instance's triangle lies in its model's space: its normals are moved into the world.
fn triangle_surface(point: vec3<f32>, hit: Hit) -> SurfacePoint {
    let shading = triangle_shading[hit.slot];
    var geometric = triangle_normal(triangles[hit.slot]);
    var n0 = vertex_attributes[shading.corners.x].normal;
    var n1 = vertex_attributes[shading.corners.y].normal;
    var n2 = vertex_attributes[shading.corners.z].normal;
    if hit.instance != NO_INSTANCE {
        let to_world = load_transform(refs[hit.instance + 2u]).normal_to_world;
        geometric = normalize(to_world * geometric);
        n0 = normalize(to_world * n0);
        n1 = normalize(to_world * n1);
        n2 = normalize(to_world * n2);
    }
    let b0 = 1.0 - hit.bary.x - hit.bary.y;
    var normal = geometric;
    let a0 = vertex_attributes[shading.corners.x];
    let a1 = vertex_attributes[shading.corners.y];
    let a2 = vertex_attributes[shading.corners.z];
    if (shading.material & HAS_NORMALS) != 0u {
        let n = n0 * b0 + n1 * hit.bary.x + n2 * hit.bary.y;
        if dot(n, n) > 0.0 {
            normal = normalize(n);
        }
    }
    let uv = triangle_uv(hit);
    var vertex_color = vec3<f32>(1.0);
    if (shading.material & HAS_COLORS) != 0u {
        vertex_color = vec3<f32>(a0.red, a0.green, a0.blue) * b0 + vec3<f32>(a1.red, a1.green, a1.blue) * hit.bary.x + vec3<f32>(a2.red, a2.green, a2.blue) * hit.bary.y;
    }
    // Vertex normals say which side is out; the winding may disagree.
    var geometric_normal = geometric;
    if dot(geometric, normal) < 0.0 {
        geometric_normal = -geometric;
    }
    return SurfacePoint(point, point, normal, geometric_normal, uv, vertex_color, material_of(hit));
}
