//! Tapered cylinders (Hill & Kelley's name for a cylinder whose radius changes linearly along
//! its axis): cylinders, cones and truncated cones about any axis, optionally closed by disks.

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};

use super::quadratic::{first_root_between_ends, solve_quadratic};
use super::{LocalSurface, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;

/// The surface swept by a circle moving from `base` to `top` while its radius changes linearly
/// from `base_radius` to `top_radius`. Work is done in a local frame: `z` along the axis (0 at
/// the base, `height` at the top), `x` and `y` across it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TaperedCylinder {
    pub(crate) base: Vec3,
    /// Unit vectors of the local frame (right-handed: `frame_x × frame_y = axis`).
    pub(crate) frame_x: Vec3,
    pub(crate) frame_y: Vec3,
    pub(crate) axis: Vec3,
    pub(crate) height: f32,
    pub(crate) base_radius: f32,
    pub(crate) top_radius: f32,
    /// Change of radius per unit of height.
    pub(crate) slope: f32,
    capped: bool,
}

impl TaperedCylinder {
    // The part numbers of a tapered cylinder's surface.
    pub const SIDE: u32 = 0;
    pub const BASE_CAP: u32 = 1;
    pub const TOP_CAP: u32 = 2;

    pub fn new(
        base: Vec3,
        top: Vec3,
        base_radius: f32,
        top_radius: f32,
        capped: bool,
    ) -> Result<TaperedCylinder, String> {
        if !base.is_finite() || !top.is_finite() {
            return Err(format!(
                "cylinder ends must be finite, got {base} and {top}"
            ));
        }
        if !base_radius.is_finite() || !top_radius.is_finite() {
            return Err(format!(
                "cylinder radii must be finite, got {base_radius} and {top_radius}"
            ));
        }
        if base_radius < 0.0 || top_radius < 0.0 {
            return Err(format!(
                "cylinder radii must not be negative, got {base_radius} and {top_radius}"
            ));
        }
        if base_radius == 0.0 && top_radius == 0.0 {
            return Err("cylinder radii must not both be zero".to_string());
        }
        let height = (top - base).length();
        let axis = (top - base).try_normalize().ok_or_else(|| {
            format!("cylinder axis must have a finite, non-zero length, got {base} to {top}")
        })?;
        let slope = (top_radius - base_radius) / height;
        if !(slope * slope).is_finite() {
            return Err(format!(
                "cylinder is too short ({height}) for its change of radius"
            ));
        }
        let frame_x = axis.any_orthonormal_vector();
        Ok(TaperedCylinder {
            base,
            frame_x,
            frame_y: axis.cross(frame_x),
            axis,
            height,
            base_radius,
            top_radius,
            slope,
            capped,
        })
    }

    /// Whether the ends are closed by disks.
    pub fn is_capped(&self) -> bool {
        self.capped
    }

    /// `p` in the local frame.
    #[inline]
    fn local_point(&self, p: Vec3) -> Vec3 {
        let rel = p - self.base;
        Vec3::new(
            rel.dot(self.frame_x),
            rel.dot(self.frame_y),
            rel.dot(self.axis),
        )
    }

