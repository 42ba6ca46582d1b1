//! Paraboloids of revolution opening towards +y (a dish, a lamp's reflector), cut at a height
//! and optionally closed there by a disk. Other orientations come from the object's transform.

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};

use super::quadratic::{first_root_between_ends, solve_quadratic};
use super::tapered_cylinder::disk_uv;
use super::{LocalSurface, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;

/// The surface `y = height·(x² + z²) / radius²` for `0 ≤ y ≤ height`, measured from `vertex`:
/// it is `radius` wide at the top.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paraboloid {
    pub(crate) vertex: Vec3,
    pub(crate) radius: f32,
    pub(crate) height: f32,
    /// `height / radius²`: how fast the surface rises with the squared distance from the axis.
    pub(crate) curvature: f32,
    capped: bool,
}

impl Paraboloid {
    // The part numbers of a paraboloid's surface.
    pub const BOWL: u32 = 0;
    pub const CAP: u32 = 1;

    pub fn new(vertex: Vec3, radius: f32, height: f32, capped: bool) -> Result<Paraboloid, String> {
        if !vertex.is_finite() {
            return Err(format!("paraboloid vertex must be finite, got {vertex}"));
        }
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(format!("paraboloid radius must be positive, got {radius}"));
        }
        if !(height > 0.0 && height.is_finite()) {
            return Err(format!("paraboloid height must be positive, got {height}"));
        }
        let curvature = height / radius / radius;
        if !curvature.is_normal() {
            return Err(format!(
                "paraboloid of radius {radius} and height {height} is too flat or too narrow to work with"
            ));
        }
        Ok(Paraboloid {
            vertex,
            radius,
            height,
            curvature,
            capped,
        })
    }

    /// Whether the top is closed by a disk.
    pub fn is_capped(&self) -> bool {
        self.capped
    }

    /// The nearest of the bowl, `k·(x² + z²) − y = 0` with `0 ≤ y ≤ height`, and (when capped)
    /// the disk at `y = height`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let d = ray.dir;
        // Work from the point `o` of the ray nearest the middle of the axis, with `s = t − shift`
        // along the ray from there, which keeps the quadratic's coefficients (and their rounding
        // errors) as small as the paraboloid.
        let origin = ray.origin - self.vertex;
        let shift = (Vec3::new(0.0, 0.5 * self.height, 0.0) - origin).dot(d) / d.length_squared();
        if !shift.is_finite() {
            return None; // no direction
        }
        let o = origin + d * shift;
        let k = self.curvature;
        let mut nearest = None;
        let mut t_far = t_max;

        let a = k * (d.x * d.x + d.z * d.z);
        let half_b = k * (o.x * d.x + o.z * d.z) - 0.5 * d.y;
        let c = k * (o.x * o.x + o.z * o.z) - o.y;
        let roots = solve_quadratic(a, half_b, c);
        let bowl = roots
            .and_then(|r| first_root_between_ends(r, shift, t_min, t_far, (o.y, d.y), self.height));
        if let Some(t) = bowl {
            nearest = Some(ShapeHit {
                t,
                part: Paraboloid::BOWL,
            });
            t_far = t;
        }

        if self.capped && d.y != 0.0 {
            let s = (self.height - o.y) / d.y;
            let t = s + shift;
            if t > t_min && t < t_far {
                let x = o.x + d.x * s;
                let z = o.z + d.z * s;
                if x * x + z * z <= self.radius * self.radius {
                    nearest = Some(ShapeHit {
                        t,
                        part: Paraboloid::CAP,
                    });
                }
            }
        }
        nearest
    }

    /// The bowl maps cylindrically (`u` the angle around the axis over 2π, as on a sphere; `v` the
    /// fraction of the height); the cap maps its disk onto `[0, 1]²` with `u` along +x and `v`
    /// along −z, like a horizontal plane.
    pub fn surface(&self, p: Vec3, part: u32) -> LocalSurface {
        let local = p - self.vertex;
        if part == Paraboloid::CAP {
            return LocalSurface {
                normal: Vec3::Y,
                uv: disk_uv(Vec2::new(local.x, -local.z), self.radius),
            };
        }
        let k2 = 2.0 * self.curvature;
        LocalSurface {
            normal: Vec3::new(k2 * local.x, -1.0, k2 * local.z),
            uv: Vec2::new(
                0.5 + local.x.atan2(local.z) / TAU,
                (local.y / self.height).clamp(0.0, 1.0),
            ),
        }
    }

    pub fn bounds(&self) -> Aabb {
        let r = self.radius;
        Aabb::new(
            self.vertex + Vec3::new(-r, 0.0, -r),
            self.vertex + Vec3::new(r, self.height, r),
        )
    }
}

