//! Where photons leave a light: only towards the specular objects, since the caustic map keeps
//! only light that a mirror or glass has turned (Jensen's projection map). Around each specular
//! object's bounding sphere a point light gets the cone of directions that sees it, a
//! directional light the disc that casts its shadow; an object without bounds (a plane) gets
//! every direction, or the disc around the whole scene. A photon picks one target in
//! proportion to its size and a point in it uniformly, so the density of its direction is the
//! number of targets that contain it over their total size; its power is the light's over
//! that density.

use std::f32::consts::{PI, TAU};

use glam::Vec3;

use crate::aabb::Aabb;
use crate::color::Color;
use crate::light::Light;
use crate::ray::Ray;

/// A sphere around something specular.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Sphere {
    pub center: Vec3,
    pub radius: f32,
}

impl Sphere {
    /// The sphere around a box.
    pub fn around(bounds: &Aabb) -> Sphere {
        Sphere {
            center: bounds.center(),
            radius: bounds.extent().length() * 0.5,
        }
    }
}

/// The directions (from a point light) or the parallel rays (from a directional light) that
/// reach one specular object.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    /// Directions within the angle whose cosine is `cos_half` of `axis`.
    Cone { axis: Vec3, cos_half: f32 },
    /// Rays through the disc of `radius` around `center`, across the light's direction.
    Disc { center: Vec3, radius: f32 },
}

impl Target {
    /// Its size: the cone's solid angle, the disc's area.
    fn measure(&self) -> f32 {
        match *self {
            Target::Cone { cos_half, .. } => TAU * (1.0 - cos_half),
            Target::Disc { radius, .. } => PI * radius * radius,
        }
    }
}

/// A light and the targets its photons aim at.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Emitter {
    light: Light,
    targets: Vec<Target>,
    /// The targets' total size.
    total: f32,
    /// Where a directional light's photons start: this far back from their disc.
    start_distance: f32,
}

impl Emitter {
    /// The emitter of `light` aiming at `specular` (spheres, or `None` for an object without
    /// bounds), in a scene whose finite objects lie in `scene_bounds`; `None` if the light
    /// cannot reach anything specular.
    pub fn new(light: &Light, specular: &[Option<Sphere>], scene_bounds: &Aabb) -> Option<Emitter> {
        let scene = Sphere::around(scene_bounds);
        let targets: Vec<Target> = match *light {
            Light::Point { position, .. } | Light::Spot(crate::light::Spot { position, .. }) => {
                specular
                    .iter()
                    .map(|sphere| cone_towards(position, *sphere))
                    .collect()
            }
            Light::Directional { .. } => specular
                .iter()
                .map(|sphere| {
                    let s = sphere.unwrap_or(scene);
                    Target::Disc {
                        center: s.center,
                        radius: s.radius,
                    }
                })
                .collect(),
        };
        let total: f32 = targets.iter().map(Target::measure).sum();
        (total > 0.0 && total.is_finite()).then_some(Emitter {
            light: *light,
            targets,
            total,
            start_distance: 2.0 * scene.radius + 1.0,
        })
    }

    /// Whether the light comes from infinitely far (a directional light), so that its photons
    /// start at no particular distance (`start_distance` back from their disc).
    pub fn is_afar(&self) -> bool {
        matches!(self.light, Light::Directional { .. })
    }

    /// Roughly the power the light sends at its targets, for sharing the photons out between
    /// lights.
    pub fn power(&self) -> f32 {
        let color = match self.light {
            Light::Point { color, .. } | Light::Directional { color, .. } => color,
            Light::Spot(spot) => spot.color,
        };
        color.max_element().max(0.0) * self.total
    }

    /// Photon `u` (three numbers in [0, 1)): its ray, and its power times the number of photons
    /// this light shoots. The power is zero where a spot light sends nothing.
    pub fn emit(&self, u: [f32; 3]) -> (Ray, Color) {
        // Pick a target in proportion to its size, reusing what is left of u[0].
        let mut pick = u[0] * self.total;
        let mut chosen = self.targets[self.targets.len() - 1];
        for target in &self.targets {
            let m = target.measure();
            if pick < m {
                chosen = *target;
                break;
            }
            pick -= m;
        }
        let (ray, color) = match (chosen, self.light) {
            (Target::Cone { axis, cos_half }, light) => {
                let dir = in_cone(axis, cos_half, u[1], u[2]);
                let (origin, color) = match light {
                    Light::Point { position, color } => (position, color),
                    Light::Spot(spot) => (spot.position, spot.color * spot.cone(dir)),
                    Light::Directional { .. } => unreachable!("directional lights aim at discs"),
                };
                (Ray::new(origin, dir), color)
            }
            (Target::Disc { center, radius }, Light::Directional { direction, color }) => {
                let (s, t) = direction.any_orthonormal_pair();
                let r = radius * u[1].sqrt();
                let angle = TAU * u[2];
                let on_disc = center + r * (angle.cos() * s + angle.sin() * t);
                let origin = on_disc + direction * self.start_distance;
                (Ray::new(origin, -direction), color)
            }
            (Target::Disc { .. }, _) => unreachable!("point lights aim at cones"),
        };
        let containing = self
            .targets
            .iter()
            .filter(|t| self.contains(t, &ray))
            .count();
        (ray, color * (self.total / containing.max(1) as f32))
    }

