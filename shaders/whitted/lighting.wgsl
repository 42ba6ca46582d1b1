// The local colour at a hit, the lecture's shading model: the twin of src/whitted/lighting.rs
// and of `Light::sample` in src/light.rs. Emission and ambient light, plus the diffuse
// (Lambert) and specular (Phong) light of every light a shadow ray reaches; transparent
// blockers tint the light that passes them.

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
        var light_color = sample.color;
        if (frame.flags & SHADOWS) != 0u {
            (*counts).shadow++;
            light_color *= walk(shadow_origin, sample.dir, 0.0, sample.distance, FIND_SHADOW).passed;
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