    /// The nearest of the side (`x² + y² = (r₀ + slope·z)²` for `0 ≤ z ≤ height`) and, when
    /// capped, the end disks.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let d = Vec3::new(
            ray.dir.dot(self.frame_x),
            ray.dir.dot(self.frame_y),
            ray.dir.dot(self.axis),
        );
        // Work from the point `o` of the ray nearest the middle of the axis, with `s = t − shift`
        // along the ray from there: the quadratic's coefficients then stay as small as the
        // cylinder, and so do their rounding errors (the sphere's trick, made general).
        let origin = self.local_point(ray.origin);
        let shift = (Vec3::new(0.0, 0.0, 0.5 * self.height) - origin).dot(d) / d.length_squared();
        if !shift.is_finite() {
            return None; // no direction
        }
        let o = origin + d * shift;
        let mut nearest = None;
        let mut t_far = t_max;

        let radius_at_o = self.base_radius + self.slope * o.z;
        let a = d.x * d.x + d.y * d.y - self.slope * self.slope * d.z * d.z;
        let half_b = o.x * d.x + o.y * d.y - self.slope * radius_at_o * d.z;
        let c = o.x * o.x + o.y * o.y - radius_at_o * radius_at_o;
        let roots = solve_quadratic(a, half_b, c);
        let side = roots
            .and_then(|r| first_root_between_ends(r, shift, t_min, t_far, (o.z, d.z), self.height));
        if let Some(t) = side {
            nearest = Some(ShapeHit {
                t,
                part: TaperedCylinder::SIDE,
            });
            t_far = t;
        }

        if self.capped && d.z != 0.0 {
            let caps = [
                (0.0, self.base_radius, TaperedCylinder::BASE_CAP),
                (self.height, self.top_radius, TaperedCylinder::TOP_CAP),
            ];
            for (z, radius, part) in caps {
                if radius == 0.0 {
                    continue; // a cone's apex
                }
                let s = (z - o.z) / d.z;
                let t = s + shift;
                if t > t_min && t < t_far {
                    let x = o.x + d.x * s;
                    let y = o.y + d.y * s;
                    if x * x + y * y <= radius * radius {
                        nearest = Some(ShapeHit { t, part });
                        t_far = t;
                    }
                }
            }
        }
        nearest
    }

    /// The outward normal at `p` on part `part` (not of unit length on the side).
    pub fn normal(&self, p: Vec3, part: u32) -> Vec3 {
        match part {
            TaperedCylinder::BASE_CAP => -self.axis,
            TaperedCylinder::TOP_CAP => self.axis,
            _ => {
                // The gradient of `√(x² + y²) − r₀ − slope·z`; at a cone's apex the radial
                // direction is undefined and any one will do.
                let local = self.local_point(p);
                let radial = Vec2::new(local.x, local.y).normalize_or(Vec2::X);
                self.frame_x * radial.x + self.frame_y * radial.y - self.axis * self.slope
            }
        }
    }

    /// The side maps cylindrically (`u` the angle around the axis over 2π, `v` the fraction of
    /// the height); each cap maps its disk onto `[0, 1]²`, the right way round seen from outside.
    pub fn surface(&self, p: Vec3, part: u32) -> LocalSurface {
        let local = self.local_point(p);
        let uv = match part {
            TaperedCylinder::BASE_CAP => disk_uv(Vec2::new(-local.x, local.y), self.base_radius),
            TaperedCylinder::TOP_CAP => disk_uv(Vec2::new(local.x, local.y), self.top_radius),
            _ => {
                let u = 0.5 + local.y.atan2(local.x) / TAU;
                let v = (local.z / self.height).clamp(0.0, 1.0);
                Vec2::new(u, v)
            }
        };
        LocalSurface {
            normal: self.normal(p, part),
            uv,
        }
    }

    /// The box around the two end circles: a circle of radius `r` about a unit axis `a` reaches
    /// `r·√(1 − aᵢ²)` along world axis `i`.
    pub fn bounds(&self) -> Aabb {
        let reach = (Vec3::ONE - self.axis * self.axis)
            .max(Vec3::ZERO)
            .map(f32::sqrt);
        let top = self.base + self.axis * self.height;
        Aabb::from_points([
            self.base - reach * self.base_radius,
            self.base + reach * self.base_radius,
            top - reach * self.top_radius,
            top + reach * self.top_radius,
        ])
    }
}

/// Texture coordinates of the point `q` (in the disk's plane, from its centre) on a disk of
/// radius `radius`, mapped onto `[0, 1]²`.
pub(crate) fn disk_uv(q: Vec2, radius: f32) -> Vec2 {
    let scale = if radius > 0.0 { 0.5 / radius } else { 0.0 };
    (Vec2::splat(0.5) + q * scale).clamp(Vec2::ZERO, Vec2::ONE)
}

