//! Tori: a tube of radius `minor_radius` swept around a ring of radius `major_radius`, the ring
//! lying in the plane through `center` perpendicular to the y axis.
//!
//! A ray meets a torus where a quartic in `t` vanishes. The quartic is solved in `f64`, made well
//! conditioned first: lengths are measured in units of the major radius, and the ray's origin
//! is moved to the point of the ray closest to the centre, which leaves a quartic without a
//! cubic term and with coefficients of order one at any scale. Its roots are then found by
//! cutting the ray at the quartic's turning points (the roots of its derivative, a cubic solved
//! in closed form) into pieces on which it is monotone, and finding the one root in each piece
//! whose ends differ in sign by Newton's method safeguarded with bisection. No root is lost to a
//! negative discriminant at grazing angles, and the crossings always come in entry/exit pairs.

use std::f32::consts::TAU;
use std::f64::consts::TAU as TAU_F64;

use arrayvec::ArrayVec;
use glam::{DVec3, Vec2, Vec3};

use super::{LocalSurface, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Torus {
    pub center: Vec3,
    /// The radius of the ring the tube goes round.
    pub major_radius: f32,
    /// The radius of the tube.
    pub minor_radius: f32,
}

impl Torus {
    /// A torus; both radii must be positive numbers and the tube must not reach the axis
    /// (`minor_radius < major_radius`): a horn or spindle torus is not a simple solid.
    pub fn new(center: Vec3, major_radius: f32, minor_radius: f32) -> Result<Torus, String> {
        if !center.is_finite() {
            return Err(format!("torus centre must be finite, got {center}"));
        }
        for (name, radius) in [("major", major_radius), ("minor", minor_radius)] {
            if !(radius.is_finite() && radius > 0.0) {
                return Err(format!(
                    "torus {name}_radius must be a positive number, got {radius}"
                ));
            }
        }
        if minor_radius >= major_radius {
            return Err(format!(
                "torus minor_radius ({minor_radius}) must be less than major_radius \
                 ({major_radius}): a tube that reaches the axis makes a horn or spindle torus, \
                 which is not supported"
            ));
        }
        Ok(Torus {
            center,
            major_radius,
            minor_radius,
        })
    }

    /// The nearest hit with `t` in the open interval `(t_min, t_max)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let t = *self.roots(ray, t_min, t_max, 1).first()?;
        Some(ShapeHit { t, part: 0 })
    }

    /// Every `t`, of any sign, where the line of `ray` crosses the surface, smallest first. They
    /// come in pairs, entry then exit; a ray touching the surface gives a pair of equal values.
    pub fn crossings(&self, ray: &Ray) -> ArrayVec<f32, 4> {
        self.roots(ray, f32::NEG_INFINITY, f32::INFINITY, 4)
    }

    /// The first `count` roots with `t` in `(t_min, t_max)`, smallest first.
    fn roots(&self, ray: &Ray, t_min: f32, t_max: f32, count: usize) -> ArrayVec<f32, 4> {
        let mut found = ArrayVec::new();
        let scale = 1.0 / f64::from(self.major_radius);
        let origin = (ray.origin - self.center).as_dvec3() * scale;
        let dir = ray.dir.as_dvec3() * scale;
        let len = dir.length();
        if !(len > 0.0 && len.is_finite() && origin.is_finite()) {
            return found;
        }
        // The ray is p(s) = o + u·s with u unit and o the point closest to the centre, so
        // o·u = 0 and t = t0 + s / len.
        let u = dir / len;
        let t0 = -origin.dot(u) / len;
        let o = origin + u * (t0 * len);
        let quartic = Quartic::new(o, u, f64::from(self.minor_radius) * scale);
        // Beyond the torus's bounding sphere, grown by 1 %, the quartic is positive.
        let reach = (1.0 + f64::from(self.minor_radius) * scale).powi(2) * 1.01;
        let half_chord_sq = reach - o.length_squared();
        if half_chord_sq <= 0.0 {
            return found;
        }
        let half_chord = half_chord_sq.sqrt();
        let lo = ((f64::from(t_min) - t0) * len).max(-half_chord);
        let hi = ((f64::from(t_max) - t0) * len).min(half_chord);
        if lo >= hi {
            return found;
        }
        let mut ends: ArrayVec<f64, 5> = ArrayVec::new();
        ends.push(lo);
        ends.extend(
            quartic
                .turning_points()
                .into_iter()
                .filter(|&s| s > lo && s < hi),
        );
        ends.push(hi);
        let mut a = lo;
        let mut fa = quartic.value(a);
        for &b in &ends[1..] {
            let fb = quartic.value(b);
            if (fa > 0.0) != (fb > 0.0) {
                let t = (t0 + quartic.root_between(a, fa, b) / len) as f32;
                if t > t_min && t < t_max {
                    found.push(t);
                    if found.len() == count {
                        break;
                    }
                }
            }
            (a, fa) = (b, fb);
        }
        found
    }

    /// The normal points from the nearest point of the ring out through `p`; `u` is the angle
    /// around the ring (as a sphere's `u`), `v` the angle around the tube, starting inside the
    /// hole and passing the top at 0.75.
    pub fn surface(&self, p: Vec3, _part: u32) -> LocalSurface {
        let q = p - self.center;
        let radial = Vec3::new(q.x, 0.0, q.z);
        let out = radial.normalize_or(Vec3::X);
        let normal = (q - out * self.major_radius).normalize_or(out);
        let u = 0.5 + q.x.atan2(q.z) / TAU;
        let v = 0.5 + q.y.atan2(radial.length() - self.major_radius) / TAU;
        LocalSurface {
            normal,
            uv: Vec2::new(u, v).clamp(Vec2::ZERO, Vec2::ONE),
        }
    }

    pub fn bounds(&self) -> Aabb {
        let outer = self.major_radius + self.minor_radius;
        let half = Vec3::new(outer, self.minor_radius, outer);
        Aabb::new(self.center - half, self.center + half)
    }
}

