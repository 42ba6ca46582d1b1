// Tori: the twin of src/shapes/torus.rs (`Torus::intersect`, `Torus::crossings`,
// `Torus::surface` and its `Quartic`), in f32 where the Rust solves the quartic in f64.
//
// The quartic is made well conditioned as the Rust makes it: lengths in units of the major
// radius and the ray's origin moved to its point closest to the centre, which leaves
// s⁴ + a2·s² + a1·s + a0 with coefficients of order one however far the ray starts (a quartic
// in t from a far origin has coefficients like |o|⁴ that cancel to nothing in f32). Its roots
// are bracketed as the Rust brackets them, between the turning points, found by Newton steps
// safeguarded with bisection, then polished by Newton's method on the signed distance to the
// tube, which f32 evaluates far better than the quartic near a thin tube.
//
// Moving the origin is where f32 alone loses what matters: the closest point is what is left
// of origin + dir·t0 after the sum cancels, so from 1000 units off a unit torus it would be
// off by 10⁻⁴, and `t` by several units in its last place. So that sum is computed exactly
// (the product split into pieces f32 holds exactly), and `t` is t0 plus a small correction,
// rounded once: the CPU's `t` to about an ulp at any distance.

struct Torus {
    center: vec3<f32>,
    major: f32,
    minor: f32,
}

fn load_torus(first: u32) -> Torus {
    let w = shape_words[first];
    return Torus(w.xyz, w.w, shape_words[first + 1u].x);
}

// `Quartic`: the implicit function along the shifted ray, s⁴ + a2·s² + a1·s + a0.
struct TorusQuartic {
    a2: f32,
    a1: f32,
    a0: f32,
}

// `Quartic::new` for the point `o` closest to the centre, the unit direction `u` and the minor
// radius `minor`, all in units of the major radius.
fn torus_quartic(o: vec3<f32>, u: vec3<f32>, minor: f32) -> TorusQuartic {
    let k = dot(o, o) + 1.0 - minor * minor;
    return TorusQuartic(
        2.0 * k - 4.0 * (u.x * u.x + u.z * u.z),
        -8.0 * (o.x * u.x + o.z * u.z),
        k * k - 4.0 * (o.x * o.x + o.z * o.z),
    );
}

fn torus_quartic_value(q: TorusQuartic, s: f32) -> f32 {
    let s2 = s * s;
    return (s2 + q.a2) * s2 + q.a1 * s + q.a0;
}

fn torus_quartic_derivative(q: TorusQuartic, s: f32) -> f32 {
    return (4.0 * s * s + 2.0 * q.a2) * s + q.a1;
}

// The real cube root.
fn torus_cbrt(x: f32) -> f32 {
    if x == 0.0 {
        return 0.0;
    }
    return copysign(pow(abs(x), 1.0 / 3.0), x);
}

// `Quartic::turning_points`: the real roots of 4s³ + 2·a2·s + a1, smallest first, the first
// `count` of `points`.
struct TorusTurningPoints {
    points: vec3<f32>,
    count: u32,
}

fn torus_turning_points(q: TorusQuartic) -> TorusTurningPoints {
    let p = q.a2 / 2.0;
    let c = q.a1 / 4.0;
    let disc = (c / 2.0) * (c / 2.0) + (p / 3.0) * (p / 3.0) * (p / 3.0);
    if disc > 0.0 || p >= 0.0 {
        // One real root; `w` is chosen so that nothing cancels.
        let w = -copysign(torus_cbrt(abs(c) / 2.0 + sqrt(max(disc, 0.0))), c);
        var point = 0.0;
        if w != 0.0 {
            point = w - p / (3.0 * w);
        }
        return TorusTurningPoints(vec3<f32>(point, 0.0, 0.0), 1u);
    }
    let m = 2.0 * sqrt(-p / 3.0);
    let angle = acos(clamp(3.0 * c / (p * m), -1.0, 1.0)) / 3.0;
    // With the angle in [0, π/3], these three are in increasing order.
    let third = 2.0 * PI / 3.0;
    return TorusTurningPoints(
        m * vec3<f32>(cos(angle - 2.0 * third), cos(angle - third), cos(angle)),
        3u,
    );
}

