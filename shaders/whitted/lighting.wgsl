// The local colour at a hit, the lecture's shading model: the twin of src/whitted/lighting.rs
// and of `Light::sample` in src/light.rs. Emission, ambient light and caustics, plus the diffuse
// (Lambert) and specular (Phong) light of every light a shadow ray reaches, dimmed by the fog
// on its way; transparent blockers tint the light that passes them, and those filled with a
// medium dim it by the length the shadow ray runs inside them (Beer–Lambert: the walk adds up
// their optical depths). The shadow rays are cast by the ray tree's loop (trace.wgsl), where
// every ray of a tree is cast.

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
    if light.kind == LIGHT_DIRECTIONAL {
        return LightSample(light.direction, T_FAR, light.color);
    }
    let to_light = light.position - point;
    if light.kind == LIGHT_SPOT {
        let distance_squared = dot(to_light, to_light);
        let distance = sqrt(distance_squared);
        let dir = to_light / distance;
        return LightSample(dir, distance, light.color * (spot_cone(light, -dir) / distance_squared));
    }
    let distance = length(to_light);
    return LightSample(to_light / distance, distance, light.color);
}

// `Tracer::tint`: what the primitive met at `hit` by the ray from `origin` along `dir` lets
// through of the light behind it; nothing through glass that bends light when the caustic
// photons bring that light instead; all of it where its surface is cut away.
fn tint(origin: vec3<f32>, dir: vec3<f32>, hit: Hit) -> vec3<f32> {
    if (frame.flags & OPAQUE) != 0u {
        return vec3<f32>(0.0);
    }
    if cut_away(origin, dir, hit) {
        return vec3<f32>(1.0);
    }
    let m = materials[material_of(hit)];
    // `Material::bends_light`.
    if (frame.flags & CAUSTICS) != 0u && m.transparency > 0.0 && m.ior != 1.0 {
        return vec3<f32>(0.0);
    }
    return m.transparency * m.color;
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

// `Tracer::transmittance_and_blocker`: what a shadow ray's walk lets through: the product of
// the blockers' tints, times the transmittance of the media inside them.
fn shadow_transmittance(found: WalkResult) -> vec3<f32> {
    return found.passed * exp(-max(found.depth, 0.0));
}

// `offset_origin` in src/ray.rs: a point moved off its surface along the normal, by an amount
// that grows with the point's magnitude.
fn offset_origin(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let a = abs(point);
    let scale = 1.0 + max(max(a.x, a.y), a.z);
    return point + normal * (2e-4 * scale);
}

// A shadow ray still to cast (`found`): from `origin` towards a light along `dir`, up to
// `distance`, and `light`, what it adds to the eye ray's colour where nothing blocks it.
struct ShadowRay {
    origin: vec3<f32>,
    distance: f32,
    dir: vec3<f32>,
    found: bool,
    light: vec3<f32>,
}

// A hit whose local colour is being gathered (`Tracer::local_color`): its material and base
// colour, the surface with normals facing the ray, the ray's unit direction and throughput,
// and the next light to look at.
struct Shading {
    m: Material,
    base: vec3<f32>,
    surface: SurfacePoint,
    normal: vec3<f32>,
    geometric_normal: vec3<f32>,
    dir: vec3<f32>,
    throughput: vec3<f32>,
    next_light: u32,
}

// `Tracer::local_color`'s light that needs no shadow ray: emission (times its texture), ambient light, and with
// caustics on the diffuse light of the caustic photons nearby.
fn shadowless_color(s: Shading) -> vec3<f32> {
    var emission = s.m.emission;
    if s.m.emission_texture != NO_TEXTURE && (frame.flags & TEXTURES) != 0u {
        emission *= texture_color(s.m.emission_texture, s.surface.uv, s.surface.object_point);
    }
    var color = emission + s.m.ambient * s.base * frame.ambient;
    if (frame.flags & CAUSTICS) != 0u && s.m.diffuse > 0.0 {
        color += s.m.diffuse * s.base * caustic_irradiance(s.surface.point, s.normal);
    }
    return color;
}

// `Tracer::local_color`'s loop over the lights, a light at a time: the shadow ray towards the
// next light that adds to the hit's colour, carrying its diffuse (Lambert) and specular (Phong)
// light, dimmed by the fog on its way; not `found` once every light has been seen.
fn next_shadow_ray(s: ptr<function, Shading>) -> ShadowRay {
    let point = (*s).surface.point;
    let normal = (*s).normal;
    while (*s).next_light < frame.light_count {
        let sample = light_sample(lights[(*s).next_light], point);
        (*s).next_light++;
        // A light behind the surface (as seen from the ray's side), or a spot turned away
        // from it, adds nothing and needs no shadow ray.
        let cos_l = dot(normal, sample.dir);
        if cos_l <= 0.0 || dot((*s).geometric_normal, sample.dir) <= 0.0 || all(sample.color == vec3<f32>(0.0)) {
            continue;
        }
        let m = (*s).m;
        let diffuse = m.diffuse * cos_l * (*s).base;
        let reflected = mirror(-sample.dir, normal);
        let cos_r = max(dot(reflected, -(*s).dir), 0.0);
        var specular = vec3<f32>(0.0);
        if m.specular > 0.0 && cos_r > 0.0 {
            specular = m.specular * pow(cos_r, m.shininess) * m.specular_color;
        }
        let arrived = dim_by_fog(point, sample).color;
        let light = (*s).throughput * arrived * (diffuse + specular);
        let origin = offset_origin(point, (*s).geometric_normal);
        return ShadowRay(origin, sample.distance, sample.dir, true, light);
    }
    return ShadowRay(vec3<f32>(0.0), 0.0, vec3<f32>(0.0), false, vec3<f32>(0.0));
}
