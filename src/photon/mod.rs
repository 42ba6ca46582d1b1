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

/// Memory one stored photon takes at the peak, while its map is built from the list: the photon
/// itself, the axis its node splits (a byte) and its 16-byte node.
const BYTES_PER_STORED: u64 = std::mem::size_of::<Photon>() as u64 + 1 + 16;

/// Photons shot in one batch. Before each, the memory of the photons all of them will store is
/// checked, projected from how many those shot so far stored (a photon may land in a caustic
/// more than once, or never).
const BATCH: u32 = 1 << 18;

/// The caustic photon map of the tracer's scene from `count` photons shot; an empty map when no
/// light reaches anything specular. The error says the photons would not fit in memory.
pub fn caustic_map(tracer: &Tracer, count: u32) -> Result<PhotonMap, String> {
    let mut caustics = Caustics::new(tracer);
    caustics.shoot(tracer, count)?;
    Ok(caustics.into_map())
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

    /// Shoots `count` more photons, a batch at a time. Before each batch the memory the map of
    /// all of them takes at its peak is checked, the photons they will store projected from
    /// those stored so far (before the first batch, the batch's own photons, each stored once);
    /// the error says it would not fit.
    pub fn shoot(&mut self, tracer: &Tracer, count: u32) -> Result<(), String> {
        let end = self.shot.saturating_add(count);
        let Some(source) = &self.source else {
            self.shot = end;
            return Ok(());
        };
        while self.shot < end {
            let batch = BATCH.min(end - self.shot);
            let (expected, what) = match self.shot {
                0 => (
                    u64::from(batch),
                    format!("the first {batch} of {end} caustic photons"),
                ),
                shot => {
                    let expected = self.stored.len() as u64 * u64::from(end) / u64::from(shot);
                    let what = format!("a map of {end} caustic photons (about {expected} stored)");
                    (expected, what)
                }
            };
            memory::check(&what, expected * BYTES_PER_STORED)?;
            if self.shot > 0 {
                let more = (expected as usize).saturating_sub(self.stored.len());
                self.stored.reserve_exact(more);
            }
            source.shoot(tracer, self.shot, batch, &mut self.stored);
            self.shot += batch;
        }
        Ok(())
    }

    /// The photons shot so far.
    pub fn shot(&self) -> u32 {
        self.shot
    }

    /// The map of the photons stored so far, which go on growing as more are shot: a copy of
    /// them is made into the map. The error says it would not fit in memory.
    pub fn map(&self) -> Result<PhotonMap, String> {
        let photons = self.stored.len() as u64;
        memory::check(
            &format!("a map of {photons} caustic photons beside the list it grows from"),
            photons * (BYTES_PER_STORED + std::mem::size_of::<Photon>() as u64),
        )?;
        Ok(self.clone().into_map())
    }

    /// The map of the photons stored, made of their list without a copy.
    pub fn into_map(self) -> PhotonMap {
        PhotonMap::build(self.stored, u64::from(self.shot), self.max_radius)
    }
}
