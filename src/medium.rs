//! Participating media: homogeneous [`Medium`]s, one filling the scene (the fog, the scene
//! file's `[atmosphere]`, in the part of space [`Fog`] says) and one inside each object whose
//! material has a `medium` (smoky glass, coloured liquid). Which of them a ray runs through
//! the tracer keeps track of (`whitted::Within`, by the rule below).
//!
//! Light travelling a distance `d` through a medium of extinction coefficient `σ` (its
//! `density`, per unit length) keeps the fraction `T(d) = exp(−σ·d)` (Beer–Lambert); of what is
//! lost, the share `albedo` is scattered (`σ_s = albedo·σ`) and the rest absorbed. Scattered
//! light leaves evenly in every direction (the isotropic phase function `1/(4π)`), tinted by
//! `color`. The tracer ([`crate::whitted`]) attenuates every ray by `T` and adds the light the
//! medium scatters into it, see `whitted/fog.rs`.
//!
//! Which medium a ray is in: eye rays start in the fog; a ray that passes into an object
//! (through a surface whose normal faces it) is inside that surface's material's medium, or in
//! clear material if it has none; a ray that passes out of a surface is back in the fog.
//! Reflected rays stay where their parent was. Nested media are not tracked: a ray leaving a
//! ball of liquid inside a smoky ball is taken to be in the fog, not in the smoke, so nested
//! objects should have clear material between them (a glass cup and the liquid in it with a
//! thin gap of air). Rays inside an object are in no fog.
//!
//! Where the fog ends: fog filling all of space would swallow the background and the light of
//! directional lights (which comes from infinitely far) whole, however thin. So the fog fills a
//! ball around the scene: the smallest ball around the box of its bounded objects, its point
//! and spot lights and the camera's eye ([`Fog::new`]); a ball rather than that box, because
//! the box's edges would show as creases in the fog over an infinite floor. A ray is attenuated
//! by the length it travels inside the ball: a ray to the background by the distance to where
//! it leaves the ball (a backdrop at distance `d`, and the background past the ball's surface
//! at distance `d`, are both dimmed by exactly `exp(−σ·d)`), and a shadow ray to a directional
//! light likewise. Infinite planes reach beyond the ball: past it they are seen through the fog
//! between them and the ball only.

use glam::Vec3;

use crate::aabb::Aabb;
use crate::color::Color;
use crate::light::Light;
use crate::shapes::solve_quadratic;

/// The isotropic phase function: the share of scattered light that leaves into each unit of
/// solid angle, the same in every direction.
pub const ISOTROPIC_PHASE: f32 = 1.0 / (4.0 * std::f32::consts::PI);

/// A homogeneous medium: the scene file's `[atmosphere]` or a material's `medium`. A density
/// of zero is clear air.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Medium {
    /// Extinction coefficient σ, per unit length.
    pub density: f32,
    /// Share of the extinction that is scattering, not absorption (0 to 1).
    pub albedo: f32,
    /// Colour of the scattered light.
    pub color: Color,
}

/// The medium filling the scene between objects: the fog.
pub type Atmosphere = Medium;

impl Default for Medium {
    /// Clear air.
    fn default() -> Self {
        Medium {
            density: 0.0,
            albedo: 1.0,
            color: Color::ONE,
        }
    }
}

impl Medium {
    /// Whether there is no medium at all.
    pub fn is_clear(&self) -> bool {
        self.density == 0.0
    }

    /// The fraction of light that passes `distance` of this medium (Beer–Lambert).
    pub fn transmittance(&self, distance: f32) -> f32 {
        (-self.density * distance).exp()
    }

    /// The scattering coefficient `σ_s = albedo·σ`, per colour channel.
    pub fn scattering(&self) -> Color {
        self.density * self.albedo * self.color
    }
}

/// The atmosphere of a scene and the ball it fills.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    pub atmosphere: Atmosphere,
    /// The centre of the ball the fog fills.
    pub center: Vec3,
    pub radius: f32,
}

/// Where a ray runs through a medium: from distance `start` to `end` along a unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    pub start: f32,
    pub end: f32,
}

impl Segment {
    pub fn length(&self) -> f32 {
        self.end - self.start
    }
}

impl Fog {
    /// The fog of `atmosphere` in the ball around the box of `object_bounds`, the positions of
    /// `lights` and `eye`; `None` in clear air.
    pub fn new(
        atmosphere: Atmosphere,
        object_bounds: Option<Aabb>,
        lights: &[Light],
        eye: Vec3,
    ) -> Option<Fog> {
        if atmosphere.is_clear() {
            return None;
        }
        let light_positions = lights.iter().filter_map(|light| match light {
            Light::Point { position, .. } => Some(*position),
            Light::Spot(spot) => Some(spot.position),
            Light::Directional { .. } => None,
        });
        let bounds = Aabb::from_points(light_positions)
            .grow(eye)
            .union(object_bounds.unwrap_or(Aabb::EMPTY));
        Some(Fog {
            atmosphere,
            center: bounds.center(),
            radius: bounds.extent().length() / 2.0,
        })
    }