#[cfg(test)]
mod tests {
    use std::f32::consts::FRAC_1_SQRT_2;

    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    /// Radius 1, from y = 0 to y = 2.
    fn cylinder(capped: bool) -> TaperedCylinder {
        TaperedCylinder::new(Vec3::ZERO, Vec3::new(0.0, 2.0, 0.0), 1.0, 1.0, capped).unwrap()
    }

    /// Base radius 1 at y = 0, apex at y = 1.
    fn cone(capped: bool) -> TaperedCylinder {
        TaperedCylinder::new(Vec3::ZERO, Vec3::Y, 1.0, 0.0, capped).unwrap()
    }

    fn hit(shape: &TaperedCylinder, ray: &Ray) -> Option<ShapeHit> {
        shape.intersect(ray, 1e-4, f32::INFINITY)
    }

    #[test]
    fn side_hit_of_a_cylinder() {
        let c = cylinder(false);
        let ray = Ray::new(Vec3::new(5.0, 1.0, 0.0), Vec3::new(-2.0, 0.0, 0.0));
        let h = hit(&c, &ray).unwrap();
        assert_eq!(h.part, TaperedCylinder::SIDE);
        assert!((h.t - 2.0).abs() < 1e-6);
        let p = ray.at(h.t);
        assert_near(p, Vec3::new(1.0, 1.0, 0.0), 1e-6);
        let s = c.surface(p, h.part);
        assert_near(s.normal.normalize(), Vec3::X, 1e-6);
        assert!((s.uv.y - 0.5).abs() < 1e-6);
    }

    #[test]
    fn side_hit_of_a_cone_has_a_sloped_normal() {
        let c = cone(false);
        let ray = Ray::new(Vec3::new(5.0, 0.5, 0.0), Vec3::new(-1.0, 0.0, 0.0));
        let h = hit(&c, &ray).unwrap();
        assert!((h.t - 4.5).abs() < 1e-6);
        let p = ray.at(h.t);
        assert_near(p, Vec3::new(0.5, 0.5, 0.0), 1e-6);
        let n = c.surface(p, h.part).normal.normalize();
        assert_near(n, Vec3::new(FRAC_1_SQRT_2, FRAC_1_SQRT_2, 0.0), 1e-6);
    }

    #[test]
    fn upside_down_cone_and_truncated_cone() {
        // Apex at the base: radius 0 at y = 0, 1 at y = 1.
        let funnel = TaperedCylinder::new(Vec3::ZERO, Vec3::Y, 0.0, 1.0, true).unwrap();
        let ray = Ray::new(Vec3::new(5.0, 0.5, 0.0), -Vec3::X);
        let p = ray.at(hit(&funnel, &ray).unwrap().t);
        assert_near(p, Vec3::new(0.5, 0.5, 0.0), 1e-6);
        let n = funnel.surface(p, TaperedCylinder::SIDE).normal.normalize();
        assert_near(n, Vec3::new(FRAC_1_SQRT_2, -FRAC_1_SQRT_2, 0.0), 1e-6);

        // Radius 2 at y = 0 to 1 at y = 2: radius 1.5 at y = 1.
        let frustum =
            TaperedCylinder::new(Vec3::ZERO, Vec3::new(0.0, 2.0, 0.0), 2.0, 1.0, false).unwrap();
        let ray = Ray::new(Vec3::new(0.0, 1.0, -5.0), Vec3::Z);
        assert!((hit(&frustum, &ray).unwrap().t - 3.5).abs() < 1e-6);
    }