/// The torus's implicit function along a ray, `(|p|² + 1 − r²)² − 4·(p_x² + p_z²)` at
/// `p = o + u·s` (major radius 1, `o·u = 0`, `|u| = 1`): `s⁴ + a2·s² + a1·s + a0`.
struct Quartic {
    a2: f64,
    a1: f64,
    a0: f64,
}

impl Quartic {
    fn new(o: DVec3, u: DVec3, minor: f64) -> Quartic {
        let k = o.length_squared() + 1.0 - minor * minor;
        Quartic {
            a2: 2.0 * k - 4.0 * (u.x * u.x + u.z * u.z),
            a1: -8.0 * (o.x * u.x + o.z * u.z),
            a0: k * k - 4.0 * (o.x * o.x + o.z * o.z),
        }
    }

    fn value(&self, s: f64) -> f64 {
        let s2 = s * s;
        (s2 + self.a2) * s2 + self.a1 * s + self.a0
    }

    fn derivative(&self, s: f64) -> f64 {
        (4.0 * s * s + 2.0 * self.a2) * s + self.a1
    }

    /// The real roots of the derivative `4s³ + 2·a2·s + a1`, i.e. of the depressed cubic
    /// `s³ + p·s + q`, in closed form (Cardano's formula for one root, the trigonometric one
    /// for three).
    fn turning_points(&self) -> ArrayVec<f64, 3> {
        let (p, q) = (self.a2 / 2.0, self.a1 / 4.0);
        let disc = (q / 2.0).powi(2) + (p / 3.0).powi(3);
        let mut points = ArrayVec::new();
        if disc > 0.0 || p >= 0.0 {
            // One real root; `w` is chosen so that nothing cancels.
            let w = -(q.abs() / 2.0 + disc.max(0.0).sqrt()).cbrt().copysign(q);
            points.push(if w == 0.0 { 0.0 } else { w - p / (3.0 * w) });
        } else {
            let m = 2.0 * (-p / 3.0).sqrt();
            let angle = (3.0 * q / (p * m)).clamp(-1.0, 1.0).acos() / 3.0;
            let mut three = [0.0, 1.0, 2.0].map(|k| m * (angle - TAU_F64 * k / 3.0).cos());
            three.sort_by(f64::total_cmp);
            points.extend(three);
        }
        points
    }