    /// Whether the photon `ray` lies in `target`.
    fn contains(&self, target: &Target, ray: &Ray) -> bool {
        match *target {
            Target::Cone { axis, cos_half } => axis.dot(ray.dir) >= cos_half,
            Target::Disc { center, radius } => {
                let to_center = center - ray.origin;
                let across = to_center - ray.dir * to_center.dot(ray.dir);
                across.length_squared() <= radius * radius
            }
        }
    }
}

/// The cone of directions from `from` that see `sphere`; every direction for `None` or when
/// `from` lies inside it.
fn cone_towards(from: Vec3, sphere: Option<Sphere>) -> Target {
    let every = Target::Cone {
        axis: Vec3::Z,
        cos_half: -1.0,
    };
    let Some(Sphere { center, radius }) = sphere else {
        return every;
    };
    let to_center = center - from;
    let distance = to_center.length();
    if distance <= radius {
        return every;
    }
    let sin_half = radius / distance;
    Target::Cone {
        axis: to_center / distance,
        cos_half: (1.0 - sin_half * sin_half).sqrt(),
    }
}

/// A direction uniformly distributed in the cone around `axis` whose half-angle has the cosine
/// `cos_half`.
fn in_cone(axis: Vec3, cos_half: f32, u1: f32, u2: f32) -> Vec3 {
    let cos = 1.0 - u1 * (1.0 - cos_half);
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let angle = TAU * u2;
    let (s, t) = axis.any_orthonormal_pair();
    (cos * axis + sin * (angle.cos() * s + angle.sin() * t)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::hash;

    fn unit(i: u32) -> f32 {
        (hash(i) >> 8) as f32 / (1u32 << 24) as f32
    }

    fn sphere(center: Vec3, radius: f32) -> Option<Sphere> {
        Some(Sphere { center, radius })
    }

    #[test]
    fn directions_stay_in_their_cone_and_cover_it() {
        let axis = Vec3::new(1.0, 2.0, -0.5).normalize();
        let cos_half = 0.8;
        let mut widest = 1.0f32;
        for i in 0..2000 {
            let d = in_cone(axis, cos_half, unit(2 * i), unit(2 * i + 1));
            assert!((d.length() - 1.0).abs() < 1e-5);
            assert!(d.dot(axis) >= cos_half - 1e-5, "{d}");
            widest = widest.min(d.dot(axis));
        }
        assert!(widest < 0.81, "the cone's edge is reached: {widest}");
    }

    #[test]
    fn the_power_of_a_point_light_sums_to_its_intensity_times_the_solid_angle_aimed_at() {
        // Two overlapping targets: the photons' powers still add up to I × Ω of their union,
        // which a fine grid of directions measures.
        let light = Light::Point {
            position: Vec3::ZERO,
            color: Color::splat(2.0),
        };
        let targets = [
            sphere(Vec3::new(0.0, 0.0, -5.0), 2.0),
            sphere(Vec3::new(1.5, 0.0, -5.0), 2.0),
        ];
        let emitter = Emitter::new(&light, &targets, &Aabb::EMPTY).unwrap();
        let n = 200_000;
        let total: f32 = (0..n)
            .map(|i| {
                emitter
                    .emit([unit(3 * i), unit(3 * i + 1), unit(3 * i + 2)])
                    .1
                    .x
            })
            .sum::<f32>()
            / n as f32;
        let cones: Vec<Target> = targets
            .iter()
            .map(|s| cone_towards(Vec3::ZERO, *s))
            .collect();
        let (m, mut inside) = (1000, 0u64);
        for i in 0..m * m {
            // Uniform directions on the sphere by their z and angle.
            let z = 1.0 - 2.0 * ((i / m) as f32 + 0.5) / m as f32;
            let angle = TAU * ((i % m) as f32 + 0.5) / m as f32;
            let r = (1.0 - z * z).sqrt();
            let dir = Vec3::new(r * angle.cos(), r * angle.sin(), z);
            let ray = Ray::new(Vec3::ZERO, dir);
            if cones.iter().any(|c| emitter.contains(c, &ray)) {
                inside += 1;
            }
        }
        let union = 4.0 * PI * inside as f32 / (m * m) as f32;
        assert!(
            (total / (2.0 * union) - 1.0).abs() < 0.01,
            "{total} vs {}",
            2.0 * union
        );
    }

    #[test]
    fn a_directional_light_sends_its_irradiance_times_the_area_of_the_disc() {
        let light = Light::Directional {
            direction: Vec3::Y,
            color: Color::ONE,
        };
        let target = [sphere(Vec3::new(1.0, 0.0, 0.0), 0.5)];
        let bounds = Aabb::new(Vec3::splat(-2.0), Vec3::splat(2.0));
        let emitter = Emitter::new(&light, &target, &bounds).unwrap();
        for i in 0..100 {
            let (ray, power) = emitter.emit([unit(3 * i), unit(3 * i + 1), unit(3 * i + 2)]);
            assert_eq!(ray.dir, -Vec3::Y);
            assert!(ray.origin.y > 2.0, "starts above the scene: {}", ray.origin);
            let across = Vec3::new(ray.origin.x - 1.0, 0.0, ray.origin.z);
            assert!(across.length() <= 0.5 + 1e-5);
            assert!((power.x - PI * 0.25).abs() < 1e-5);
        }
    }

    #[test]
    fn a_light_inside_a_target_or_facing_a_plane_shoots_everywhere() {
        assert_eq!(
            cone_towards(Vec3::ZERO, sphere(Vec3::X, 2.0)).measure(),
            4.0 * PI
        );
        assert_eq!(cone_towards(Vec3::ZERO, None).measure(), 4.0 * PI);
    }
}
