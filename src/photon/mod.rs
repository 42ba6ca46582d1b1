//! Caustics by photon mapping (Jensen): light that reaches a diffuse surface only by way of
//! mirrors and glass, which the Whitted tracer's shadow rays cannot find. Before the image is
//! traced, photons leave the lights towards the specular objects (`emit`), follow their
//! reflections and refractions (`trace`), and are stored where they land on diffuse surfaces
//! after at least one specular turn: the caustic photon map ([`crate::photon_map`]), a kd-tree. At each diffuse
//! hit the tracer adds the irradiance of the nearest photons ([`PhotonMap::irradiance`]).
//!
//! The photons carry light as it really spreads, falling off with the square of the distance:
//! a light of intensity `I` gives a surface at distance `r` the irradiance `I·cos θ / r²`, as
//! spot lights do. (Point lights light surfaces directly without that fall-off, as in the
//! lecture, so scenes made for caustics light them with spot lights.) The map depends on the
//! lights and objects only, not on the camera.

mod emit;
mod trace;

pub use crate::photon_map::{Photon, PhotonMap};
pub use trace::PhotonSource;

use crate::memory;
use crate::whitted::Tracer;

/// How far an estimate looks for photons at most, as a share of the size of the scene (the
/// diagonal of its bounded objects' box).
const MAX_RADIUS_SHARE: f32 = 0.05;

/// Memory one stored photon takes at most while its map is built: a copy in the list, one in the
/// tree, and its 16-byte node.
const BYTES_PER_PHOTON: u64 = 2 * std::mem::size_of::<Photon>() as u64 + 16;

/// The caustic photon map of the tracer's scene from `count` photons shot; an empty map when no
/// light reaches anything specular. The error says the photons would not fit in memory.
pub fn caustic_map(tracer: &Tracer, count: u32) -> Result<PhotonMap, String> {
    let mut caustics = Caustics::new(tracer);
    caustics.shoot(tracer, count)?;
    Ok(caustics.map())
}

/// A caustic photon map that grows: more photons shot sharpen the same caustics (each photon's
/// power is shared with all the photons shot, and the estimates gather from nearer).
#[derive(Clone, Debug)]
pub struct Caustics {
    source: Option<PhotonSource>,
    stored: Vec<Photon>,
    shot: u32,
    max_radius: f32,
}

impl Caustics {
    /// No photons shot yet.
    pub fn new(tracer: &Tracer) -> Caustics {
        let size = tracer.scene.geometry.finite_bounds().extent().length();
        Caustics {
            source: PhotonSource::new(tracer.scene),
            stored: Vec::new(),
            shot: 0,
            max_radius: if size.is_finite() && size > 0.0 {
                size * MAX_RADIUS_SHARE
            } else {
                1.0
            },
        }
    }

    /// Shoots `count` more photons. Most land at most once in a caustic; the memory of one
    /// stored photon for each photon shot is checked first, and the error says it would not fit.
    pub fn shoot(&mut self, tracer: &Tracer, count: u32) -> Result<(), String> {
        let total = u64::from(self.shot) + u64::from(count);
        memory::check(
            &format!("a map of {total} caustic photons"),
            total * BYTES_PER_PHOTON,
        )?;
        if let Some(source) = &self.source {
            let more = source.shoot(tracer, self.shot, count);
            self.stored.extend(more);
        }
        self.shot = self.shot.saturating_add(count);
        Ok(())
    }

    /// The photons shot so far.
    pub fn shot(&self) -> u32 {
        self.shot
    }

    /// The map of the photons stored so far.
    pub fn map(&self) -> PhotonMap {
        PhotonMap::build(self.stored.clone(), u64::from(self.shot), self.max_radius)
    }
}