    /// The part of the ray `origin + s·dir` (`dir` a unit vector), `start ≤ s ≤ end`, that
    /// lies in the fog; `None` if it misses the fog's ball there. The ray is inside the ball
    /// between the roots of `|origin + s·dir − center|² = radius²`.
    pub fn segment(&self, origin: Vec3, dir: Vec3, start: f32, end: f32) -> Option<Segment> {
        let to_origin = origin - self.center;
        let c = to_origin.length_squared() - self.radius * self.radius;
        let (enter, leave) = solve_quadratic(1.0, to_origin.dot(dir), c)?;
        let (start, end) = (start.max(enter), end.min(leave));
        (start < end).then_some(Segment { start, end })
    }

    /// The fraction of light that passes along the ray from `start` to `end`.
    pub fn transmittance(&self, origin: Vec3, dir: Vec3, start: f32, end: f32) -> f32 {
        self.segment(origin, dir, start, end)
            .map_or(1.0, |segment| {
                self.atmosphere.transmittance(segment.length())
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fog(density: f32) -> Atmosphere {
        Atmosphere {
            density,
            albedo: 0.5,
            color: Color::new(1.0, 0.5, 0.25),
        }
    }

    #[test]
    fn beer_lambert_halves_the_light_every_ln2_over_sigma() {
        let a = fog(0.5);
        assert_eq!(a.transmittance(0.0), 1.0);
        assert!((a.transmittance(2.0 * std::f32::consts::LN_2) - 0.5).abs() < 1e-6);
        assert_eq!(a.scattering(), Color::new(0.25, 0.125, 0.0625));
        assert!(Atmosphere::default().is_clear());
    }

    #[test]
    fn the_fog_fills_the_ball_around_the_objects_the_point_lights_and_the_eye() {
        let objects = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let lights = [
            Light::Point {
                position: Vec3::new(0.0, 5.0, 0.0),
                color: Color::ONE,
            },
            Light::Directional {
                direction: Vec3::Y,
                color: Color::ONE,
            },
        ];
        // The box from (0, 0, −4) to (1, 5, 1), whose diagonal is √51.
        let eye = Vec3::new(0.5, 0.5, -4.0);
        let f = Fog::new(fog(1.0), Some(objects), &lights, eye).unwrap();
        assert_eq!(f.center, Vec3::new(0.5, 2.5, -1.5));
        assert!((f.radius - 51f32.sqrt() / 2.0).abs() < 1e-6);
        let clear = Atmosphere::default();
        assert_eq!(Fog::new(clear, Some(objects), &lights, eye), None);
        // Only a directional light (and maybe infinite planes): the fog is the eye's point, and
        // no ray crosses any of it.
        let f = Fog::new(fog(1.0), None, &lights[1..], eye).unwrap();
        assert_eq!(f.transmittance(eye, Vec3::X, 0.0, f32::INFINITY), 1.0);
    }

    #[test]
    fn a_ray_is_attenuated_only_inside_the_ball() {
        // The box from (−1, −1, −1) to (1, 1, 1): the ball of radius √3 around the origin.
        let box_ = Some(Aabb::new(-Vec3::ONE, Vec3::ONE));
        let f = Fog::new(fog(1.0), box_, &[], Vec3::ZERO).unwrap();
        let r = 3f32.sqrt();
        // From outside, through the centre: a diameter of fog.
        let origin = Vec3::new(-5.0, 0.0, 0.0);
        let through = f.segment(origin, Vec3::X, 0.0, f32::INFINITY).unwrap();
        assert!((through.start - (5.0 - r)).abs() < 1e-5 && (through.end - (5.0 + r)).abs() < 1e-5);
        let t = f.transmittance(origin, Vec3::X, 0.0, f32::INFINITY);
        assert!((t - (-2.0 * r).exp()).abs() < 1e-5);
        // Stopped at the centre, from the centre out, or turned away.
        assert!((f.segment(origin, Vec3::X, 0.0, 5.0).unwrap().length() - r).abs() < 1e-5);
        assert!((f.segment(Vec3::ZERO, Vec3::Y, 0.0, 9.0).unwrap().length() - r).abs() < 1e-6);
        assert_eq!(f.segment(origin, -Vec3::X, 0.0, f32::INFINITY), None);
        assert_eq!(f.transmittance(origin, -Vec3::X, 0.0, f32::INFINITY), 1.0);
        // Passing beside the ball.
        assert_eq!(
            f.segment(Vec3::new(-5.0, 2.0, 0.0), Vec3::X, 0.0, 9.0),
            None
        );
    }
}
