// Fog and other media along the rays of the ray tree: the twin of src/whitted/fog.rs
// (`Tracer::through_medium`, `in_scattered`, `light_in_medium`, `dim_by_fog`, `Spread`,
// `hash_vec3`). A ray through a medium keeps its transmittance of the light from beyond and
// gains the light the medium scatters into it from every light, gathered at `fog_steps`
// stratified sample points per light, jittered by a hash of the ray, each with a shadow ray.

// What a medium does to a ray: the share of the light from its far end that passes, and the
// light the medium scatters into it.
struct Passage {
    transmittance: f32,
    in_scattered: vec3<f32>,
}

// `Tracer::through_medium`: the passage of the ray from `origin` along `ray_dir`, whose hit is
// at `t_end` (T_FAR: none), through the medium `within` says.
fn through_medium(within: u32, origin: vec3<f32>, ray_dir: vec3<f32>, t_end: f32, counts: ptr<function, Counts>) -> Passage {
    let length = length(ray_dir);
    let dir = ray_dir / length;
    var end = T_FAR;
    if t_end < T_FAR {
        end = t_end * length;
    }
    let inside = within_segment(within, origin, dir, end);
    if !inside.segment.found {
        return Passage(1.0, vec3<f32>(0.0));
    }
    let segment = inside.segment;
    let transmittance = medium_transmittance(inside.medium, segment.end - segment.start);
    return Passage(transmittance, in_scattered(inside.medium, origin, dir, segment, counts));
}

// `Tracer::in_scattered`: the light `medium` scatters towards `origin` from the `segment` of
// the ray along the unit vector `dir`, light by light, each by `fog_steps` stratified samples
// spread as `Spread` says.
fn in_scattered(medium: Medium, origin: vec3<f32>, dir: vec3<f32>, segment: Segment, counts: ptr<function, Counts>) -> vec3<f32> {
    if medium.density == 0.0 {
        return vec3<f32>(0.0);
    }
    let steps = frame.fog_steps;
    let seed_origin = hash_vec3(origin);
    let seed_dir = hash_vec3(dir);
    var gathered = vec3<f32>(0.0);
    for (var index = 0u; index < frame.light_count; index++) {
        let light = lights[index];
        let spread = spread_along(light, origin, dir, segment, medium.density);
        for (var k = 0u; k < steps; k++) {
            // Sample k of the light, jittered inside the k-th of `steps` equal strata.
            let u = jitter(seed_origin, seed_dir, index * steps + k).x;
            let at = spread_at(spread, (f32(k) + u) / f32(steps));
            let point = origin + dir * at.s;
            gathered += at.weight * light_in_medium(light, point, counts);
        }
    }
    return gathered * medium_scattering(medium) * (ISOTROPIC_PHASE / f32(steps));
}

// `Tracer::light_in_medium`: the light of `light` that arrives at `point`, a point in a medium:
// what a shadow ray lets through, dimmed by the fog along it.
fn light_in_medium(light: Light, point: vec3<f32>, counts: ptr<function, Counts>) -> vec3<f32> {
    let sample = light_sample(light, point);
    if all(sample.color == vec3<f32>(0.0)) {
        return vec3<f32>(0.0);
    }
    var passed = vec3<f32>(1.0);
    if (frame.flags & SHADOWS) != 0u {
        (*counts).shadow++;
        passed = shadow_transmittance(point, sample.dir, sample.distance);
    }
    if all(passed == vec3<f32>(0.0)) {
        return vec3<f32>(0.0);
    }
    return passed * dim_by_fog(point, sample).color;
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
    if light.kind != SPOT_LIGHT {
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
