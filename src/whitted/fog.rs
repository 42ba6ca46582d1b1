//! Fog and other media along the rays of the ray tree (the scene's [`crate::medium::Fog`], and
//! the media inside objects): every ray that runs through one is attenuated by Beer–Lambert and
//! gains the light the medium scatters into it (single scattering), and light reaching a
//! surface is attenuated by the fog on its way from the light (and by the media inside the
//! objects it passes, see `lighting`).
//!
//! The light scattered towards the start of a ray by the medium between `a` and `b` (distances
//! along the ray) is
//!
//! ```text
//! L_s = ∫ₐᵇ T(s − a) · σ_s · phase · Σ_lights L_light(x(s)) · V(x(s)) · T_light(x(s)) ds
//! ```
//!
//! with `T` the transmittance of the medium, `σ_s` its scattering coefficient (times its
//! colour), `phase` the isotropic phase function, and for each light what arrives at the point
//! `x(s)`: its colour `L_light`, `V` what a shadow ray from `x(s)` lets through (0 in shadow, so
//! shadows cast dark beams; the media of the objects it passes dim it) and `T_light` the fog's
//! transmittance along that shadow ray. The integral is estimated light by light with
//! `fog_steps` stratified samples: the samples' range is cut into equal strata and each is
//! sampled at one jittered point, crowded where the medium still lets light through or, for
//! spot lights, equiangularly ([`Spread`]), so a segment of any length, out to the horizon, is
//! covered by the same number of samples. The jitter is a hash of the ray itself, so a pixel
//! comes out the same whatever thread renders it, and neighbouring pixels' errors differ,
//! which the eye sees as fine noise rather than bands.
//!
//! Rays inside objects (a transmitted ray in a glass ball) are in no fog: the fog fills the
//! space between objects. Inside an object whose material has a medium, the segment is the
//! ray's, from its start to the next surface, and the medium is the material's.

use glam::Vec3;

use super::Within;
use super::{Tracer, TreeObserver};
use crate::color::Color;
use crate::light::{Light, LightSample};
use crate::medium::{Fog, ISOTROPIC_PHASE, Medium, Segment};
use crate::ray::Ray;
use crate::sampling::{hash, jitter};
use crate::stats::RayCounts;

impl Tracer<'_> {
    /// What reaches the start of `ray` when `color` leaves its point at parameter `t_end` (the
    /// hit; infinity for the background): `color` attenuated by the fog in between, plus the
    /// light the fog scatters into the ray. Unchanged without fog: only this test is inlined
    /// into the tracer, so that scenes without fog trace as fast as before.
    #[inline(always)]
    pub(super) fn through_fog<O: TreeObserver>(
        &self,
        ray: &Ray,
        t_end: f32,
        color: Color,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        match &self.fog {
            Some(_) => self.through_medium(Within::Fog, ray, t_end, color, counts, observer),
            None => color,
        }
    }

    /// [`Self::through_fog`] for a ray in the medium `within` says: the fog, or the medium
    /// inside an object.
    #[inline(never)]
    pub(super) fn through_medium<O: TreeObserver>(
        &self,
        within: Within,
        ray: &Ray,
        t_end: f32,
        color: Color,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        let length = ray.dir.length();
        let dir = ray.dir / length;
        let (fog, materials) = (self.fog.as_ref(), &self.scene.materials);
        let end = t_end * length;
        let Some((medium, segment)) = within.segment(fog, materials, ray.origin, dir, end) else {
            observer.fog(1.0, Color::ZERO);
            return color;
        };
        let transmittance = medium.transmittance(segment.length());
        let in_scattered = self.in_scattered(&medium, ray.origin, dir, segment, counts, observer);
        observer.fog(transmittance, in_scattered);
        transmittance * color + in_scattered
    }

    /// The light `medium` scatters towards `origin` from the `segment` of the ray along the
    /// unit vector `dir`: the integral of the module's comment, light by light, each by
    /// `fog_steps` stratified samples spread as [`Spread`] says.
    fn in_scattered<O: TreeObserver>(
        &self,
        medium: &Medium,
        origin: Vec3,
        dir: Vec3,
        segment: Segment,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        if medium.is_clear() {
            return Color::ZERO;
        }
        let steps = self.scene.settings.fog_steps;
        let (seed_origin, seed_dir) = (hash_vec3(origin), hash_vec3(dir));
        let mut gathered = Color::ZERO;
        for (index, light) in self.scene.lights.iter().enumerate() {
            let spread = Spread::new(light, origin, dir, segment, medium.density);
            for k in 0..steps {
                // Sample k of the light, jittered inside the k-th of `steps` equal strata.
                let (u, _) = jitter(seed_origin, seed_dir, index as u32 * steps + k);
                let (s, weight) = spread.at((k as f32 + u) / steps as f32);
                let point = origin + dir * s;
                let arriving = self.light_in_medium(light, point, counts, observer);
                gathered += weight * arriving;
            }
        }
        gathered * medium.scattering() * (ISOTROPIC_PHASE / steps as f32)
    }

    /// The light of `light` that arrives at `point`, a point in a medium: what a shadow ray lets
    /// through, attenuated by the fog along it.
    fn light_in_medium<O: TreeObserver>(
        &self,
        light: &Light,
        point: Vec3,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        let mut sample = light.sample(point);
        if sample.color == Color::ZERO {
            return Color::ZERO;
        }
        let passed = if self.scene.settings.shadows {
            counts.shadow += 1;
            let shadow_ray = Ray::new(point, sample.dir);
            let no_record = |_: &_, _| {};
            self.transmittance_and_blocker(&shadow_ray, sample.distance, observer, no_record)
                .0
        } else {
            Color::ONE
        };
        if passed == Color::ZERO {
            return Color::ZERO;
        }
        self.dim_by_fog(point, &mut sample);
        passed * sample.color
    }

    /// Dims `sample`, the light arriving at the surface point `point`, by the fog along the
    /// shadow ray; leaves it without fog (only this test is inlined into the shading).
    #[inline(always)]
    pub(super) fn dim_by_fog(&self, point: Vec3, sample: &mut LightSample) {
        if let Some(fog) = &self.fog {
            dim(fog, point, sample);
        }
    }
}

