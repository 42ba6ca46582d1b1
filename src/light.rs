//! Lights: coloured point lights and directional lights (a light at infinity).

use glam::Vec3;

use crate::color::Color;

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// Light from a point, the same in every direction (no fall-off, as in the lecture).
    Point { position: Vec3, color: Color },
    /// Parallel light arriving along `-direction`: `direction` points towards the light.
    Directional { direction: Vec3, color: Color },
}

/// Where a light is seen from a surface point: the unit direction towards it, the distance a
/// shadow ray must cover, and its colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightSample {
    pub dir: Vec3,
    pub distance: f32,
    pub color: Color,
}

impl Light {
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
        }
    }
}