#[cfg(test)]
mod tests {
    use std::f32::consts::FRAC_1_SQRT_2;

    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    /// `y = x² + z²` up to y = 1.
    fn dish(capped: bool) -> Paraboloid {
        Paraboloid::new(Vec3::ZERO, 1.0, 1.0, capped).unwrap()
    }

    fn hit(shape: &Paraboloid, ray: &Ray) -> Option<ShapeHit> {
        shape.intersect(ray, 1e-4, f32::INFINITY)
    }

    #[test]
    fn side_hit() {
        let ray = Ray::new(Vec3::new(5.0, 0.25, 0.0), Vec3::new(-2.0, 0.0, 0.0));
        let h = hit(&dish(true), &ray).unwrap();
        assert_eq!(h.part, Paraboloid::BOWL);
        assert!((h.t - 2.25).abs() < 1e-6);
        let p = ray.at(h.t);
        assert_near(p, Vec3::new(0.5, 0.25, 0.0), 1e-6);
        let s = dish(true).surface(p, h.part);
        assert_near(
            s.normal.normalize(),
            Vec3::new(FRAC_1_SQRT_2, -FRAC_1_SQRT_2, 0.0),
            1e-6,
        );
        assert!((s.uv.y - 0.25).abs() < 1e-6);
    }

    #[test]
    fn from_above_open_hits_the_inside_and_capped_hits_the_cap() {
        let ray = Ray::new(Vec3::new(0.5, 5.0, 0.0), -Vec3::Y);
        let open = hit(&dish(false), &ray).unwrap();
        assert_eq!(open.part, Paraboloid::BOWL);
        assert!((open.t - 4.75).abs() < 1e-6);
        let closed = hit(&dish(true), &ray).unwrap();
        assert_eq!(
            closed,
            ShapeHit {
                t: 4.0,
                part: Paraboloid::CAP
            }
        );
        let s = dish(true).surface(ray.at(closed.t), closed.part);
        assert_eq!(s.normal, Vec3::Y);
        assert_eq!(s.uv, Vec2::new(0.75, 0.5));
    }

    #[test]
    fn ray_from_inside_hits_the_exit() {
        let sideways = Ray::new(Vec3::new(0.0, 0.5, 0.0), Vec3::X);
        let h = hit(&dish(true), &sideways).unwrap();
        assert!((h.t - 0.5f32.sqrt()).abs() < 1e-6);
        let p = sideways.at(h.t);
        let n = dish(true).surface(p, h.part).normal;
        assert!(n.dot(p - Vec3::new(0.0, 0.5, 0.0)) > 0.0);
        let up = Ray::new(Vec3::new(0.2, 0.5, 0.0), Vec3::Y);
        assert_eq!(
            hit(&dish(true), &up),
            Some(ShapeHit {
                t: 0.5,
                part: Paraboloid::CAP
            })
        );
        assert_eq!(hit(&dish(false), &up), None);
    }

    #[test]
    fn tangent_at_the_vertex_and_misses() {
        let tangent = Ray::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
        let h = hit(&dish(true), &tangent).unwrap();
        assert!((h.t - 5.0).abs() < 1e-3, "{h:?}");
        let n = dish(true)
            .surface(tangent.at(h.t), h.part)
            .normal
            .normalize();
        assert_near(n, -Vec3::Y, 1e-3);
        let below = Ray::new(Vec3::new(-5.0, -0.001, 0.0), Vec3::X);
        let above = Ray::new(Vec3::new(-5.0, 1.001, 0.0), Vec3::X);
        let down_outside = Ray::new(Vec3::new(1.5, 5.0, 0.0), -Vec3::Y);
        for ray in [below, above, down_outside] {
            assert_eq!(hit(&dish(true), &ray), None, "{ray:?}");
        }
    }