    #[test]
    fn caps_are_hit_when_capped() {
        let down = Ray::new(Vec3::new(0.5, 5.0, 0.0), Vec3::new(0.0, -2.0, 0.0));
        let h = hit(&cylinder(true), &down).unwrap();
        assert_eq!(
            h,
            ShapeHit {
                t: 1.5,
                part: TaperedCylinder::TOP_CAP
            }
        );
        let s = cylinder(true).surface(down.at(h.t), h.part);
        assert_eq!(s.normal, Vec3::Y);
        let up = Ray::new(Vec3::new(0.5, -5.0, 0.0), Vec3::Y);
        let h = hit(&cylinder(true), &up).unwrap();
        assert_eq!(
            h,
            ShapeHit {
                t: 5.0,
                part: TaperedCylinder::BASE_CAP
            }
        );
        assert_eq!(cylinder(true).surface(up.at(h.t), h.part).normal, -Vec3::Y);
        // Open, the same ray passes down the tube.
        assert_eq!(hit(&cylinder(false), &down), None);
    }

    #[test]
    fn a_cone_has_no_cap_at_its_apex() {
        let up = Ray::new(Vec3::new(0.0, -5.0, 0.0), Vec3::Y);
        assert_eq!(
            hit(&cone(true), &up).unwrap().part,
            TaperedCylinder::BASE_CAP
        );
        // From above, the ray meets the apex of the side.
        let down = Ray::new(Vec3::new(0.25, 5.0, 0.0), -Vec3::Y);
        let h = hit(&cone(true), &down).unwrap();
        assert_eq!(h.part, TaperedCylinder::SIDE);
        assert!((h.t - 4.25).abs() < 1e-5);
    }

