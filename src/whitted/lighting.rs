//! The local colour at a hit (the lecture's shading model): the surface's own emission and
//! ambient light, plus the diffuse
//! (Lambert) and specular (Phong) light of every light that a shadow ray reaches, plus, with
//! caustics on, the diffuse light of the caustic photons nearby. Transparent blockers tint the
//! light that passes them, and those filled with a medium dim it by the length the shadow ray
//! travels inside them (Beer–Lambert).

use std::ops::ControlFlow;

use glam::Vec3;

use super::shadow_cache;
use super::{LightTerms, LocalTerms, ShadowEvent, Tracer, TreeObserver, reflect};
use crate::color::Color;
use crate::material::Material;
use crate::primitive::{Hit, PrimId, PrimKind, SurfacePoint};
use crate::ray::{Ray, offset_origin};
use crate::shapes::Shape;
use crate::stats::RayCounts;

impl Tracer<'_> {
    /// Emission and ambient, plus the diffuse and specular light of every light the point can
    /// see.
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
        let terms = LocalTerms {
            emission: self.emission(material, surface),
            ambient: material.ambient * base * settings.ambient,
        };
        observer.local_terms(terms);
        let mut color = terms.emission + terms.ambient;
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
            if light_color == Color::ZERO && !O::RECORDS_TERMS {
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
            observer.light(LightTerms {
                light: light_index,
                diffuse,
                specular,
                unshadowed: sample.color,
                arrived: light_color,
            });
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
                && self.tint(ray, &hit) == Color::ZERO
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
    /// per object) times the transmittance `exp(−τ)` of the media inside them, `τ` the sum of
    /// their optical depths ([`Self::optical_depth`]); and the opaque primitive that ended the
    /// search, if one did. `on_blocker` hears of each primitive met, with its tint.
    pub(super) fn transmittance_and_blocker(
        &self,
        ray: &Ray,
        distance: f32,
        cost: &mut impl crate::bvh::cost::TraversalCost,
        on_blocker: impl FnMut(&Hit, Color),
    ) -> (Color, Option<PrimId>) {
        // A flag checked once: in scenes without media the search sums no optical depths.
        if !self.media {
            return self.tints(ray, distance, cost, on_blocker, |_| {});
        }
        let mut depth = 0.0;
        let add_depth = |hit: &Hit| depth += self.optical_depth(ray, distance, hit);
        let (passed, blocker) = self.tints(ray, distance, cost, on_blocker, add_depth);
        (passed * (-depth.max(0.0)).exp(), blocker)
    }

    /// The product of the tints of the blockers along `ray` up to `distance`, and the opaque
    /// primitive that ended the search, if one did; `on_blocker` hears of each primitive met,
    /// with its tint, and `on_passed` of each the light passes.
    fn tints(
        &self,
        ray: &Ray,
        distance: f32,
        cost: &mut impl crate::bvh::cost::TraversalCost,
        mut on_blocker: impl FnMut(&Hit, Color),
        mut on_passed: impl FnMut(&Hit),
    ) -> (Color, Option<PrimId>) {
        let mut passed = Color::ONE;
        let mut blocker = None;
        self.bvh
            .any_hit_counted(&self.scene.geometry, ray, 0.0, distance, cost, |hit| {
                let tint = self.tint(ray, hit);
                on_blocker(hit, tint);
                passed *= tint;
                if passed == Color::ZERO {
                    blocker = (tint == Color::ZERO).then_some(hit.prim);
                    ControlFlow::Break(())
                } else {
                    on_passed(hit);
                    ControlFlow::Continue(())
                }
            });
        (passed, blocker)
    }

    /// The optical depth `σ·length` that the shadow `ray` (up to `distance`) adds by running
    /// through the medium inside the primitive of `hit`, the first hit the search met on it.
    ///
    /// The hits come in no particular order, but the length inside an object is the sum of
    /// `+t` at each crossing out of it and `−t` at each crossing into it (a ray that starts
    /// inside has only the crossing out). A mesh triangle is met once and adds its own term; an
    /// object (a sphere, a box, a CSG solid) is met once, at its first crossing, so its later
    /// crossings are found here by intersecting it again past each one. Inside an object the
    /// medium is that of the surface the ray entered by (the one it leaves by, if it starts
    /// inside). A light inside an object is taken to be outside it: the object's part adds
    /// nothing then, the sum being kept from going below zero.
    fn optical_depth(&self, ray: &Ray, distance: f32, hit: &Hit) -> f32 {
        let geometry = &self.scene.geometry;
        let materials = &self.scene.materials;
        // The density of the medium behind the crossing at `crossing`, and whether the ray
        // passes out there.
        let crossing = |crossing: &Hit| {
            let surface = geometry.surface(ray, crossing);
            let medium = materials[surface.material as usize].medium;
            let density = medium.map_or(0.0, |m| m.density);
            (density, ray.dir.dot(surface.geometric_normal) > 0.0)
        };
        let has_medium = materials[geometry.material(hit) as usize].medium.is_some();
        let length = ray.dir.length();
        let object = match hit.prim.kind() {
            PrimKind::Object(o) => &geometry.objects[o],
            PrimKind::Triangle(_) | PrimKind::Instance(_) if !has_medium => return 0.0,
            PrimKind::Triangle(_) | PrimKind::Instance(_) => {
                let (density, leaving) = crossing(hit);
                let sign = if leaving { 1.0 } else { -1.0 };
                return sign * density * hit.t * length;
            }
        };
        // A CSG solid's operands may differ in material; any other object has one.
        if !has_medium && !matches!(object.shape, Shape::Csg(_)) {
            return 0.0;
        }
        let mut depth = 0.0;
        // Where the ray entered, with the density inside: the ray's start if it starts inside.
        let mut inside: Option<(f32, f32)> = None;
        let mut next = Some(*hit);
        while let Some(at) = next {
            let (density, leaving) = crossing(&at);
            if leaving {
                let (start, density) = inside.unwrap_or((0.0, density));
                depth += density * (at.t - start) * length;
                inside = None;
            } else {
                inside = Some((at.t, density));
            }
            next = geometry.intersect(hit.prim, ray, at.t, distance);
        }
        depth
    }

    /// What a primitive met by `ray` at `hit` lets through of the light behind it:
    /// `transparency × colour`; nothing through glass that bends light when the caustic photons
    /// bring that light instead; all of it where its surface is cut away.
    fn tint(&self, ray: &Ray, hit: &Hit) -> Color {
        if self.opaque {
            return Color::ZERO;
        }
        if self.cut_away(ray, hit) {
            return Color::ONE;
        }
        let material = &self.scene.materials[self.scene.geometry.material(hit) as usize];
        if self.caustics.is_some() && material.bends_light() {
            return Color::ZERO;
        }
        material.filter()
    }
}
