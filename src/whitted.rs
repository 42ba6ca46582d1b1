//! The Whitted integrator: the colour seen along a ray, found by building the lecture's ray
//! tree. At each hit: ambient light, a shadow ray to each light for its diffuse and specular
//! share, then a reflected ray and, through transparent surfaces, a transmitted ray bent by
//! Snell's law, recursively, until a ray leaves the scene, `max_depth` is reached, or the
//! branch's weight falls below `min_weight` (adaptive depth control).

use std::ops::ControlFlow;

use glam::Vec3;

use crate::bvh::Bvh;
use crate::material::{Color, Material};
use crate::primitive::{Hit, PrimId, SurfacePoint};
use crate::ray::{Ray, offset_origin};
use crate::scene::Scene;
use crate::shadow_cache;
use crate::stats::RayCounts;

/// Eye rays start at the eye but only see what lies beyond the image plane, at `t = 1`.
pub const EYE_RAY_T_MIN: f32 = 1.0;

/// A scene and its BVH, ready to trace.
#[derive(Clone, Copy)]
pub struct Tracer<'a> {
    pub scene: &'a Scene,
    pub bvh: &'a Bvh,
}

/// How a surface splits what is not absorbed between the reflected and the transmitted ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scattering {
    pub reflect: f32,
    pub transmit: f32,
    /// Direction of the transmitted ray, `None` under total internal reflection.
    pub refracted: Option<Vec3>,
}

impl<'a> Tracer<'a> {
    pub fn new(scene: &'a Scene, bvh: &'a Bvh) -> Self {
        Tracer { scene, bvh }
    }

    /// The closest hit along `ray` beyond `t_min`.
    pub fn closest_hit(&self, ray: &Ray, t_min: f32) -> Option<Hit> {
        self.bvh
            .closest_hit(&self.scene.geometry, ray, t_min, f32::INFINITY)
    }

    /// The colour seen by the eye ray `ray` (depth 1, weight 1).
    pub fn trace_eye(&self, ray: &Ray, counts: &mut RayCounts) -> Color {
        counts.primary += 1;
        match self.closest_hit(ray, EYE_RAY_T_MIN) {
            Some(hit) => {
                counts.primary_hits += 1;
                self.shade(ray, &hit, 1, 1.0, counts)
            }
            None => self.scene.settings.background,
        }
    }

    /// The colour seen along a secondary ray at `depth` carrying `weight`.
    fn trace(&self, ray: &Ray, depth: u32, weight: f32, counts: &mut RayCounts) -> Color {
        match self.closest_hit(ray, 0.0) {
            Some(hit) => self.shade(ray, &hit, depth, weight, counts),
            None => self.scene.settings.background,
        }
    }

    /// The surface's colour: its texture's if it has one (and textures are on).
    pub fn base_color(&self, material: &Material, surface: &SurfacePoint) -> Color {
        match material.texture {
            Some(t) if self.scene.settings.textures => {
                self.scene.textures[t as usize].color(surface.uv, surface.object_point)
            }
            _ => material.color,
        }
    }

    /// The colour at a hit: the local (Phong) colour plus the reflected and transmitted rays.
    fn shade(
        &self,
        ray: &Ray,
        hit: &Hit,
        depth: u32,
        weight: f32,
        counts: &mut RayCounts,
    ) -> Color {
        let settings = &self.scene.settings;
        let surface = self.scene.geometry.surface(ray, hit);
        let material = &self.scene.materials[surface.material as usize];
        let base = self.base_color(material, &surface);
        let dir = ray.dir.normalize();
        // Face the normals towards the side the ray came from.
        let entering = dir.dot(surface.geometric_normal) < 0.0;
        let side = if entering { 1.0 } else { -1.0 };
        let normal = surface.normal * side;
        let geometric_normal = surface.geometric_normal * side;

        let mut color = self.local_color(
            material,
            base,
            &surface,
            normal,
            geometric_normal,
            dir,
            counts,
        );

        if depth >= settings.max_depth {
            return color;
        }
        let scattering = scattering(material, dir, normal, entering);
        let reflect_weight = weight * scattering.reflect;
        if settings.reflections && scattering.reflect > 0.0 && reflect_weight >= settings.min_weight
        {
            counts.reflected += 1;
            let reflected = Ray::new(
                offset_origin(surface.point, geometric_normal),
                reflect(dir, normal),
            );
            color += scattering.reflect * self.trace(&reflected, depth + 1, reflect_weight, counts);
        }
        let transmit_weight = weight * scattering.transmit;
        if let Some(refracted) = scattering.refracted
            && settings.refractions
            && scattering.transmit > 0.0
            && transmit_weight >= settings.min_weight
        {
            counts.transmitted += 1;
            let transmitted = Ray::new(offset_origin(surface.point, -geometric_normal), refracted);
            color += scattering.transmit
                * base
                * self.trace(&transmitted, depth + 1, transmit_weight, counts);
        }
        color
    }