    #[test]
    fn ray_from_inside_hits_the_exit() {
        let ray = Ray::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(0.0, 0.0, 3.0));
        let h = hit(&cylinder(true), &ray).unwrap();
        assert_eq!(h.part, TaperedCylinder::SIDE);
        assert!((h.t - 1.0 / 3.0).abs() < 1e-6);
        let up = Ray::new(Vec3::new(0.2, 1.0, 0.0), Vec3::Y);
        assert_eq!(
            hit(&cylinder(true), &up),
            Some(ShapeHit {
                t: 1.0,
                part: TaperedCylinder::TOP_CAP
            })
        );
        // A ray leaving the side from a point on it does not hit it again.
        let out = Ray::new(Vec3::new(1.0, 1.0, 0.0), Vec3::new(1.0, 0.3, 0.2));
        assert_eq!(hit(&cylinder(true), &out), None);
    }

    #[test]
    fn misses_and_tangents() {
        let c = cylinder(true);
        let above = Ray::new(Vec3::new(5.0, 2.5, 0.0), -Vec3::X);
        let beside = Ray::new(Vec3::new(5.0, 1.0, 1.001), -Vec3::X);
        let along_axis_outside = Ray::new(Vec3::new(1.5, -5.0, 0.0), Vec3::Y);
        for ray in [above, beside, along_axis_outside] {
            assert_eq!(hit(&c, &ray), None, "{ray:?}");
        }
        // Touching the side along the line x = 0, z = 1: a double root, no NaN.
        let tangent = Ray::new(Vec3::new(5.0, 1.0, 1.0), -Vec3::X);
        let h = hit(&c, &tangent).unwrap();
        assert!((h.t - 5.0).abs() < 1e-3, "{h:?}");
        assert!(c.surface(tangent.at(h.t), h.part).normal.is_finite());
        // Parallel to a line of the cone (45° to its axis), through its side once at
        // (0.5, 0.5, 0): the quadratic turns linear.
        let along_slope = Ray::new(Vec3::new(0.5, -1.5, -2.0), Vec3::new(0.0, 1.0, 1.0));
        let h = hit(&cone(false), &along_slope).unwrap();
        assert!((h.t - 2.0).abs() < 1e-5, "{h:?}");
        assert_near(along_slope.at(h.t), Vec3::new(0.5, 0.5, 0.0), 1e-5);
    }

    #[test]
    fn ray_through_a_thin_cone_tip_from_afar_lands_on_the_surface() {
        // Where the cone is thin, the ray's two roots nearly coincide; solving from an origin 3
        // units away once put the hit 1e-4 off the surface and past the point aimed at.
        let top = Vec3::new(-1.327_029_3, 0.385_335_27, 1.114_284_3);
        let cone = TaperedCylinder::new(Vec3::ZERO, top, 0.255_472_78, 0.0, false).unwrap();
        let target = Vec3::new(-1.284_730_6, 0.365_441_86, 1.081_611);
        let from = Vec3::new(0.771_524_4, -0.046_773_9, 0.634_432_4);
        let ray = Ray::new(target + from * 3.2, -from * 3.2);
        let h = hit(&cone, &ray).unwrap();
        assert!(h.t <= 1.0 + 1e-5, "{h:?}");
        let p = ray.at(h.t);
        let axis = top.normalize();
        let z = p.dot(axis);
        let radius = 0.255_472_78 * (1.0 - z / top.length());
        assert!(((p - axis * z).length() - radius).abs() < 1e-5, "{p}");
    }

    #[test]
    fn respects_the_t_range() {
        let c = cylinder(true);
        let ray = Ray::new(Vec3::new(5.0, 1.0, 0.0), -Vec3::X);
        assert_eq!(c.intersect(&ray, 0.0, 4.0), None);
        let far_side = c.intersect(&ray, 4.0, 10.0).unwrap();
        assert!((far_side.t - 6.0).abs() < 1e-6);
        assert_eq!(c.intersect(&ray, 6.0, 10.0), None);
    }

    #[test]
    fn hit_points_lie_on_the_surface_with_outward_normals() {
        let c = TaperedCylinder::new(
            Vec3::new(1.0, -1.0, 0.5),
            Vec3::new(-0.5, 2.0, 1.5),
            1.5,
            0.4,
            true,
        )
        .unwrap();
        let base = Vec3::new(1.0, -1.0, 0.5);
        let top = Vec3::new(-0.5, 2.0, 1.5);
        let axis = (top - base).normalize();
        let centre = (base + top) * 0.5;
        for i in 0..64 {
            let angle = i as f32 * 0.7;
            let origin = centre + 6.0 * Vec3::new(angle.cos(), (i as f32 * 0.3).sin(), angle.sin());
            let target = centre + Vec3::new(0.3, -0.2, 0.1) * (i % 3) as f32;
            let ray = Ray::new(origin, (target - origin) * 0.5);
            let h = hit(&c, &ray).expect("aimed inside");
            let p = ray.at(h.t);
            let z = (p - base).dot(axis);
            let radial = (p - base) - axis * z;
            let n = c.surface(p, h.part).normal.normalize();
            assert!((n.length() - 1.0).abs() < 1e-5);
            match h.part {
                TaperedCylinder::SIDE => {
                    let radius = 1.5 + (0.4 - 1.5) * z / (top - base).length();
                    assert!((radial.length() - radius).abs() < 1e-4, "{p}");
                    assert!(n.dot(radial) > 0.0);
                }
                TaperedCylinder::BASE_CAP => assert!(z.abs() < 1e-4 && n.dot(-axis) > 0.999),
                _ => assert!((p - top).dot(axis).abs() < 1e-4 && n.dot(axis) > 0.999),
            }
            assert!(n.dot(p - centre) > 0.0);
        }
    }

    #[test]
    fn texture_coordinates() {
        let c = cylinder(true);
        for p in [
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, -1.0),
            Vec3::new(-1.0, 1.0, 0.0),
        ] {
            let uv = c.surface(p, TaperedCylinder::SIDE).uv;
            assert!(
                uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all(),
                "{uv}"
            );
        }
        assert_eq!(
            c.surface(Vec3::new(0.0, 2.0, -1.0), TaperedCylinder::SIDE)
                .uv
                .y,
            1.0
        );
        // Opposite sides of the axis are half a turn apart.
        let u0 = c
            .surface(Vec3::new(1.0, 1.0, 0.0), TaperedCylinder::SIDE)
            .uv
            .x;
        let u1 = c
            .surface(Vec3::new(-1.0, 1.0, 0.0), TaperedCylinder::SIDE)
            .uv
            .x;
        assert!(((u0 - u1).abs() - 0.5).abs() < 1e-6);
        assert_eq!(
            c.surface(Vec3::new(0.0, 2.0, 0.0), TaperedCylinder::TOP_CAP)
                .uv,
            Vec2::splat(0.5)
        );
        let rim = c
            .surface(Vec3::new(1.0, 2.0, 0.0), TaperedCylinder::TOP_CAP)
            .uv;
        assert!(((rim - Vec2::splat(0.5)).length() - 0.5).abs() < 1e-6);
    }

    #[test]
    fn bounds_hold_the_end_circles() {
        let c = TaperedCylinder::new(Vec3::ZERO, Vec3::new(0.0, 2.0, 0.0), 1.0, 0.5, true).unwrap();
        let b = c.bounds();
        assert_near(b.min, Vec3::new(-1.0, 0.0, -1.0), 1e-6);
        assert_near(b.max, Vec3::new(1.0, 2.0, 1.0), 1e-6);
    }

    #[test]
    fn rejects_bad_parameters() {
        let new = |base, top, r0, r1| TaperedCylinder::new(base, top, r0, r1, true);
        assert_eq!(
            new(Vec3::ZERO, Vec3::Y, -1.0, 1.0).unwrap_err(),
            "cylinder radii must not be negative, got -1 and 1"
        );
        assert!(
            new(Vec3::ZERO, Vec3::Y, 0.0, 0.0)
                .unwrap_err()
                .contains("both be zero")
        );
        assert!(
            new(Vec3::Y, Vec3::Y, 1.0, 1.0)
                .unwrap_err()
                .contains("axis")
        );
        assert!(new(Vec3::ZERO, Vec3::Y, f32::NAN, 1.0).is_err());
        assert!(new(Vec3::ZERO, Vec3::splat(f32::INFINITY), 1.0, 1.0).is_err());
        assert!(new(Vec3::ZERO, Vec3::Y * 1e-30, 0.0, 1e30).is_err());
    }

    #[test]
    fn transformed_cylinder_in_the_world() {
        // The unit cylinder (radius 1, y from 0 to 1) scaled to radius 2 and height 3, turned
        // 90° about z (+y → −x), moved by (10, 0, 0): its axis runs from (10, 0, 0) to
        // (7, 0, 0) with radius 2.
        let unit = TaperedCylinder::new(Vec3::ZERO, Vec3::Y, 1.0, 1.0, true).unwrap();
        let steps = [
            TransformStep::Scale(Vec3::new(2.0, 3.0, 2.0)),
            TransformStep::Rotate {
                axis: Vec3::Z,
                degrees: 90.0,
            },
            TransformStep::Translate(Vec3::new(10.0, 0.0, 0.0)),
        ];
        let side = Ray::new(Vec3::new(8.5, 10.0, 0.0), Vec3::new(0.0, -1.0, 0.0));
        let (h, s) = hit_in_world(Shape::TaperedCylinder(unit), &steps, &side).unwrap();
        assert_eq!(h.part, TaperedCylinder::SIDE);
        assert!((h.t - 8.0).abs() < 1e-5);
        assert_near(s.point, Vec3::new(8.5, 2.0, 0.0), 1e-5);
        assert_near(s.normal, Vec3::Y, 1e-5);
        assert_near(s.object_point, Vec3::new(1.0, 0.5, 0.0), 1e-5);

        let end_on = Ray::new(Vec3::new(0.0, 0.5, 0.5), Vec3::new(2.0, 0.0, 0.0));
        let (h, s) = hit_in_world(Shape::TaperedCylinder(unit), &steps, &end_on).unwrap();
        assert_eq!(h.part, TaperedCylinder::TOP_CAP);
        assert!((h.t - 3.5).abs() < 1e-5);
        assert_near(s.normal, -Vec3::X, 1e-5);
    }
}
