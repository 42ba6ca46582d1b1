// The local colour at a hit, the lecture's shading model: the twin of src/whitted/lighting.rs
// and of `Light::sample` in src/light.rs. Emission and ambient light, plus the diffuse
// (Lambert) and specular (Phong) light of every light a shadow ray reaches, dimmed by the fog
// on its way; transparent blockers tint the light that passes them, and those filled with a
// medium dim it by the length the shadow ray runs inside them (Beer–Lambert).

// Rays counted as the CPU counts them (`RayCounts`).
struct Counts {
    primary_hits: u32,
    shadow: u32,
    reflected: u32,
    transmitted: u32,
    over_budget: u32,
}

// `LightSample`: the unit direction towards the light, the distance a shadow ray covers, and
// the colour that arrives before any blocker.
struct LightSample {
    dir: vec3<f32>,
    distance: f32,
    color: vec3<f32>,
}

// `Spot::cone`: the share of a spot's light that leaves towards `dir` (from the light).
fn spot_cone(light: Light, dir: vec3<f32>) -> f32 {
    let cos = dot(light.direction, dir);
    if cos >= light.cos_full {
        return 1.0;
    }
    if cos <= light.cos_angle {
        return 0.0;
    }
    let x = (cos - light.cos_angle) / (light.cos_full - light.cos_angle);
    return x * x * (3.0 - 2.0 * x);
}

// `Light::sample`: where the light is seen from `point`.
fn light_sample(light: Light, point: vec3<f32>) -> LightSample {
    if light.kind == DIRECTIONAL_LIGHT {
        return LightSample(light.direction, T_FAR, light.color);
    }
    let to_light = light.position - point;
    if light.kind == SPOT_LIGHT {
        let distance_squared = dot(to_light, to_light);
        let distance = sqrt(distance_squared);
        let dir = to_light / distance;
        return LightSample(dir, distance, light.color * (spot_cone(light, -dir) / distance_squared));
    }
    let distance = length(to_light);
    return LightSample(to_light / distance, distance, light.color);
}

// `Tracer::tint`: what the primitive hit lets through of the light behind it.
fn tint(hit: Hit) -> vec3<f32> {
    if (frame.flags & OPAQUE) != 0u {
        return vec3<f32>(0.0);
    }
    let m = materials[material_of(hit)];
    return m.transparency * m.color;
}

// `Tracer::transmittance_and_blocker`: what passes along the shadow ray from `origin` along
// `dir` up to `distance`: the product of the blockers' tints, times the transmittance of the
// media inside them by the sum of their optical depths, which the walk adds up.
fn shadow_transmittance(origin: vec3<f32>, dir: vec3<f32>, distance: f32) -> vec3<f32> {
    let found = walk(origin, dir, 0.0, distance, FIND_SHADOW);
    return found.passed * exp(-max(found.depth, 0.0));
}

// The most times a line crosses the surface of an object the GPU traces (a torus's four).
const MAX_CROSSINGS: u32 = 4u;

// `Tracer::optical_depth`: the optical depth `σ·length` that the shadow ray from `origin` along
// `dir` (up to `distance`) adds by running through the medium inside the primitive of `hit`,
// the first hit the walk met on it. The hits come in no particular order, but the length
// inside an object is the sum of `+t` at each crossing out of it and `−t` at each crossing
// into it (a ray that starts inside has only the crossing out). This is an object's share: it
// is met once, at its first crossing, so its later crossings are found by intersecting it
// again past each one. An object the GPU traces has one material, whose medium fills it.
fn object_optical_depth(origin: vec3<f32>, dir: vec3<f32>, distance: f32, hit: Hit) -> f32 {
    let o = objects[hit.prim & ~OBJECT_BIT];
    let density = materials[o.material].medium_density;
    if density == 0.0 {
        return 0.0;
    }
    let length = length(dir);
    var depth = 0.0;
    // Where the ray entered, while it is inside.
    var inside = false;
    var entered_at = 0.0;
    var at = hit;
    for (var k = 0u; k < MAX_CROSSINGS; k++) {
        let normal = object_surface(o, origin, dir, at.t, at.part).normal;
        if dot(dir, normal) > 0.0 {
            var start = 0.0;
            if inside {
                start = entered_at;
            }
            depth += density * (at.t - start) * length;
            inside = false;
        } else {
            inside = true;
            entered_at = at.t;
        }
        let next = intersect_object(o, origin, dir, at.t, distance);
        if !next.found {
            break;
        }
        at = Hit(next.t, hit.prim, next.part, 0u, vec2<f32>(0.0), true);
    }
    return depth;
}

// `Tracer::optical_depth` of a mesh triangle, met once: `+σ·t` where the ray passes out of the
// mesh through it, `−σ·t` where it passes in.
fn triangle_optical_depth(origin: vec3<f32>, dir: vec3<f32>, hit: Hit) -> f32 {
    let surface = triangle_surface(origin + dir * hit.t, hit);
    let density = materials[surface.material].medium_density;
    var sign = -1.0;
    if dot(dir, surface.geometric_normal) > 0.0 {
        sign = 1.0;
    }
    return sign * density * hit.t * length(dir);
}

// `offset_origin` in src/ray.rs: a point moved off its surface along the normal, by an amount
// that grows with the point's magnitude.
fn offset_origin(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let a = abs(point);
    let scale = 1.0 + max(max(a.x, a.y), a.z);
    return point + normal * (2e-4 * scale);
}

// `Tracer::local_color`.
fn local_color(m: Material, base: vec3<f32>, surface: SurfacePoint, normal: vec3<f32>, geometric_normal: vec3<f32>, dir: vec3<f32>, counts: ptr<function, Counts>) -> vec3<f32> {
    var color = m.emission + m.ambient * base * frame.ambient;
    let shadow_origin = offset_origin(surface.point, geometric_normal);
    for (var i = 0u; i < frame.light_count; i++) {
        let sample = light_sample(lights[i], surface.point);
        // A light behind the surface (as seen from the ray's side), or a spot turned away
        // from it, adds nothing and needs no shadow ray.
        let cos_l = dot(normal, sample.dir);
        if cos_l <= 0.0 || dot(geometric_normal, sample.dir) <= 0.0 || all(sample.color == vec3<f32>(0.0)) {
            continue;
        }
        var light_color = dim_by_fog(surface.point, sample).color;
        if (frame.flags & SHADOWS) != 0u {
            (*counts).shadow++;
            light_color *= shadow_transmittance(shadow_origin, sample.dir, sample.distance);
        }
        if all(light_color == vec3<f32>(0.0)) {
            continue;
        }
        let diffuse = m.diffuse * cos_l * base;
        let reflected = mirror(-sample.dir, normal);
        let cos_r = max(dot(reflected, -dir), 0.0);
        var specular = vec3<f32>(0.0);
        if m.specular > 0.0 && cos_r > 0.0 {
            specular = m.specular * pow(cos_r, m.shininess) * m.specular_color;
        }
        color += light_color * (diffuse + specular);
    }
    return color;
}
