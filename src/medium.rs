//! Participating media: a homogeneous fog filling the scene ([`Atmosphere`], the scene file's
//! `[atmosphere]`), and the part of space it fills ([`Fog`]).
//!
//! Light travelling a distance `d` through fog of extinction coefficient `σ` (its `density`,
//! per unit length) keeps the fraction `T(d) = exp(−σ·d)` (Beer–Lambert); of what is lost, the
//! share `albedo` is scattered (`σ_s = albedo·σ`) and the rest absorbed. Scattered light leaves
//! evenly in every direction (the isotropic phase function `1/(4π)`), tinted by `color`. The
//! tracer ([`crate::whitted`]) attenuates every ray by `T` and adds the light the fog scatters
//! into it, see `whitted/fog.rs`.
//!
//! Where the fog ends: fog filling all of space would swallow the background and the light of
//! directional lights (which comes from infinitely far) whole, however thin. So the fog fills
//! the scene's box: the box around its bounded objects, its point and spot lights and the
//! camera's eye ([`Fog::new`]). A ray is attenuated by the length it travels inside that box: a
//! ray to the background by the distance to where it leaves the box (so a backdrop at distance
//! `d` and the background seen past the box's wall at distance `d` are both dimmed by exactly
//! `exp(−σ·d)`), and a shadow ray to a directional light likewise. Infinite planes reach beyond
//! the box: past it they are seen through the fog between them and the box only.

use glam::Vec3;

use crate::aabb::Aabb;
use crate::color::Color;
use crate::light::Light;

/// The isotropic phase function: the share of scattered light that leaves into each unit of
/// solid angle, the same in every direction.
pub const ISOTROPIC_PHASE: f32 = 1.0 / (4.0 * std::f32::consts::PI);

/// A homogeneous fog: the scene file's `[atmosphere]`. A density of zero is clear air.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Atmosphere {
    /// Extinction coefficient σ, per unit length.
    pub density: f32,
    /// Share of the extinction that is scattering, not absorption (0 to 1).
    pub albedo: f32,
    /// Colour of the scattered light.
    pub color: Color,
}

impl Default for Atmosphere {
    /// Clear air.
    fn default() -> Self {
        Atmosphere {
            density: 0.0,
            albedo: 1.0,
            color: Color::ONE,
        }
    }
}

impl Atmosphere {
    /// Whether there is no fog at all.
    pub fn is_clear(&self) -> bool {
        self.density == 0.0
    }

    /// The fraction of light that passes `distance` of this fog (Beer–Lambert).
    pub fn transmittance(&self, distance: f32) -> f32 {
        (-self.density * distance).exp()
    }

    /// The scattering coefficient `σ_s = albedo·σ`, per colour channel.
    pub fn scattering(&self) -> Color {
        self.density * self.albedo * self.color
    }
}

/// The atmosphere of a scene and the box it fills.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fog {
    pub atmosphere: Atmosphere,
    /// The box the fog fills: around the bounded objects, the point and spot lights and the eye.
    pub region: Aabb,
}

/// Where a ray runs through the fog: from distance `start` to `end` along a unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FogSegment {
    pub start: f32,
    pub end: f32,
}

impl FogSegment {
    pub fn length(&self) -> f32 {
        self.end - self.start
    }
}

impl Fog {
    /// The fog of `atmosphere` in the box around `object_bounds`, the positions of `lights` and
    /// `eye`; `None` in clear air.
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
        let region = Aabb::from_points(light_positions)
            .grow(eye)
            .union(object_bounds.unwrap_or(Aabb::EMPTY));
        Some(Fog { atmosphere, region })
    }

    /// The part of the ray `origin + s·dir` (`dir` a unit vector), `start ≤ s ≤ end`, that
    /// lies in the fog; `None` if it misses the fog's box there. This is the slab test, written
    /// out so that a ray parallel to a slab (a zero component of `dir`) is inside it or not by
    /// its origin alone, without the not-a-number of `0·∞`.
    pub fn segment(
        &self,
        origin: Vec3,
        dir: Vec3,
        mut start: f32,
        mut end: f32,
    ) -> Option<FogSegment> {
        for axis in 0..3 {
            let (o, d) = (origin[axis], dir[axis]);
            let (low, high) = (self.region.min[axis], self.region.max[axis]);
            if d == 0.0 {
                if o < low || o > high {
                    return None;
                }
                continue;
            }
            let (t_low, t_high) = ((low - o) / d, (high - o) / d);
            start = start.max(t_low.min(t_high));
            end = end.min(t_low.max(t_high));
        }
        (start < end).then_some(FogSegment { start, end })
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
    fn the_fog_fills_the_box_of_the_objects_the_point_lights_and_the_eye() {
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
        let eye = Vec3::new(0.5, 0.5, -2.0);
        let f = Fog::new(fog(1.0), Some(objects), &lights, eye).unwrap();
        let expected = Aabb::new(Vec3::new(0.0, 0.0, -2.0), Vec3::new(1.0, 5.0, 1.0));
        assert_eq!(f.region, expected);
        let clear = Atmosphere::default();
        assert_eq!(Fog::new(clear, Some(objects), &lights, eye), None);
        // Only a directional light (and maybe infinite planes): the fog is the eye's point, and
        // no ray crosses any of it.
        let f = Fog::new(fog(1.0), None, &lights[1..], eye).unwrap();
        assert_eq!(f.transmittance(eye, Vec3::X, 0.0, f32::INFINITY), 1.0);
    }

    #[test]
    fn a_ray_is_attenuated_only_inside_the_box() {
        let box_ = Some(Aabb::new(Vec3::ZERO, Vec3::splat(2.0)));
        let f = Fog::new(fog(1.0), box_, &[], Vec3::ONE).unwrap();
        // From outside, through the box: two units of fog.
        let origin = Vec3::new(-3.0, 1.0, 1.0);
        let through = f.segment(origin, Vec3::X, 0.0, f32::INFINITY).unwrap();
        assert_eq!((through.start, through.end), (3.0, 5.0));
        assert!(
            (f.transmittance(origin, Vec3::X, 0.0, f32::INFINITY) - (-2f32).exp()).abs() < 1e-6
        );
        // Stopped halfway in, or turned away.
        assert_eq!(f.segment(origin, Vec3::X, 0.0, 4.0).unwrap().length(), 1.0);
        assert_eq!(f.segment(origin, -Vec3::X, 0.0, f32::INFINITY), None);
        assert_eq!(f.transmittance(origin, -Vec3::X, 0.0, f32::INFINITY), 1.0);
    }
}
