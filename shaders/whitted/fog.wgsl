// Fog and other media along the rays of the ray tree: the twin of src/whitted/fog.rs
// (`Tracer::through_medium`, `in_scattered`, `light_in_medium`, `dim_by_fog`, `Spread`,
// `hash_vec3`). A ray through a medium keeps its transmittance of the light from beyond and
// gains the light the medium scatters into it from every light, gathered at `fog_steps`
// stratified sample points per light, jittered by a hash of the ray, each with a shadow ray
// that the ray tree's loop casts (trace.wgsl).

// The light a medium scatters into a ray (`Tracer::in_scattered`), gathered a sample at a time:
// the ray from `origin` along the unit vector `dir`, its `segment` inside `medium`, the seeds of
// its jitter, `scale` what a sample's light is multiplied by (the ray's throughput, the
// medium's scattering, the phase function, one over the samples per light), and the next of
// its `count` samples (light by light, `fog_steps` each).
struct InScatter {
    medium: Medium,
    origin: vec3<f32>,
    next: u32,
    dir: vec3<f32>,
    count: u32,
    scale: vec3<f32>,
    seed_origin: u32,
    segment: Segment,
    seed_dir: u32,
}

// What a medium does to a ray: the share of the light from its far end that passes, and the
// light the medium scatters into it, still to gather.
struct Passage {
    transmittance: f32,
    in_scatter: InScatter,
}

// `Tracer::through_medium`: the passage of the ray from `origin` along `ray_dir`, whose hit is
// at `t_end` (T_FAR: none), through the medium `within` says; `throughput` is the ray's.
fn through_medium(within: u32, origin: vec3<f32>, ray_dir: vec3<f32>, t_end: f32, throughput: vec3<f32>) -> Passage {
    let length = length(ray_dir);
    let dir = ray_dir / length;
    var end = T_FAR;
    if t_end < T_FAR {
        end = t_end * length;
    }
    let inside = within_segment(within, origin, dir, end);
    var in_scatter: InScatter;
    if !inside.segment.found {
        return Passage(1.0, in_scatter);
    }
    let segment = inside.segment;
    let medium = inside.medium;
    let transmittance = medium_transmittance(medium, segment.end - segment.start);
    if medium.density == 0.0 {
        return Passage(transmittance, in_scatter);
    }
    let steps = frame.fog_steps;
    let scale = throughput * medium_scattering(medium) * (ISOTROPIC_PHASE / f32(steps));
    in_scatter = InScatter(medium, origin, 0u, dir, frame.light_count * steps, scale, hash_vec3(origin), segment, hash_vec3(dir));
    return Passage(transmittance, in_scatter);
}

// `Tracer::in_scattered` and `Tracer::light_in_medium`, a sample at a time: the shadow ray from
// the next sample point of `s` towards its light, carrying the light that arrives there dimmed
// by the fog on its way; not `found` once every sample has been taken. Sample k of a light is
// jittered inside the k-th of `fog_steps` equal strata and spread as `Spread` says.
fn next_scatter_ray(s: ptr<function, InScatter>) -> ShadowRay {
    let steps = frame.fog_steps;
    while (*s).next < (*s).count {
        let sample_index = (*s).next;
        (*s).next++;
        let index = sample_index / steps;
        let k = sample_index % steps;
        let light = lights[index];
        let spread = spread_along(light, (*s).origin, (*s).dir, (*s).segment, (*s).medium.density);
        let u = jitter((*s).seed_origin, (*s).seed_dir, sample_index).x;
        let at = spread_at(spread, (f32(k) + u) / f32(steps));
        let point = (*s).origin + (*s).dir * at.s;
        let sample = light_sample(light, point);
        if all(sample.color == vec3<f32>(0.0)) {
            continue;
        }
        let light_color = (*s).scale * (at.weight * dim_by_fog(point, sample).color);
        return ShadowRay(point, sample.distance, sample.dir, true, light_color);
    }
    return ShadowRay(vec3<f32>(0.0), 0.0, vec3<f32>(0.0), false, vec3<f32>(0.0));
}