// `Quartic::root_between`: the root in [a, b], where the quartic is monotone and changes sign
// (`fa` is its value at `a`).
fn torus_root_between(q: TorusQuartic, a_start: f32, fa: f32, b_start: f32) -> f32 {
    var a = a_start;
    var b = b_start;
    let a_positive = fa > 0.0;
    var s = 0.5 * (a + b);
    for (var i = 0; i < 60; i++) {
        let f = torus_quartic_value(q, s);
        if f == 0.0 {
            return s;
        }
        if (f > 0.0) == a_positive {
            a = s;
        } else {
            b = s;
        }
        var next = 0.5 * (a + b);
        let slope = torus_quartic_derivative(q, s);
        if slope != 0.0 {
            let newton = s - f / slope;
            if newton > min(a, b) && newton < max(a, b) {
                next = newton;
            }
        }
        if abs(next - s) <= 1e-7 * (1.0 + abs(s)) {
            return next;
        }
        s = next;
    }
    return s;
}

// x split into two halves of its significand, hi + lo = x exactly, so that the product of
// two halves is exact in f32. The split is by bits: a compiler may rewrite the algebra of
// an error-free sum (lavapipe folds (a + b) − a to b) or not fuse `fma`, but not a mask.
fn torus_split(x: f32) -> vec2<f32> {
    let hi = bitcast<f32>(bitcast<u32>(x) & 0xfffff000u);
    return vec2<f32>(hi, x - hi);
}

// z + x·y where x·y nearly cancels z: the product in exact pieces, the largest added to z
// first, which is exact where they cancel (Sterbenz), so only the small remainder rounds.
fn torus_cancelling_sum(z: f32, x: f32, y: f32) -> f32 {
    let a = torus_split(x);
    let b = torus_split(y);
    return (z + a.x * b.x) + ((a.x * b.y + a.y * b.x) + a.y * b.y);
}

// `s` moved by Newton's steps on the signed distance from o + u·s to the tube's surface,
// |(ρ − 1, y)| − r with ρ the distance from the axis, while they bring it closer to zero. Near
// the surface the quartic is this distance times about 8·r, so at a thin tube or a shallow
// angle its f32 value has lost digits that the distance keeps.
fn torus_polish(o: vec3<f32>, u: vec3<f32>, minor: f32, s_start: f32) -> f32 {
    var s = s_start;
    var distance = torus_tube_distance(o + u * s, minor);
    for (var i = 0; i < 2; i++) {
        let p = o + u * s;
        let rho = length(p.xz);
        let tube = vec2<f32>(rho - 1.0, p.y);
        let tube_len = length(tube);
        if rho == 0.0 || tube_len == 0.0 {
            break;
        }
        let slope = (tube.x * dot(p.xz, u.xz) / rho + tube.y * u.y) / tube_len;
        if slope == 0.0 {
            break;
        }
        let next = s - distance / slope;
        let next_distance = torus_tube_distance(o + u * next, minor);
        if abs(next_distance) >= abs(distance) {
            break;
        }
        s = next;
        distance = next_distance;
    }
    return s;
}

fn torus_tube_distance(p: vec3<f32>, minor: f32) -> f32 {
    return length(vec2<f32>(length(p.xz) - 1.0, p.y)) - minor;
}

// Up to four values of `t`, smallest first: the first `count` of `t`.
struct TorusRoots {
    t: vec4<f32>,
    count: u32,
}

