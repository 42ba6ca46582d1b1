// The quadratic equation every quadric surface reduces to: the twin of src/shapes/quadratic.rs.

// `x` with the sign bit of `s`, as Rust's `f32::copysign` (which tells −0 from +0).
fn copysign(x: f32, s: f32) -> f32 {
    return bitcast<f32>((bitcast<u32>(x) & 0x7fffffffu) | (bitcast<u32>(s) & 0x80000000u));
}

// Two sorted roots, `t0 <= t1`; `found` is false where there are none.
struct Roots {
    t0: f32,
    t1: f32,
    found: bool,
}

// `solve_quadratic`: the real roots of a·t² + 2·half_b·t + c = 0, smaller first, by the stable
// form q = −(half_b + sign(half_b)·√disc), t = q/a and t = c/q.
fn solve_quadratic(a: f32, half_b: f32, c: f32) -> Roots {
    if a == 0.0 {
        if half_b == 0.0 {
            return Roots(0.0, 0.0, false);
        }
        let t = -c / (2.0 * half_b);
        return Roots(t, t, true);
    }
    let disc = half_b * half_b - a * c;
    if disc < 0.0 {
        return Roots(0.0, 0.0, false);
    }
    let q = -(half_b + copysign(sqrt(disc), half_b));
    if q == 0.0 {
        return Roots(0.0, 0.0, true);
    }
    let t0 = q / a;
    let t1 = c / q;
    if t0 <= t1 {
        return Roots(t0, t1, true);
    }
    return Roots(t1, t0, true);
}

// `first_root_in`: the first of the sorted roots (t0, t1) in (t_min, t_max).
fn first_root_in(t0: f32, t1: f32, t_min: f32, t_max: f32) -> ShapeHit {
    if t0 > t_min && t0 < t_max {
        return ShapeHit(t0, 0u, true);
    }
    if t1 > t_min && t1 < t_max {
        return ShapeHit(t1, 0u, true);
    }
    return no_hit();
}

// `first_root_between_ends`: the ray parameter t = s + shift of the first of the sorted roots
// `s` with t in (t_min, t_max) whose height o_axis + d_axis·s along the shape's axis is in
// [0, height].
fn first_root_between_ends(roots: Roots, shift: f32, t_min: f32, t_max: f32, o_axis: f32, d_axis: f32, height: f32) -> ShapeHit {
    for (var i = 0u; i < 2u; i++) {
        var s = roots.t0;
        if i == 1u {
            s = roots.t1;
        }
        let t = s + shift;
        let z = o_axis + d_axis * s;
        if t > t_min && t < t_max && z >= 0.0 && z <= height {
            return ShapeHit(t, 0u, true);
        }
    }
    return no_hit();
}