// `Tracer::dim_by_fog`: `sample`, the light arriving at `point`, dimmed by the fog on its way
// from the light.
fn dim_by_fog(point: vec3<f32>, sample: LightSample) -> LightSample {
    if frame.fog_density == 0.0 {
        return sample;
    }
    let passed = fog_transmittance(point, sample.dir, 0.0, sample.distance);
    return LightSample(sample.dir, sample.distance, sample.color * passed);
}

// `Spread`: how a light's sample points are spread along a segment of a medium. Not
// `equiangular` (`Spread::Transmittance`, for point and directional lights): as the medium's
// transmittance from the segment's start falls, `mass` the share of the light the whole
// segment takes away. `equiangular` (`Spread::Equiangular`, for spot lights): evenly in the
// angle under which the light sees the ray, `foot` the distance to the point nearest the light,
// `height` the light's distance from the ray, the angles those of the segment's ends.
struct Spread {
    equiangular: bool,
    start: f32,
    density: f32,
    mass: f32,
    foot: f32,
    height: f32,
    angle_start: f32,
    angle_end: f32,
}

// `Spread::new`: the spread for `light` along `segment` of the ray from `origin` along the unit
// vector `dir`, through a medium of extinction coefficient `density` (more than zero).
fn spread_along(light: Light, origin: vec3<f32>, dir: vec3<f32>, segment: Segment, density: f32) -> Spread {
    let mass = -exp_m1(-density * (segment.end - segment.start));
    let by_transmittance = Spread(false, segment.start, density, mass, 0.0, 0.0, 0.0, 0.0);
    if light.kind != LIGHT_SPOT {
        return by_transmittance;
    }
    let to_light = light.position - origin;
    let foot = dot(to_light, dir);
    let height = length(to_light - foot * dir);
    // A ray through the light itself: no angles to spread over (f32::EPSILON).
    if height <= 1.1920929e-7 * length(to_light) {
        return by_transmittance;
    }
    let angle_start = atan((segment.start - foot) / height);
    let angle_end = atan((segment.end - foot) / height);
    return Spread(true, segment.start, density, 0.0, foot, height, angle_start, angle_end);
}

// A sample of a spread: its distance along the ray and its weight `T(s − start) / pdf(s)`.
struct SpreadSample {
    s: f32,
    weight: f32,
}

// `Spread::at`: the sample at `u` (from 0 to 1).
fn spread_at(spread: Spread, u: f32) -> SpreadSample {
    if !spread.equiangular {
        // The inverse of the distribution `(1 − exp(−σ·(s − start))) / mass`.
        let s = spread.start - ln_1p(-u * spread.mass) / spread.density;
        return SpreadSample(s, spread.mass / spread.density);
    }
    let angle = spread.angle_start + u * (spread.angle_end - spread.angle_start);
    let along = spread.height * tan(angle);
    let h = spread.height;
    let weight = (spread.angle_end - spread.angle_start) * (h * h + along * along) / h;
    let s = spread.foot + along;
    return SpreadSample(s, weight * exp(-spread.density * (s - spread.start)));
}

// Rust's `f32::exp_m1`: eˣ − 1, accurate where x is small (Kahan's way: the rounding of eˣ
// divided out by that of its logarithm).
fn exp_m1(x: f32) -> f32 {
    let u = exp(x);
    if u == 1.0 {
        return x;
    }
    let m = u - 1.0;
    if m == -1.0 {
        return -1.0;
    }
    return m * x / log(u);
}

// Rust's `f32::ln_1p`: ln(1 + x), accurate where x is small (the same way).
fn ln_1p(x: f32) -> f32 {
    let u = 1.0 + x;
    if u == 1.0 {
        return x;
    }
    return log(u) * x / (u - 1.0);
}

// `hash_vec3`: a hash of a vector's bits, to seed the jitter of a ray's samples.
fn hash_vec3(v: vec3<f32>) -> u32 {
    return hash(bitcast<u32>(v.x) ^ hash(bitcast<u32>(v.y) ^ hash(bitcast<u32>(v.z))));
}
