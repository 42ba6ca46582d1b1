// Participating media: the twin of src/medium.rs (`Medium`, `Backdrop::distance`, `Fog::segment`,
// `Fog::transmittance`) and of `Within` in src/whitted/within.rs, which says which medium a ray
// runs through. The fog and its backdrop are the frame's, a material's medium its record's.

// `Medium`: the extinction coefficient per unit length (zero: clear), the share of it that is
// scattering, and the colour of the scattered light.
struct Medium {
    color: vec3<f32>,
    density: f32,
    albedo: f32,
}

// `Medium::transmittance`: the fraction of light that passes `distance` of the medium.
fn medium_transmittance(m: Medium, distance: f32) -> f32 {
    return exp(-m.density * distance);
}

// `Medium::scattering`: the scattering coefficient per colour channel.
fn medium_scattering(m: Medium) -> vec3<f32> {
    return m.density * m.albedo * m.color;
}

// `Fog::medium`: the fog's medium (a density of zero: no fog).
fn fog_medium() -> Medium {
    return Medium(frame.fog_color, frame.fog_density, frame.fog_albedo);
}

// `Segment`: where a ray runs through a medium, from `start` to `end` along a unit direction;
// `found` is false where it runs through none.
struct Segment {
    start: f32,
    end: f32,
    found: bool,
}

// `Backdrop::distance`: how far along the ray from `origin` along the unit vector `dir` the fog's
// backdrop lies; the ball's is where the ray leaves it (its start, if the ray misses it or runs
// away from it).
fn backdrop_distance(origin: vec3<f32>, dir: vec3<f32>) -> f32 {
    if (frame.flags & BALL_BACKDROP) == 0u {
        return frame.backdrop_distance;
    }
    let to_origin = origin - frame.backdrop_center;
    let c = dot(to_origin, to_origin) - frame.backdrop_radius * frame.backdrop_radius;
    let roots = solve_quadratic(1.0, dot(to_origin, dir), c);
    if !roots.found {
        return 0.0;
    }
    return max(roots.t1, 0.0);
}

// `Fog::segment`: the part of the ray from `origin` along the unit vector `dir`, from `start`
// to `end`, that runs through the fog: up to a surface at `end`, or up to the backdrop where
// `end` is T_FAR (no surface).
fn fog_segment(origin: vec3<f32>, dir: vec3<f32>, start: f32, end: f32) -> Segment {
    var until = end;
    if end >= T_FAR {
        until = backdrop_distance(origin, dir);
    }
    return Segment(start, until, start < until);
}

// `Fog::transmittance`: the fraction of light that passes along the ray from `start` to `end`.
fn fog_transmittance(origin: vec3<f32>, dir: vec3<f32>, start: f32, end: f32) -> f32 {
    let segment = fog_segment(origin, dir, start, end);
    if !segment.found {
        return 1.0;
    }
    return medium_transmittance(fog_medium(), segment.end - segment.start);
}

// `Within::after_crossing`: where a ray is after passing through a surface of `material`:
// `entering` the object, in its medium; leaving it, back in the fog.
fn after_crossing(material: u32, entering: bool) -> u32 {
    if !entering {
        return WITHIN_FOG;
    }
    if materials[material].medium_density != 0.0 {
        return material;
    }
    return WITHIN_CLEAR;
}

// A medium and the segment of a ray inside it.
struct InMedium {
    medium: Medium,
    segment: Segment,
}

// `Within::segment`: the medium along the ray from `origin` along the unit vector `dir` up to
// distance `end` (the next surface; T_FAR for none), with the segment of the ray inside it
// (not `found` where there is no medium). Inside an object the segment runs from the origin to
// the next surface; a ray inside an object that finds none has left it.
fn within_segment(within: u32, origin: vec3<f32>, dir: vec3<f32>, end: f32) -> InMedium {
    let none = InMedium(fog_medium(), Segment(0.0, 0.0, false));
    if within == WITHIN_FOG {
        if frame.fog_density == 0.0 {
            return none;
        }
        return InMedium(fog_medium(), fog_segment(origin, dir, 0.0, end));
    }
    if within == WITHIN_CLEAR || end >= T_FAR {
        return none;
    }
    let m = materials[within];
    return InMedium(Medium(m.medium_color, m.medium_density, m.medium_albedo), Segment(0.0, end, true));
}
