//! The local colour at a hit (the lecture's shading model): ambient light, plus the diffuse
//! (Lambert) and specular (Phong) light of every light that a shadow ray reaches, plus, with
//! caustics on, the diffuse light of the caustic photons nearby. Transparent blockers tint the
//! light that passes them.

use std::ops::ControlFlow;

use glam::Vec3;

use super::shadow_cache;
use super::{ShadowEvent, Tracer, TreeObserver, reflect};
use crate::color::Color;
use crate::material::Material;
use crate::photon::bends_light;
use crate::primitive::{Hit, PrimId, SurfacePoint};
use crate::ray::{Ray, offset_origin};
use crate::stats::RayCounts;

impl Tracer<'_> {
    /// Ambient, plus the diffuse and specular light of every light the point can see.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn local_color<O: TreeObserver>(
        &self,
        material: &Material,
        base: Color,
        surface: &SurfacePoint,
        normal: Vec3,
        geometric_normal: Vec3,
        dir: Vec3,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        let settings = &self.scene.settings;
        let mut color = material.ambient * base * settings.ambient;
        let shadow_origin = offset_origin(surface.point, geometric_normal);
        for (light_index, light) in self.scene.lights.iter().enumerate() {
            let mut sample = light.sample(surface.point);
            // A light behind the surface (as seen from the ray's side), or a spot turned away
            // from it, adds nothing and needs no shadow ray.
            let cos_l = normal.dot(sample.dir);
            if cos_l <= 0.0
                || geometric_normal.dot(sample.dir) <= 0.0
                || sample.color == Color::ZERO
            {
                continue;
            }
            self.dim_by_fog(surface.point, &mut sample);
            let light_color = if settings.shadows {
                counts.shadow += 1;
                let shadow_ray = Ray::new(shadow_origin, sample.dir);
                let (passed, blockers) =
                    self.light_transmittance(light_index, &shadow_ray, sample.distance, observer);
                let arrived = sample.color * passed;
                observer.shadow(ShadowEvent {
                    light: light_index,
                    ray: &shadow_ray,
                    distance: sample.distance,
                    blockers: &blockers,
                    arrived,
                });
                arrived
            } else {
                sample.color
            };
            if light_color == Color::ZERO {
                continue;
            }
            let diffuse = material.diffuse * cos_l * base;
            let mirror = reflect(-sample.dir, normal);
            let cos_r = mirror.dot(-dir).max(0.0);
            let specular = if material.specular > 0.0 && cos_r > 0.0 {
                material.specular * cos_r.powf(material.shininess) * material.specular_color
            } else {
                Color::ZERO
            };
            color += light_color * (diffuse + specular);
        }
        if let Some(caustics) = self.caustics
            && material.diffuse > 0.0
        {
            let gather = settings.caustic_gather as usize;
            let irradiance = caustics.irradiance(surface.point, normal, gather);
            observer.caustic(irradiance);
            color += material.diffuse * base * irradiance;
        }
        color
    }

    /// The fraction of light that reaches the origin of the shadow ray `ray` from light `light`
    /// ([`Self::transmittance_and_blocker`]), trying the light's last blocker on this thread
    /// first (see [`super::shadow_cache`]) unless the observer says not to. With an observer that
    /// records blockers, also every primitive the search met, with its tint.
    fn light_transmittance<O: TreeObserver>(
        &self,
        light: usize,
        ray: &Ray,
        distance: f32,
        observer: &mut O,
    ) -> (Color, Vec<(Hit, Color)>) {
        let geometry = &self.scene.geometry;
        let mut blockers = Vec::new();
        if O::USES_SHADOW_CACHE
            && let Some(id) = shadow_cache::last_blocker(light)
            && geometry.contains(id)
        {
            observer.prims_tested(1);
            // Tinted by what is hit: a CSG object's operands may differ.
            if let Some(hit) = geometry.intersect(id, ray, 0.0, distance)
                && self.tint(&hit) == Color::ZERO
            {
                return (Color::ZERO, blockers);
            }
        }
        let (passed, blocker) =
            self.transmittance_and_blocker(ray, distance, observer, |hit, tint| {
                if O::RECORDS_BLOCKERS {
                    blockers.push((*hit, tint));
                }
            });
        shadow_cache::remember(light, blocker);
        (passed, blockers)
    }

    /// The transmittance along `ray` up to `distance`: zero if an opaque object is in between,
    /// otherwise the product of the transparent blockers' tints (`transparency × colour`, once
    /// per object); and the opaque primitive that ended the search, if one did. `on_blocker`
    /// hears of each primitive met, with its tint.
    pub(super) fn transmittance_and_blocker(
        &self,
        ray: &Ray,
        distance: f32,
        cost: &mut impl crate::bvh::cost::TraversalCost,
        mut on_blocker: impl FnMut(&Hit, Color),
    ) -> (Color, Option<PrimId>) {
        let mut passed = Color::ONE;
        let mut blocker = None;
        self.bvh
            .any_hit_counted(&self.scene.geometry, ray, 0.0, distance, cost, |hit| {
                let tint = self.tint(hit);
                on_blocker(hit, tint);
                passed *= tint;
                if passed == Color::ZERO {
                    blocker = (tint == Color::ZERO).then_some(hit.prim);
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            });
        (passed, blocker)
    }

    /// What a primitive lets through of the light behind it: `transparency × colour`; nothing
    /// through glass that bends light when the caustic photons bring that light instead.
    fn tint(&self, hit: &Hit) -> Color {
        let material = &self.scene.materials[self.scene.geometry.material(hit) as usize];
        if self.caustics.is_some() && bends_light(material) {
            return Color::ZERO;
        }
        material.transparency * material.color
    }
}