    /// The root in `[a, b]`, where the quartic is monotone and changes sign (`fa` is its value
    /// at `a`): Newton steps, falling back to bisection whenever a step leaves the bracket.
    fn root_between(&self, mut a: f64, fa: f64, mut b: f64) -> f64 {
        let a_positive = fa > 0.0;
        let mut s = 0.5 * (a + b);
        for _ in 0..100 {
            let f = self.value(s);
            if f == 0.0 {
                return s;
            }
            if (f > 0.0) == a_positive {
                a = s;
            } else {
                b = s;
            }
            let newton = s - f / self.derivative(s);
            let next = if newton > a.min(b) && newton < a.max(b) {
                newton
            } else {
                0.5 * (a + b)
            };
            if (next - s).abs() <= 1e-14 * (1.0 + s.abs()) {
                return next;
            }
            s = next;
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    const CENTER: Vec3 = Vec3::new(1.0, 2.0, 3.0);

    /// Ring radius 2, tube radius 0.5, around (1, 2, 3).
    fn torus() -> Torus {
        Torus::new(CENTER, 2.0, 0.5).unwrap()
    }

    fn assert_crossings(ray: &Ray, expected: &[f32], tolerance: f32) {
        let found = torus().crossings(ray);
        assert_eq!(found.len(), expected.len(), "{found:?} vs {expected:?}");
        for (f, e) in found.iter().zip(expected) {
            assert!((f - e).abs() <= tolerance, "{found:?} vs {expected:?}");
        }
    }

    #[test]
    fn refuses_bad_radii() {
        assert!(Torus::new(Vec3::ZERO, 1.0, 0.999).is_ok());
        for (major, minor, word) in [
            (0.0, 0.5, "major_radius must be a positive"),
            (1.0, -0.5, "minor_radius must be a positive"),
            (f32::NAN, 0.5, "major_radius"),
            (1.0, f32::INFINITY, "minor_radius"),
            (1.0, 1.0, "less than major_radius"),
            (1.0, 2.0, "spindle"),
        ] {
            let error = Torus::new(Vec3::ZERO, major, minor).unwrap_err();
            assert!(error.contains(word), "{error}");
        }
        assert!(Torus::new(Vec3::NAN, 1.0, 0.5).is_err());
    }

    #[test]
    fn ray_through_the_middle_crosses_four_times() {
        let ray = Ray::new(CENTER - Vec3::X * 10.0, Vec3::X);
        assert_crossings(&ray, &[7.5, 8.5, 11.5, 12.5], 1e-5);
        assert_eq!(
            torus().intersect(&ray, 8.0, 20.0),
            Some(ShapeHit { t: 8.5, part: 0 })
        );
        assert_eq!(torus().intersect(&ray, 12.5, 20.0), None);
        // The crossings are along the whole line, behind the origin too.
        let backwards = Ray::new(CENTER + Vec3::X * 10.0, Vec3::X * 2.0);
        assert_crossings(&backwards, &[-6.25, -5.75, -4.25, -3.75], 1e-5);
        assert_eq!(torus().intersect(&backwards, 0.0, f32::INFINITY), None);
    }

    #[test]
    fn rays_along_the_axis() {
        let through_hole = Ray::new(CENTER + Vec3::Y * 5.0, -Vec3::Y);
        assert!(torus().crossings(&through_hole).is_empty());
        let through_tube = Ray::new(CENTER + Vec3::new(2.0, 5.0, 0.0), -Vec3::Y);
        assert_crossings(&through_tube, &[4.5, 5.5], 1e-5);
        let s = torus().surface(through_tube.at(4.5), 0);
        assert_near(s.normal, Vec3::Y, 1e-5);
        assert_near(s.uv.extend(0.0), Vec3::new(0.75, 0.75, 0.0), 1e-5);
    }

    #[test]
    fn ray_from_inside_the_tube_hits_its_wall() {
        let ray = Ray::new(CENTER + Vec3::new(0.0, 0.0, 2.0), Vec3::new(0.0, 1.0, 1.0));
        let h = torus().intersect(&ray, 1e-4, f32::INFINITY).unwrap();
        let p = ray.at(h.t) - CENTER;
        let tube = Vec2::new(Vec2::new(p.x, p.z).length() - 2.0, p.y).length();
        assert!((tube - 0.5).abs() < 1e-5, "{p}");
        assert!((h.t - 0.5 / 2f32.sqrt()).abs() < 1e-5, "{h:?}");
    }

    #[test]
    fn grazing_the_top_of_the_tube() {
        // The plane y = 0.5 touches the tube along a circle; a ray in it touches twice.
        let at = |dy: f32| Ray::new(CENTER + Vec3::new(-10.0, 0.5 + dy, 0.0), Vec3::X);
        let touching = torus().crossings(&at(-1e-5));
        assert_eq!(touching.len(), 4, "{touching:?}");
        assert!((touching[0] - 8.0).abs() < 1e-2 && (touching[3] - 12.0).abs() < 1e-2);
        assert!(touching[0] < touching[1] && touching[2] < touching[3]);
        assert!(torus().crossings(&at(1e-5)).is_empty());
        // Exactly tangent, rounding decides whether the touch counts, but never half of it.
        assert!(torus().crossings(&at(0.0)).len().is_multiple_of(2));
    }

    #[test]
    fn grazing_the_outer_silhouette() {
        let at = |dz: f32| Ray::new(CENTER + Vec3::new(-10.0, 0.0, 2.5 + dz), Vec3::X);
        let touching = torus().crossings(&at(-1e-5));
        assert_eq!(touching.len(), 2, "{touching:?}");
        assert!((touching[0] - 10.0).abs() < 1e-2 && touching[0] < touching[1]);
        assert!(torus().crossings(&at(1e-5)).is_empty());
        assert!(torus().crossings(&at(0.0)).len().is_multiple_of(2));
    }

    #[test]
    fn grazing_the_inner_equator() {
        // The line x = 1.5 (relative to the centre) touches the inner equator from inside the
        // tube: four crossings with a double one in the middle; just inside the hole the middle
        // pair comes apart, and just into the tube it goes away.
        let at = |dx: f32| Ray::new(CENTER + Vec3::new(1.5 + dx, 0.0, -10.0), Vec3::Z);
        let touching = torus().crossings(&at(0.0));
        assert!(touching.len() == 2 || touching.len() == 4, "{touching:?}");
        let in_hole = torus().crossings(&at(-1e-4));
        assert_eq!(in_hole.len(), 4, "{in_hole:?}");
        assert!(in_hole[1] < in_hole[2], "{in_hole:?}");
        assert!((in_hole[1] - 10.0).abs() < 2e-2 && (in_hole[2] - 10.0).abs() < 2e-2);
        assert_eq!(torus().crossings(&at(1e-4)).len(), 2);
    }

    #[test]
    fn tiny_and_huge_tori_are_hit_alike() {
        for scale in [1e-3, 1.0, 1e3] {
            let torus = Torus::new(CENTER * scale, 2.0 * scale, 0.5 * scale).unwrap();
            let ray = Ray::new(
                (CENTER + Vec3::new(-10.0, 0.3, 0.1)) * scale,
                Vec3::new(1.0, 0.0, 0.0),
            );
            // The ray crosses the tube where the distance from the axis is 2 ± √(0.25 − 0.3²).
            let x = |rho: f32| (rho * rho - 0.01).sqrt();
            let expected =
                [10.0 - x(2.4), 10.0 - x(1.6), 10.0 + x(1.6), 10.0 + x(2.4)].map(|t| t * scale);
            let found = torus.crossings(&ray);
            assert_eq!(found.len(), 4, "scale {scale}: {found:?}");
            for (f, e) in found.iter().zip(expected) {
                assert!((f - e).abs() < 1e-5 * scale, "scale {scale}: {found:?}");
            }
        }
    }

    #[test]
    fn surface_normal_and_uv() {
        let t = torus();
        let outer = t.surface(CENTER + Vec3::Z * 2.5, 0);
        assert_near(outer.normal, Vec3::Z, 1e-6);
        assert_near(outer.uv.extend(0.0), Vec3::new(0.5, 0.5, 0.0), 1e-6);
        let inner = t.surface(CENTER + Vec3::X * 1.5, 0);
        assert_near(inner.normal, -Vec3::X, 1e-6);
        assert_near(inner.uv.extend(0.0), Vec3::new(0.75, 1.0, 0.0), 1e-6);
        let bottom = t.surface(CENTER + Vec3::new(0.0, -0.5, -2.0), 0);
        assert_near(bottom.normal, -Vec3::Y, 1e-6);
        assert_near(bottom.uv.extend(0.0), Vec3::new(1.0, 0.25, 0.0), 1e-6);
    }

    #[test]
    fn bounds_hold_the_tube() {
        let b = torus().bounds();
        assert_eq!(b.min, CENTER - Vec3::new(2.5, 0.5, 2.5));
        assert_eq!(b.max, CENTER + Vec3::new(2.5, 0.5, 2.5));
    }

    #[test]
    fn turned_upright_in_the_world() {
        // A unit-ring torus turned about x so that its axis is z, moved to z = 5.
        let steps = [
            TransformStep::Rotate {
                axis: Vec3::X,
                degrees: 90.0,
            },
            TransformStep::Translate(Vec3::new(0.0, 0.0, 5.0)),
        ];
        let shape = Shape::Torus(Torus::new(Vec3::ZERO, 1.0, 0.25).unwrap());
        let through_hole = Ray::new(Vec3::ZERO, Vec3::Z);
        assert!(hit_in_world(shape.clone(), &steps, &through_hole).is_none());
        let through_tube = Ray::new(Vec3::new(1.0, 0.0, 0.0), Vec3::Z);
        let (h, s) = hit_in_world(shape, &steps, &through_tube).unwrap();
        assert!((h.t - 4.75).abs() < 1e-5, "{h:?}");
        assert_near(s.normal, -Vec3::Z, 1e-5);
    }
}
