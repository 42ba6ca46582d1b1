//! The quadratic equation every quadric surface reduces to, solved without catastrophic
//! cancellation.

use glam::Vec4;

/// Real roots of `a·t² + 2·half_b·t + c = 0`, smaller first. Uses the stable form
/// `q = −(half_b + sign(half_b)·√disc)`, `t = q/a` and `t = c/q`, so neither root loses
/// precision when `half_b² ≫ a·c`.
#[inline]
pub fn solve_quadratic(a: f32, half_b: f32, c: f32) -> Option<(f32, f32)> {
    if a == 0.0 {
        if half_b == 0.0 {
            return None;
        }
        let t = -c / (2.0 * half_b);
        return Some((t, t));
    }
    let disc = half_b * half_b - a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -(half_b + disc.sqrt().copysign(half_b));
    if q == 0.0 {
        return Some((0.0, 0.0));
    }
    let (t0, t1) = (q / a, c / q);
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

/// [`solve_quadratic`]'s two roots where `a ≠ 0` and `disc = half_b² − a·c ≥ 0`, for four
/// equations at once (one per SIMD lane), in the same arithmetic: smaller first, both 0 where
/// `q` is. The packs of shapes use it.
#[inline(always)]
pub fn sorted_roots4(a: Vec4, half_b: Vec4, c: Vec4, disc: Vec4) -> (Vec4, Vec4) {
    let q = -(half_b + disc.sqrt().copysign(half_b));
    let (t0, t1) = (q / a, c / q);
    let in_order = t0.cmple(t1);
    let q_is_zero = q.cmpeq(Vec4::ZERO);
    let near = Vec4::select(in_order, t0, t1);
    let far = Vec4::select(in_order, t1, t0);
    (
        Vec4::select(q_is_zero, Vec4::ZERO, near),
        Vec4::select(q_is_zero, Vec4::ZERO, far),
    )
}

/// The first of two sorted roots in `(t_min, t_max)`.
#[inline]
pub fn first_root_in((t0, t1): (f32, f32), t_min: f32, t_max: f32) -> Option<f32> {
    if t0 > t_min && t0 < t_max {
        Some(t0)
    } else if t1 > t_min && t1 < t_max {
        Some(t1)
    } else {
        None
    }
}

/// The ray parameter `t = s + shift` of the first of two sorted roots `s` with `t` in
/// `(t_min, t_max)` whose point lies between the end planes of a bounded quadric: its height
/// `o_axis + d_axis·s` along the shape's axis is in `[0, height]`.
#[inline]
pub fn first_root_between_ends(
    (s0, s1): (f32, f32),
    shift: f32,
    t_min: f32,
    t_max: f32,
    (o_axis, d_axis): (f32, f32),
    height: f32,
) -> Option<f32> {
    [s0, s1]
        .into_iter()
        .map(|s| (s + shift, o_axis + d_axis * s))
        .find_map(|(t, z)| (t > t_min && t < t_max && (0.0..=height).contains(&z)).then_some(t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_a_simple_quadratic() {
        // (t − 1)(t − 3) = t² − 4t + 3
        assert_eq!(solve_quadratic(1.0, -2.0, 3.0), Some((1.0, 3.0)));
    }

    #[test]
    fn no_real_roots() {
        assert_eq!(solve_quadratic(1.0, 0.0, 1.0), None);
    }

    #[test]
    fn small_root_keeps_precision() {
        // t² − 2e4·t + 1: roots ≈ 5e-5 and 2e4; the naive formula returns 0 for the small one.
        let (t0, t1) = solve_quadratic(1.0, -1e4, 1.0).unwrap();
        assert!((t0 - 5e-5).abs() < 1e-9, "{t0}");
        assert!((t1 - 2e4).abs() < 1.0, "{t1}");
    }
}