// `Torus::roots`: the first `wanted` roots with `t` in (t_min, t_max), smallest first.
fn torus_roots(tor: Torus, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32, wanted: u32) -> TorusRoots {
    var found = TorusRoots(vec4<f32>(0.0), 0u);
    let start = origin - tor.center;
    let dir_sq = dot(dir, dir);
    if !(dir_sq > 0.0) {
        return found;
    }
    let scale = 1.0 / tor.major;
    let len = sqrt(dir_sq) * scale;
    let minor = tor.minor * scale;
    // The ray is p(s) = o + u·s with u unit and o the point closest to the centre, so o·u = 0
    // and t = t0 + s / len. t0 is taken as f32 gives it and the point there computed as an
    // exact sum, then moved by the small `shift` to the closest point, so that t = t0 +
    // (shift + s / len) rounds once.
    let t0 = -dot(start, dir) / dir_sq;
    let at_t0 = vec3<f32>(
        torus_cancelling_sum(start.x, dir.x, t0),
        torus_cancelling_sum(start.y, dir.y, t0),
        torus_cancelling_sum(start.z, dir.z, t0),
    );
    let shift = -dot(at_t0, dir) / dir_sq;
    let o = (at_t0 + dir * shift) * scale;
    let u = dir / sqrt(dir_sq);
    let quartic = torus_quartic(o, u, minor);
    // Beyond the torus's bounding sphere, grown by 1 %, the quartic is positive.
    let reach = (1.0 + minor) * (1.0 + minor) * 1.01;
    let half_chord_sq = reach - dot(o, o);
    if half_chord_sq <= 0.0 {
        return found;
    }
    let half_chord = sqrt(half_chord_sq);
    let t_closest = t0 + shift;
    var lo = -half_chord;
    if t_min - t_closest > lo / len {
        lo = (t_min - t_closest) * len;
    }
    var hi = half_chord;
    if t_max - t_closest < hi / len {
        hi = (t_max - t_closest) * len;
    }
    if lo >= hi {
        return found;
    }
    let turning = torus_turning_points(quartic);
    var ends = array<f32, 4>(hi, hi, hi, hi);
    var end_count = 0u;
    for (var k = 0u; k < turning.count; k++) {
        let s = turning.points[k];
        if s > lo && s < hi {
            ends[end_count] = s;
            end_count++;
        }
    }
    ends[end_count] = hi;
    var a = lo;
    var fa = torus_quartic_value(quartic, a);
    for (var k = 0u; k <= end_count; k++) {
        let b = ends[k];
        let fb = torus_quartic_value(quartic, b);
        if (fa > 0.0) != (fb > 0.0) {
            let s = torus_polish(o, u, minor, torus_root_between(quartic, a, fa, b));
            let t = t0 + (shift + s / len);
            if t > t_min && t < t_max {
                found.t[found.count] = t;
                found.count++;
                if found.count == wanted {
                    break;
                }
            }
        }
        a = b;
        fa = fb;
    }
    return found;
}

// `Torus::intersect`: the nearest hit with `t` in (t_min, t_max).
fn intersect_torus(tor: Torus, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let roots = torus_roots(tor, origin, dir, t_min, t_max, 1u);
    if roots.count == 0u {
        return no_hit();
    }
    return ShapeHit(roots.t[0], 0u, true);
}

// `Torus::crossings`: every `t`, of any sign, where the line of the ray crosses the surface,
// smallest first, in entry/exit pairs.
fn torus_crossings(tor: Torus, origin: vec3<f32>, dir: vec3<f32>) -> Crossings {
    let roots = torus_roots(tor, origin, dir, -FLOAT_MAX, FLOAT_MAX, 4u);
    return Crossings(roots.t, vec4<u32>(0u), roots.count);
}

// `Torus::surface`: the normal points from the nearest point of the ring out through `p`; u is
// the angle around the ring, v the angle around the tube, starting inside the hole.
fn torus_surface(tor: Torus, p: vec3<f32>, part: u32) -> LocalSurface {
    let q = p - tor.center;
    let radial = vec3<f32>(q.x, 0.0, q.z);
    let radial_len = length(radial);
    var out = vec3<f32>(1.0, 0.0, 0.0);
    if radial_len > 0.0 {
        out = radial / radial_len;
    }
    let tube = q - out * tor.major;
    var normal = out;
    let tube_len = length(tube);
    if tube_len > 0.0 {
        normal = tube / tube_len;
    }
    let u = 0.5 + atan2(q.x, q.z) / (2.0 * PI);
    let v = 0.5 + atan2(q.y, radial_len - tor.major) / (2.0 * PI);
    return LocalSurface(normal, clamp(vec2<f32>(u, v), vec2<f32>(0.0), vec2<f32>(1.0)));
}
