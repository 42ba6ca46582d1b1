// How a surface splits a ray: the twin of src/whitted/scattering.rs (mirror direction, Snell's
// law, total internal reflection, Schlick's Fresnel approximation) and of `Material::schlick`.

// `reflect`: the mirror direction of `d` about the unit normal `n`.
fn mirror(d: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return d - 2.0 * dot(d, n) * n;
}

// `refract`: `d` (unit) bent through a surface with unit normal `n` facing it, `eta = n1 / n2`;
// `found` is false past the critical angle.
struct Refracted {
    dir: vec3<f32>,
    found: bool,
}

fn refract_dir(d: vec3<f32>, n: vec3<f32>, eta: f32) -> Refracted {
    let cos_i = -dot(d, n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return Refracted(vec3<f32>(0.0), false);
    }
    let cos_t = sqrt(1.0 - sin2_t);
    return Refracted(normalize(eta * d + (eta * cos_i - cos_t) * n), true);
}

// `Material::schlick`.
fn schlick(cos_i: f32, n1: f32, n2: f32) -> f32 {
    let r = (n1 - n2) / (n1 + n2);
    let r0 = r * r;
    let x = clamp(1.0 - cos_i, 0.0, 1.0);
    return r0 + (1.0 - r0) * (x * x * x * x * x);
}

// `Scattering`: the reflected and transmitted weights and the transmitted direction.
struct Scattering {
    reflect: f32,
    // The reflected ray's weight as a colour: `kr` tinted, the share taken from transmission not.
    reflect_color: vec3<f32>,
    transmit: f32,
    refracted: Refracted,
}

// `scattering`.
fn scattering(m: Material, dir: vec3<f32>, normal: vec3<f32>, entering: bool) -> Scattering {
    var reflect = m.reflectivity;
    var transmit = m.transparency;
    let tinted = m.reflection_color * m.reflectivity;
    if transmit == 0.0 {
        return Scattering(reflect, tinted, transmit, Refracted(vec3<f32>(0.0), false));
    }
    var n1 = m.ior;
    var n2 = 1.0;
    if entering {
        n1 = 1.0;
        n2 = m.ior;
    }
    let refracted = refract_dir(dir, normal, n1 / n2);
    if !refracted.found {
        reflect += transmit;
        transmit = 0.0;
    } else if m.fresnel != 0u {
        // Schlick's formula wants the angle on the optically thinner side.
        var cos = -dot(refracted.dir, normal);
        if n1 <= n2 {
            cos = -dot(dir, normal);
        }
        let fresnel = schlick(cos, n1, n2);
        reflect += transmit * fresnel;
        transmit *= 1.0 - fresnel;
    }
    return Scattering(reflect, tinted + vec3<f32>(reflect - m.reflectivity), transmit, refracted);
}