    /// Ambient, plus the diffuse and specular light of every light the point can see.
    #[allow(clippy::too_many_arguments)]
    fn local_color(
        &self,
        material: &Material,
        base: Color,
        surface: &SurfacePoint,
        normal: Vec3,
        geometric_normal: Vec3,
        dir: Vec3,
        counts: &mut RayCounts,
    ) -> Color {
        let settings = &self.scene.settings;
        let mut color = material.ambient * base * settings.ambient;
        let shadow_origin = offset_origin(surface.point, geometric_normal);
        for (light_index, light) in self.scene.lights.iter().enumerate() {
            let sample = light.sample(surface.point);
            // A light behind the surface (as seen from the ray's side) adds nothing and needs
            // no shadow ray.
            let cos_l = normal.dot(sample.dir);
            if cos_l <= 0.0 || geometric_normal.dot(sample.dir) <= 0.0 {
                continue;
            }
            let light_color = if settings.shadows {
                counts.shadow += 1;
                let shadow_ray = Ray::new(shadow_origin, sample.dir);
                sample.color * self.light_transmittance(light_index, &shadow_ray, sample.distance)
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
        color
    }

    /// The fraction of light that reaches `origin` from `distance` away along `dir`: zero if
    /// an opaque object is in between, otherwise the product of the transparent blockers'
    /// tints (`transparency × colour`, once per object).
    pub fn transmittance(&self, origin: Vec3, dir: Vec3, distance: f32) -> Color {
        self.transmittance_and_blocker(&Ray::new(origin, dir), distance)
            .0
    }

    /// [`Self::transmittance`] along the shadow ray `ray` towards light `light`, trying the
    /// light's last blocker on this thread first (see [`crate::shadow_cache`]).
    fn light_transmittance(&self, light: usize, ray: &Ray, distance: f32) -> Color {
        let geometry = &self.scene.geometry;
        if let Some(id) = shadow_cache::last_blocker(light)
            && geometry.contains(id)
            && self.tint(id) == Color::ZERO
            && geometry.intersect(id, ray, 0.0, distance).is_some()
        {
            return Color::ZERO;
        }
        let (passed, blocker) = self.transmittance_and_blocker(ray, distance);
        shadow_cache::remember(light, blocker);
        passed
    }

    /// The transmittance along `ray` up to `distance`, and the opaque primitive that ended the
    /// search, if one did.
    fn transmittance_and_blocker(&self, ray: &Ray, distance: f32) -> (Color, Option<PrimId>) {
        let mut passed = Color::ONE;
        let mut blocker = None;
        self.bvh
            .any_hit(&self.scene.geometry, ray, 0.0, distance, |hit| {
                let tint = self.tint(hit.prim);
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

    /// What a primitive lets through of the light behind it: `transparency × colour`.
    fn tint(&self, id: PrimId) -> Color {
        let material = &self.scene.materials[self.scene.geometry.material(id) as usize];
        material.transparency * material.color
    }
}

/// Mirror direction of `d` about the unit normal `n`.
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Direction of a ray `d` (unit) refracted through a surface with unit normal `n` facing the
/// incoming ray, with `eta = n1 / n2` (Snell's law); `None` past the critical angle.
pub fn refract(d: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}

/// The reflected and transmitted weights at a surface. Entering, the ray goes from index 1
/// into `ior`; leaving, the other way round. Under total internal reflection the transmitted
/// share is reflected. With `fresnel`, Schlick's reflectance moves light from transmission to
/// reflection at grazing angles.
pub fn scattering(material: &Material, dir: Vec3, normal: Vec3, entering: bool) -> Scattering {
    let mut reflect = material.reflectivity;
    let mut transmit = material.transparency;
    if transmit == 0.0 {
        return Scattering {
            reflect,
            transmit,
            refracted: None,
        };
    }
    let (n1, n2) = if entering {
        (1.0, material.ior)
    } else {
        (material.ior, 1.0)
    };
    let refracted = refract(dir, normal, n1 / n2);
    match refracted {
        None => {
            reflect += transmit;
            transmit = 0.0;
        }
        Some(t) if material.fresnel => {
            // Schlick's formula wants the angle on the optically thinner side.
            let cos = if n1 <= n2 {
                -dir.dot(normal)
            } else {
                -t.dot(normal)
            };
            let fresnel = Material::schlick(cos, n1, n2);
            reflect += transmit * fresnel;
            transmit *= 1.0 - fresnel;
        }
        Some(_) => {}
    }
    Scattering {
        reflect,
        transmit,
        refracted,
    }
}
