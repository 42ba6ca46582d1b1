//! Lights: coloured point lights, directional lights (a light at infinity) and spot lights (a
//! point light that shines into a cone).

use glam::Vec3;

use crate::color::Color;

/// A light of the scene.
#[derive(Clone, Copy, Debug, PartialEq, strum::EnumDiscriminants)]
#[strum_discriminants(
    name(LightKind),
    doc = "The kinds of light, one per variant of `Light`.",
    derive(Hash, strum::EnumIter)
)]
pub enum Light {
    /// Light from a point, the same in every direction (no fall-off, as in the lecture).
    Point { position: Vec3, color: Color },
    /// Parallel light arriving along `-direction`: `direction` points towards the light.
    Directional { direction: Vec3, color: Color },
    /// Light from a point into a cone around `direction`, see [`Spot`].
    Spot(Spot),
}

/// A spot light: a point light at `position` shining into the cone of half-angle `angle`
/// around `direction`. Unlike [`Light::Point`] it falls off with the square of the distance,
/// as a real lamp does: `color` is its intensity `I`, and a surface at distance `r` whose normal
/// makes the angle θ with the direction to the light receives the irradiance `I·cos θ / r²`.
/// Across the cone's soft edge, the last `falloff` degrees inside `angle`, the light fades
/// from full to nothing by a smoothstep of the cosine of the angle off the axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spot {
    pub position: Vec3,
    /// Unit vector along the cone's axis, away from the light.
    pub direction: Vec3,
    /// Cosine of the half-angle of the cone: no light outside it.
    pub cos_angle: f32,
    /// Cosine of `angle − falloff`: full light inside it.
    pub cos_full: f32,
    pub color: Color,
}

impl Spot {
    /// A spot light; `angle` (the cone's half-angle) and `falloff` (its soft edge) are in
    /// degrees, with `0 < angle ≤ 90` and `0 ≤ falloff ≤ angle`, and `direction` is a unit vector.
    pub fn new(position: Vec3, direction: Vec3, angle: f32, falloff: f32, color: Color) -> Spot {
        Spot {
            position,
            direction,
            cos_angle: angle.to_radians().cos(),
            cos_full: (angle - falloff).to_radians().cos(),
            color,
        }
    }

    /// [`Light::sample`] of the spot: the inverse-square law times the cone.
    #[inline(never)]
    fn sample(&self, point: Vec3) -> LightSample {
        let to_light = self.position - point;
        let distance_squared = to_light.length_squared();
        let distance = distance_squared.sqrt();
        let dir = to_light / distance;
        LightSample {
            dir,
            distance,
            color: self.color * (self.cone(-dir) / distance_squared),
        }
    }

    /// The share of the light that leaves towards the unit vector `dir` (from the light): 1
    /// inside the full cone, 0 outside the cone, a smoothstep across the soft edge.
    pub fn cone(&self, dir: Vec3) -> f32 {
        let cos = self.direction.dot(dir);
        if cos >= self.cos_full {
            1.0
        } else if cos <= self.cos_angle {
            0.0
        } else {
            let x = (cos - self.cos_angle) / (self.cos_full - self.cos_angle);
            x * x * (3.0 - 2.0 * x)
        }
    }
}

/// Where a light is seen from a surface point: the unit direction towards it, the distance a
/// shadow ray must cover, and the colour that arrives (before any blocker).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    pub dir: Vec3,
    pub distance: f32,
    pub color: Color,
}

impl Light {
    /// Where the light is seen from `point`. Inlined into the shading; a spot's own sampling is
    /// not, to keep the shading's code small.
    #[inline(always)]
    pub fn sample(&self, point: Vec3) -> LightSample {
        match *self {
            Light::Point { position, color } => {
                let to_light = position - point;
                let distance = to_light.length();
                LightSample {
                    dir: to_light / distance,
                    distance,
                    color,
                }
            }
            Light::Directional { direction, color } => LightSample {
                dir: direction,
                distance: f32::INFINITY,
                color,
            },
            Light::Spot(spot) => spot.sample(point),
        }
    }

    /// The same light with its colour scaled.
    pub fn scaled(&self, factor: f32) -> Light {
        match *self {
            Light::Point { position, color } => Light::Point {
                position,
                color: color * factor,
            },
            Light::Directional { direction, color } => Light::Directional {
                direction,
                color: color * factor,
            },
            Light::Spot(spot) => Light::Spot(Spot {
                color: spot.color * factor,
                ..spot
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spot(angle: f32, falloff: f32) -> Spot {
        Spot::new(Vec3::ZERO, -Vec3::Y, angle, falloff, Color::ONE)
    }

    /// The unit vector `degrees` off the downward axis.
    fn off_axis(degrees: f32) -> Vec3 {
        let a = degrees.to_radians();
        Vec3::new(a.sin(), -a.cos(), 0.0)
    }

    #[test]
    fn the_cone_is_full_inside_dark_outside_and_smooth_between() {
        let s = spot(30.0, 10.0);
        assert_eq!(s.cone(off_axis(0.0)), 1.0);
        assert_eq!(s.cone(off_axis(19.9)), 1.0);
        assert_eq!(s.cone(off_axis(30.1)), 0.0);
        assert_eq!(s.cone(Vec3::Y), 0.0);
        let band: Vec<f32> = (1..10).map(|d| s.cone(off_axis(20.0 + d as f32))).collect();
        assert!(band.windows(2).all(|w| w[0] > w[1]), "{band:?}");
        assert!(band.iter().all(|&c| c > 0.0 && c < 1.0), "{band:?}");
        // A hard edge: no band at all.
        let hard = spot(30.0, 0.0);
        assert_eq!(hard.cone(off_axis(29.9)), 1.0);
        assert_eq!(hard.cone(off_axis(30.1)), 0.0);
    }

    #[test]
    fn a_spot_falls_off_with_the_square_of_the_distance() {
        let light = Light::Spot(spot(45.0, 0.0));
        let near = light.sample(Vec3::new(0.0, -1.0, 0.0));
        let far = light.sample(Vec3::new(0.0, -3.0, 0.0));
        assert_eq!(near.dir, Vec3::Y);
        assert_eq!(far.distance, 3.0);
        assert!((near.color.x / far.color.x - 9.0).abs() < 1e-5);
    }
}