/// Dims `sample`, the light arriving at `point`, by `fog` on its way from the light.
#[inline(never)]
fn dim(fog: &Fog, point: Vec3, sample: &mut LightSample) {
    sample.color *= fog.transmittance(point, sample.dir, 0.0, sample.distance);
}

/// How a light's sample points are spread along a segment of a medium. Each sample at distance
/// `s` is weighted by `T(s − start) / pdf(s)`, so any spread gives the right integral on
/// average; a spread that is dense where the integrand is large gives it with less noise.
enum Spread {
    /// As the medium's transmittance from the segment's start falls, `pdf(s) ∝ exp(−σ·(s −
    /// start))`: for point and directional lights, whose light changes little along the ray
    /// next to how the fog dims it. On a long segment (a floor plane near the horizon, a
    /// backdrop far away, or none) the samples stay where the fog still lets light through,
    /// and each is weighted by the constant `(1 − exp(−σ·L)) / σ`.
    Transmittance {
        start: f32,
        density: f32,
        /// `1 − exp(−σ·L)`: the share of the light that the whole segment takes away.
        mass: f32,
    },
    /// Equiangular sampling (Kulla and Fajardo, 2012) for spot lights, whose light falls off as
    /// `1/r²`: the samples are spread evenly in the angle under which the light sees the ray,
    /// so they crowd where the ray passes closest to the light, and the weight `1/pdf`, which
    /// grows as `r²`, cancels the fall-off. `foot` is the distance along the ray to the point
    /// nearest the light, `height` the light's distance from the ray, and the angles are those
    /// of the segment's ends seen from the light, measured from the foot.
    Equiangular {
        start: f32,
        density: f32,
        foot: f32,
        height: f32,
        angle_start: f32,
        angle_end: f32,
    },
}

impl Spread {
    /// The spread for `light` along `segment` of the ray from `origin` along the unit vector
    /// `dir`, through a medium of extinction coefficient `density` (more than zero).
    fn new(light: &Light, origin: Vec3, dir: Vec3, segment: Segment, density: f32) -> Spread {
        let by_transmittance = Spread::Transmittance {
            start: segment.start,
            density,
            mass: -(-density * segment.length()).exp_m1(),
        };
        let Light::Spot(spot) = light else {
            return by_transmittance;
        };
        let to_light = spot.position - origin;
        let foot = to_light.dot(dir);
        let height = (to_light - foot * dir).length();
        // A ray through the light itself: no angles to spread over.
        if height <= f32::EPSILON * to_light.length() {
            return by_transmittance;
        }
        Spread::Equiangular {
            start: segment.start,
            density,
            foot,
            height,
            angle_start: ((segment.start - foot) / height).atan(),
            angle_end: ((segment.end - foot) / height).atan(),
        }
    }

    /// The sample at `u` (from 0 to 1): its distance along the ray and its weight
    /// `T(s − start) / pdf(s)`.
    fn at(&self, u: f32) -> (f32, f32) {
        match *self {
            Spread::Transmittance {
                start,
                density,
                mass,
            } => {
                // The inverse of the distribution `(1 − exp(−σ·(s − start))) / mass`.
                let s = start - (-u * mass).ln_1p() / density;
                (s, mass / density)
            }
            Spread::Equiangular {
                start,
                density,
                foot,
                height,
                angle_start,
                angle_end,
            } => {
                let angle = angle_start + u * (angle_end - angle_start);
                let along = height * angle.tan();
                let weight = (angle_end - angle_start) * (height * height + along * along) / height;
                let s = foot + along;
                (s, weight * (-density * (s - start)).exp())
            }
        }
    }
}

/// A hash of a vector's bits, to seed the jitter of a ray's samples.
fn hash_vec3(v: Vec3) -> u32 {
    hash(v.x.to_bits() ^ hash(v.y.to_bits() ^ hash(v.z.to_bits())))
}
