//! Participating media: homogeneous [`Medium`]s, one filling the scene (the fog, the scene
//! file's `[atmosphere]`, see [`Fog`]) and one inside each object whose material has a
//! `medium` (smoky glass, coloured liquid). Which of them a ray runs through the tracer keeps
//! track of (`whitted::Within`, by the rule below).
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
//! thin gap of air). Rays inside an object are in no fog. A ray inside an object that meets no
//! further surface (an object that is not closed) is taken to have left it: it is not
//! attenuated.
//!
//! The fog fills all of space: whatever a ray meets at distance `t` (eye, reflected,
//! transmitted, shadow ray or photon, infinite planes included) is seen through exactly
//! `exp(−σ·t)` and with the light scattered into the whole segment. Only what lies at no
//! distance needs a convention, since infinitely much fog would swallow it whole: the
//! background, and the light of directional lights, which comes from infinitely far. Both are
//! taken to lie at the [`Backdrop`]: by default the far side of the ball around the scene (its
//! bounded objects, point and spot lights and the eye), or at `background_distance` along the
//! ray from its start when the scene file says (`inf`: the fog hides the background, and a
//! directional light, entirely).

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

/// The medium filling the scene between objects, the fog, and how far it reaches along rays
/// that meet nothing.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Atmosphere {
    pub medium: Medium,
    /// Where rays that meet nothing see the background, along the ray from its start: `None`
    /// for the far side of the ball around the scene ([`Backdrop::Ball`]).
    pub background_distance: Option<f32>,
}

impl Atmosphere {
    /// Whether there is no fog at all.
    pub fn is_clear(&self) -> bool {
        self.medium.is_clear()
    }
}

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

/// The fog: the scene's medium, filling all of space, and where rays that meet nothing end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    pub medium: Medium,
    pub backdrop: Backdrop,
}

/// Where a ray that meets nothing (one to the background, a shadow ray to a directional light)
/// stops running through the fog.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Backdrop {
    /// Where the ray leaves the ball around the scene (its start, if it starts outside the
    /// ball and runs away from it or past it).
    Ball { center: Vec3, radius: f32 },
    /// At this distance along every ray from its start (infinite: nowhere).
    Distance(f32),
}

impl Backdrop {
    /// How far along the ray `origin + s·dir` (`dir` a unit vector) the backdrop lies. The ray
    /// is inside the ball between the roots of `|origin + s·dir − center|² = radius²`.
    pub fn distance(&self, origin: Vec3, dir: Vec3) -> f32 {
        match *self {
            Backdrop::Ball { center, radius } => {
                let to_origin = origin - center;
                let c = to_origin.length_squared() - radius * radius;
                solve_quadratic(1.0, to_origin.dot(dir), c).map_or(0.0, |(_, leave)| leave.max(0.0))
            }
            Backdrop::Distance(distance) => distance,
        }
    }
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
    /// The fog of `atmosphere`; `None` in clear air. Without a `background_distance` its
    /// backdrop is the smallest ball around the box of `object_bounds`, the positions of
    /// `lights` and `eye` (a ball rather than that box, whose edges would show as creases in
    /// the fog over an infinite floor).
    pub fn new(
        atmosphere: Atmosphere,
        object_bounds: Option<Aabb>,
        lights: &[Light],
        eye: Vec3,
    ) -> Option<Fog> {
        if atmosphere.is_clear() {
            return None;
        }
        let backdrop = match atmosphere.background_distance {
            Some(distance) => Backdrop::Distance(distance),
            None => {
                let light_positions = lights.iter().filter_map(|light| match light {
                    Light::Point { position, .. } => Some(*position),
                    Light::Spot(spot) => Some(spot.position),
                    Light::Directional { .. } => None,
                });
                let bounds = Aabb::from_points(light_positions)
                    .grow(eye)
                    .union(object_bounds.unwrap_or(Aabb::EMPTY));
                Backdrop::Ball {
                    center: bounds.center(),
                    radius: bounds.extent().length() / 2.0,
                }
            }
        };
        Some(Fog {
            medium: atmosphere.medium,
            backdrop,
        })
    }

    /// The part of the ray `origin + s·dir` (`dir` a unit vector), `start ≤ s ≤ end`, that
    /// runs through the fog: all of it up to a surface at `end`, or up to the backdrop when
    /// `end` is infinite; `None` if that is empty.
    pub fn segment(&self, origin: Vec3, dir: Vec3, start: f32, end: f32) -> Option<Segment> {
        let end = if end.is_finite() {
            end
        } else {
            self.backdrop.distance(origin, dir)
        };
        (start < end).then_some(Segment { start, end })
    }