    #[test]
    fn respects_the_t_range() {
        let d = dish(true);
        let ray = Ray::new(Vec3::new(5.0, 0.25, 0.0), -Vec3::X);
        assert_eq!(d.intersect(&ray, 0.0, 4.5), None);
        let far = d.intersect(&ray, 4.5, 10.0).unwrap();
        assert!((far.t - 5.5).abs() < 1e-6);
        assert_eq!(d.intersect(&ray, 5.5, 10.0), None);
    }

    #[test]
    fn hit_points_lie_on_the_surface_with_outward_normals() {
        let p = Paraboloid::new(Vec3::new(1.0, -2.0, 0.5), 1.5, 2.5, true).unwrap();
        let inside = Vec3::new(1.0, -0.5, 0.5);
        let k = 2.5 / (1.5 * 1.5);
        for i in 0..64 {
            let angle = i as f32 * 0.9;
            let origin = inside + 5.0 * Vec3::new(angle.cos(), (i as f32 * 0.4).sin(), angle.sin());
            let ray = Ray::new(origin, inside - origin);
            let h = hit(&p, &ray).expect("aimed inside");
            let q = ray.at(h.t) - Vec3::new(1.0, -2.0, 0.5);
            match h.part {
                Paraboloid::BOWL => {
                    assert!((k * (q.x * q.x + q.z * q.z) - q.y).abs() < 1e-4, "{q}")
                }
                _ => assert!((q.y - 2.5).abs() < 1e-5 && q.x.hypot(q.z) <= 1.5 + 1e-5),
            }
            let n = p.surface(ray.at(h.t), h.part).normal.normalize();
            assert!((n.length() - 1.0).abs() < 1e-5);
            assert!(n.dot(ray.at(h.t) - inside) > 0.0);
        }
    }

    #[test]
    fn rejects_bad_parameters() {
        assert_eq!(
            Paraboloid::new(Vec3::ZERO, -1.0, 1.0, true).unwrap_err(),
            "paraboloid radius must be positive, got -1"
        );
        assert!(Paraboloid::new(Vec3::ZERO, 1.0, 0.0, true).is_err());
        assert!(Paraboloid::new(Vec3::ZERO, 1.0, f32::INFINITY, true).is_err());
        assert!(Paraboloid::new(Vec3::ZERO, 1e-30, 1e30, true).is_err());
        assert!(Paraboloid::new(Vec3::splat(f32::NAN), 1.0, 1.0, true).is_err());
    }

    #[test]
    fn transformed_paraboloid_in_the_world() {
        // z' = 2(x² + y²) after turning +y to +z (90° about x), vertex moved to (0, 0, 1).
        let steep = Paraboloid::new(Vec3::ZERO, 1.0, 2.0, false).unwrap();
        let steps = [
            TransformStep::Rotate {
                axis: Vec3::X,
                degrees: 90.0,
            },
            TransformStep::Translate(Vec3::new(0.0, 0.0, 1.0)),
        ];
        let expected_normal = Vec3::new(2.0, 0.0, -1.0) / 5f32.sqrt();
        let into_mouth = Ray::new(Vec3::new(0.5, 0.0, 10.0), Vec3::new(0.0, 0.0, -1.0));
        let (h, s) = hit_in_world(Shape::Paraboloid(steep), &steps, &into_mouth).unwrap();
        assert!((h.t - 8.5).abs() < 1e-5);
        assert_near(s.point, Vec3::new(0.5, 0.0, 1.5), 1e-5);
        assert_near(s.object_point, Vec3::new(0.5, 0.5, 0.0), 1e-5);
        assert_near(s.normal, expected_normal, 1e-5);

        let from_side = Ray::new(Vec3::new(5.0, 0.0, 1.5), Vec3::new(-1.0, 0.0, 0.0));
        let (h, s) = hit_in_world(Shape::Paraboloid(steep), &steps, &from_side).unwrap();
        assert!((h.t - 4.5).abs() < 1e-5);
        assert_near(s.normal, expected_normal, 1e-5);
    }
}