    /// The fraction of light that passes along the ray from `start` to `end`.
    pub fn transmittance(&self, origin: Vec3, dir: Vec3, start: f32, end: f32) -> f32 {
        self.segment(origin, dir, start, end)
            .map_or(1.0, |segment| self.medium.transmittance(segment.length()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fog(density: f32) -> Atmosphere {
        Atmosphere {
            medium: Medium {
                density,
                albedo: 0.5,
                color: Color::new(1.0, 0.5, 0.25),
            },
            background_distance: None,
        }
    }

    #[test]
    fn beer_lambert_halves_the_light_every_ln2_over_sigma() {
        let a = fog(0.5).medium;
        assert_eq!(a.transmittance(0.0), 1.0);
        assert!((a.transmittance(2.0 * std::f32::consts::LN_2) - 0.5).abs() < 1e-6);
        assert_eq!(a.scattering(), Color::new(0.25, 0.125, 0.0625));
        assert!(Atmosphere::default().is_clear());
    }

    #[test]
    fn the_backdrop_is_the_ball_around_the_objects_the_point_lights_and_the_eye() {
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
        let Backdrop::Ball { center, radius } = f.backdrop else {
            panic!("{f:?}");
        };
        assert_eq!(center, Vec3::new(0.5, 2.5, -1.5));
        assert!((radius - 51f32.sqrt() / 2.0).abs() < 1e-6);
        let clear = Atmosphere::default();
        assert_eq!(Fog::new(clear, Some(objects), &lights, eye), None);
        let far = Atmosphere {
            background_distance: Some(40.0),
            ..fog(1.0)
        };
        let f = Fog::new(far, Some(objects), &lights, eye).unwrap();
        assert_eq!(f.backdrop, Backdrop::Distance(40.0));
    }

    #[test]
    fn a_surface_is_seen_through_all_the_fog_before_it_and_the_background_up_to_the_backdrop() {
        // The box from (−1, −1, −1) to (1, 1, 1): the ball of radius √3 around the origin.
        let box_ = Some(Aabb::new(-Vec3::ONE, Vec3::ONE));
        let f = Fog::new(fog(1.0), box_, &[], Vec3::ZERO).unwrap();
        let r = 3f32.sqrt();
        // A surface anywhere, inside the ball or far outside it: all the way.
        let origin = Vec3::new(-5.0, 0.0, 0.0);
        for end in [3.0, 5.0, 100.0] {
            let segment = f.segment(origin, Vec3::X, 0.5, end).unwrap();
            assert_eq!(segment, Segment { start: 0.5, end });
            let t = f.transmittance(origin, Vec3::X, 0.0, end);
            assert!((t - (-end).exp()).abs() < 1e-6);
        }
        // Nothing met: up to where the ray leaves the ball.
        let through = f.segment(origin, Vec3::X, 0.0, f32::INFINITY).unwrap();
        assert!((through.end - (5.0 + r)).abs() < 1e-5, "{through:?}");
        assert!(
            (f.segment(Vec3::ZERO, Vec3::Y, 0.0, f32::INFINITY)
                .unwrap()
                .end
                - r)
                .abs()
                < 1e-6
        );
        // Turned away from the ball, or passing beside it: the backdrop is at the start.
        assert_eq!(f.segment(origin, -Vec3::X, 0.0, f32::INFINITY), None);
        assert_eq!(f.transmittance(origin, -Vec3::X, 0.0, f32::INFINITY), 1.0);
        let beside = Vec3::new(-5.0, 2.0, 0.0);
        assert_eq!(f.segment(beside, Vec3::X, 0.0, f32::INFINITY), None);
        // A backdrop at a distance, or nowhere.
        let at = |d| Fog {
            backdrop: Backdrop::Distance(d),
            ..f
        };
        assert_eq!(
            at(7.0).segment(beside, Vec3::X, 0.0, f32::INFINITY),
            Some(Segment {
                start: 0.0,
                end: 7.0
            })
        );
        assert_eq!(
            at(f32::INFINITY).transmittance(beside, Vec3::X, 0.0, f32::INFINITY),
            0.0
        );
    }
}
