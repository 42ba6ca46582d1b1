//! The Whitted integrator: the colour seen along a ray, found by building the lecture's ray
//! tree. At each hit: ambient light, a shadow ray to each light for its diffuse and specular
//! share (`lighting`), then a reflected ray and, through transparent surfaces, a transmitted
//! ray bent by Snell's law ([`scattering`]), recursively, until a ray leaves the scene,
//! `max_depth` is reached, the branch's weight falls below `min_weight` (adaptive depth
//! control), or the tree has used up its [`RAY_BUDGET`].
//!
//! In a scene with fog (`[atmosphere]`), every ray is attenuated by the fog it crosses and
//! gains the light the fog scatters into it, and shadow rays are attenuated too (`fog`).
//! Rays inside an object whose material has a medium run through that medium the same way
//! ([`crate::medium`] says which medium a ray is in), and shadow rays are attenuated by the
//! length they travel inside such objects (`lighting`).
//!
//! Where a material cuts its surface away by its texture's alpha, rays and shadow rays pass
//! the cut-away points (`cut_outs`).
//!
//! Shadow rays try first the primitive that last blocked the same light on the same thread
//! (the shadow cache of Haines and Greenberg, `shadow_cache`).
//!
//! The tracing functions are generic over a [`TreeObserver`] that hears the tree
//! as it grows. The renderer passes `()`, which compiles away; the inspector
//! ([`crate::inspect`]) records the tree with the very same code.

mod cut_outs;
mod fog;
mod lighting;
mod observer;
mod scattering;
mod shadow_cache;
mod within;

pub use cut_outs::MAX_CUT_OUTS;
pub use observer::{LightTerms, LocalTerms, RayKind, ShadowEvent, StopReason, TreeObserver};
pub use scattering::{Scattering, reflect, refract, scattering};
pub use within::Within;

use crate::bvh::Bvh;
use crate::bvh::packet::PACKET_SIZE;
use crate::color::Color;
use crate::item_buffer::{Item, ItemBuffer, far_limit};
use crate::material::{Material, all_opaque, any_cut_outs};
use crate::medium::Fog;
use crate::photon_map::PhotonMap;
use crate::primitive::{Hit, SurfacePoint};
use crate::ray::{Ray, offset_origin};
use crate::scene::Scene;
use crate::stats::RayCounts;
use crate::texture::Wrap;

/// Eye rays start at the eye but only see what lies beyond the image plane, at `t = 1`.
pub const EYE_RAY_T_MIN: f32 = 1.0;

/// Most reflected and transmitted rays one eye ray's tree may trace. A tree can double at
/// every level (two nested glass balls with `min_weight = 0` and `max_depth = 64` would need
/// about 3·10¹³ rays for one pixel), so the budget bounds the work per pixel, and what the
/// inspector records, at about a millisecond. A full binary tree ten levels deep needs 1022;
/// trees with adaptive depth control on stay far below that. Branches past the budget are cut,
/// depth first, and counted in [`RayCounts::over_budget`].
pub const RAY_BUDGET: u64 = 1024;

/// A scene and its BVH, ready to trace.
#[derive(Clone, Copy)]
pub struct Tracer<'a> {
    pub scene: &'a Scene,
    pub bvh: &'a Bvh,
    /// The scene's fog and its backdrop; `None` in clear air.
    pub fog: Option<Fog>,
    /// The caustic photon map, with caustics on ([`Self::with_caustics`]).
    pub caustics: Option<&'a PhotonMap>,
    /// Whether any material has a medium: shadow rays in scenes without look for none.
    pub media: bool,
    /// Whether every material is opaque (lets no light through) and has no cut-outs: a shadow
    /// ray then stops at the first hit without looking up its material.
    pub opaque: bool,
    /// Whether any material cuts its surface away by its texture's alpha
    /// ([`Material::alpha_cutoff`]): searches then go on past cut-away hits.
    pub cut_outs: bool,
    /// The first hits a raster pass found for the film's pixel centres
    /// ([`Self::with_item_buffer`]).
    pub item_buffer: Option<&'a ItemBuffer>,
}

impl<'a> Tracer<'a> {
    pub fn new(scene: &'a Scene, bvh: &'a Bvh) -> Self {
        let fog = Fog::new(
            scene.atmosphere,
            bvh.bounds(),
            &scene.lights,
            scene.camera.eye,
        );
        Tracer {
            scene,
            bvh,
            fog,
            caustics: None,
            media: scene.materials.iter().any(|m| m.medium.is_some()),
            opaque: all_opaque(&scene.materials),
            cut_outs: any_cut_outs(&scene.materials),
            item_buffer: None,
        }
    }

    /// The same tracer starting the eye rays through the pixel centres of a film from
    /// `item_buffer`'s first hits (the renderer uses it for a film it fits); `None` searches
    /// every eye ray's first hit in full. The image is the same either way.
    pub fn with_item_buffer(self, item_buffer: Option<&'a ItemBuffer>) -> Self {
        Tracer {
            item_buffer,
            ..self
        }
    }

    /// The same tracer adding the light of the caustic photon map `caustics` at diffuse hits,
    /// and no longer letting shadow rays through glass that bends light (the photons bring
    /// that light, in the right place); `None` leaves caustics off.
    pub fn with_caustics(self, caustics: Option<&'a PhotonMap>) -> Self {
        Tracer { caustics, ..self }
    }

    /// The closest hit along `ray` beyond `t_min` (past cut-outs).
    pub fn closest_hit(&self, ray: &Ray, t_min: f32) -> Option<Hit> {
        self.closest_hit_counted(ray, t_min, &mut ())
    }

    /// [`Self::closest_hit`], its search counted in `cost`.
    fn closest_hit_counted(
        &self,
        ray: &Ray,
        t_min: f32,
        cost: &mut impl crate::bvh::cost::TraversalCost,
    ) -> Option<Hit> {
        let geometry = &self.scene.geometry;
        let hit = self
            .bvh
            .closest_hit_counted(geometry, ray, t_min, f32::INFINITY, cost);
        self.past_cut_outs(ray, hit, f32::INFINITY, cost)
    }

    /// The colour seen by the eye ray `ray` (depth 1, weight 1).
    pub fn trace_eye(&self, ray: &Ray, counts: &mut RayCounts) -> Color {
        self.trace_eye_observed(ray, counts, &mut ())
    }

    /// [`Self::trace_eye`], telling `observer` of every ray of the tree.
    pub fn trace_eye_observed<O: TreeObserver>(
        &self,
        ray: &Ray,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        observer.ray(RayKind::Eye, 1, ray, 1.0, Color::ONE);
        let hit = self.closest_hit_counted(ray, EYE_RAY_T_MIN, observer);
        self.shade_eye(ray, hit, counts, observer)
    }

    /// The colours seen by the eye rays `rays` (up to [`PACKET_SIZE`], neighbours in the image),
    /// into `colors`: [`Self::trace_eye`] of each, with the eye rays' first hits found together
    /// ([`Self::first_hits`]).
    pub fn trace_eye_packet(
        &self,
        rays: &[Ray],
        items: &[Option<Item>],
        colors: &mut [Color],
        counts: &mut RayCounts,
    ) {
        let mut hits = [None; PACKET_SIZE];
        let hits = &mut hits[..rays.len()];
        self.first_hits(rays, items, hits, counts);
        for ((ray, hit), color) in rays.iter().zip(hits.iter()).zip(colors) {
            *color = self.shade_eye(ray, *hit, counts, &mut ());
        }
    }

    /// The closest hits of the eye rays `rays` (up to [`PACKET_SIZE`], neighbours in the image)
    /// into `hits`, the rays traced as one packet. Where a ray's `items` entry names its pixel's
    /// item (the film has an item buffer), its hit is searched for only up to the item
    /// ([`far_limit`]), and in full if none is found there; the rays found within their items
    /// are counted in `counts`. A hit on a cut-out goes on past it, each ray on its own.
    pub fn first_hits(
        &self,
        rays: &[Ray],
        items: &[Option<Item>],
        hits: &mut [Option<Hit>],
        counts: &mut RayCounts,
    ) {
        let geometry = &self.scene.geometry;
        let mut limits = [f32::INFINITY; PACKET_SIZE];
        let limits = &mut limits[..rays.len()];
        for ((limit, ray), &item) in limits.iter_mut().zip(rays).zip(items) {
            *limit = far_limit(geometry, item, ray, EYE_RAY_T_MIN);
        }
        self.bvh
            .closest_hits_within(geometry, rays, EYE_RAY_T_MIN, limits, hits);
        for ((ray, hit), &limit) in rays.iter().zip(hits.iter_mut()).zip(limits.iter()) {
            let within_item = limit.is_finite() && hit.is_some();
            if limit.is_finite() && hit.is_none() {
                *hit = (self.bvh).closest_hit(geometry, ray, EYE_RAY_T_MIN, f32::INFINITY);
            }
            *hit = self.past_cut_outs(ray, *hit, f32::INFINITY, &mut ());
            if within_item && hit.is_some() {
                counts.from_item_buffer += 1;
            }
        }
    }

    /// The colour seen by the eye ray `ray`, whose closest hit is `hit`.
    fn shade_eye<O: TreeObserver>(
        &self,
        ray: &Ray,
        hit: Option<Hit>,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        counts.primary += 1;
        let branch = Branch {
            depth: 1,
            weight: 1.0,
            budget_end: counts.reflected + counts.transmitted + RAY_BUDGET,
            within: Within::Fog,
        };
        let color = match hit {
            Some(hit) => {
                counts.primary_hits += 1;
                self.shade(ray, &hit, branch, counts, observer)
            }
            None => self.miss(ray, observer),
        };
        let t_end = hit.map_or(f32::INFINITY, |hit| hit.t);
        let color = self.through_fog(ray, t_end, color, counts, observer);
        observer.done(color);
        color
    }

    /// The colour seen along a secondary ray of `branch`.
    fn trace<O: TreeObserver>(
        &self,
        ray: &Ray,
        branch: Branch,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        let hit = self.closest_hit_counted(ray, 0.0, observer);
        let color = match hit {
            Some(hit) => self.shade(ray, &hit, branch, counts, observer),
            None => self.miss(ray, observer),
        };
        let t_end = hit.map_or(f32::INFINITY, |hit| hit.t);
        let color = match branch.within {
            Within::Fog => self.through_fog(ray, t_end, color, counts, observer),
            Within::Medium(_) => {
                self.through_medium(branch.within, ray, t_end, color, counts, observer)
            }
            Within::Clear => color,
        };
        observer.done(color);
        color
    }

    /// What a ray that leaves the scene sees: the background image where the ray crosses it,
    /// else the background colour.
    #[inline(always)]
    fn miss<O: TreeObserver>(&self, ray: &Ray, observer: &mut O) -> Color {
        let scene = self.scene;
        let on_image = scene.background_image.as_ref().and_then(|image| {
            let aspect = image.width as f32 / image.height as f32;
            let uv = scene.camera.backdrop_uv(ray.dir, aspect)?;
            Some(image.sample(uv, [Wrap::Clamp; 2]))
        });
        let background = on_image.unwrap_or(scene.settings.background);
        observer.miss(background);
        background
    }

    /// The surface's colour: its texture's if it has one (and textures are on), else the
    /// material's, times the mesh's vertex colour.
    pub fn base_color(&self, material: &Material, surface: &SurfacePoint) -> Color {
        let color = match material.texture {
            Some(t) if self.scene.settings.textures => {
                self.scene.textures[t as usize].color(surface.uv, surface.object_point)
            }
            _ => material.color,
        };
        color * surface.vertex_color
    }

    /// The light the surface gives off at `surface`: the material's emission, times its
    /// emission texture there (with textures on).
    pub fn emission(&self, material: &Material, surface: &SurfacePoint) -> Color {
        match material.emission_texture {
            Some(t) if self.scene.settings.textures => {
                let texture = &self.scene.textures[t as usize];
                material.emission * texture.color(surface.uv, surface.object_point)
            }
            _ => material.emission,
        }
    }

    /// The colour at a hit: the local (Phong) colour plus the reflected and transmitted rays.
    fn shade<O: TreeObserver>(
        &self,
        ray: &Ray,
        hit: &Hit,
        branch: Branch,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> Color {
        let Branch { depth, weight, .. } = branch;
        let settings = &self.scene.settings;
        let geometry = &self.scene.geometry;
        let material = &self.scene.materials[geometry.material(hit) as usize];
        let textured = (material.texture.is_some() || material.emission_texture.is_some())
            && settings.textures;
        let surface = geometry.surface_with(ray, hit, textured || O::WANTS_UV);
        let base = self.base_color(material, &surface);
        let dir = ray.dir.normalize();
        // Face the normals towards the side the ray came from.
        let entering = dir.dot(surface.geometric_normal) < 0.0;
        let side = if entering { 1.0 } else { -1.0 };
        let normal = surface.normal * side;
        let geometric_normal = surface.geometric_normal * side;
        observer.hit(hit, &surface, normal, entering);

        let mut color = self.local_color(
            material,
            base,
            &surface,
            normal,
            geometric_normal,
            dir,
            counts,
            observer,
        );
        observer.local(color);

        if depth >= settings.max_depth {
            if material.reflectivity > 0.0 || material.transparency > 0.0 {
                observer.stop(StopReason::MaxDepth);
            }
            return color;
        }
        let scattering = scattering(material, dir, normal, entering);
        let reflect_weight = weight * scattering.reflect;
        if scattering.reflect > 0.0
            && self.traces_branch(RayKind::Reflected, reflect_weight, branch, counts, observer)
        {
            counts.reflected += 1;
            let reflected = Ray::new(
                offset_origin(surface.point, geometric_normal),
                reflect(dir, normal),
            );
            let scale = scattering.reflect_color;
            observer.ray(
                RayKind::Reflected,
                depth + 1,
                &reflected,
                reflect_weight,
                scale,
            );
            let child = branch.child(reflect_weight);
            color += scale * self.trace(&reflected, child, counts, observer);
        }
        let transmit_weight = weight * scattering.transmit;
        match scattering.refracted {
            None if material.transparency > 0.0 => observer.cut(
                RayKind::Transmitted,
                StopReason::TotalInternalReflection,
                weight * material.transparency,
            ),
            Some(refracted)
                if scattering.transmit > 0.0
                    && self.traces_branch(
                        RayKind::Transmitted,
                        transmit_weight,
                        branch,
                        counts,
                        observer,
                    ) =>
            {
                counts.transmitted += 1;
                let transmitted =
                    Ray::new(offset_origin(surface.point, -geometric_normal), refracted);
                let scale = scattering.transmit * base;
                observer.ray(
                    RayKind::Transmitted,
                    depth + 1,
                    &transmitted,
                    transmit_weight,
                    scale,
                );
                // A ray that enters a surface travels inside the object, in its medium if it
                // has one and in no fog.
                let child = Branch {
                    within: Within::after_crossing(
                        &self.scene.materials,
                        surface.material,
                        entering,
                    ),
                    ..branch.child(transmit_weight)
                };
                color += scale * self.trace(&transmitted, child, counts, observer);
            }
            _ => {}
        }
        color
    }

    /// Whether a child ray of `kind` carrying `weight` is traced from `branch`: its kind is
    /// switched on, its weight is at least `min_weight` (adaptive depth control) and the tree
    /// has budget left. If not, the observer hears why.
    #[inline(always)]
    fn traces_branch<O: TreeObserver>(
        &self,
        kind: RayKind,
        weight: f32,
        branch: Branch,
        counts: &mut RayCounts,
        observer: &mut O,
    ) -> bool {
        let settings = &self.scene.settings;
        let enabled = match kind {
            RayKind::Reflected => settings.reflections,
            _ => settings.transmission,
        };
        let reason = if !enabled {
            StopReason::Disabled
        } else if weight < settings.min_weight {
            StopReason::MinWeight
        } else if counts.reflected + counts.transmitted >= branch.budget_end {
            counts.over_budget += 1;
            StopReason::RayBudget
        } else {
            return true;
        };
        observer.cut(kind, reason, weight);
        false
    }
}

/// Where a ray stands in its eye ray's tree.
#[derive(Clone, Copy, Debug)]
struct Branch {
    /// The eye ray is depth 1.
    depth: u32,
    /// The product of the reflection and transmission weights from the eye.
    weight: f32,
    /// The tree's budget runs out when the counts of reflected plus transmitted rays reach
    /// this ([`RAY_BUDGET`] past their value when the eye ray started).
    budget_end: u64,
    /// The medium the ray runs through: the fog (if the scene has any) between objects, the
    /// object's medium or none inside them.
    within: Within,
}

impl Branch {
    /// A child ray one level deeper, carrying `weight`.
    fn child(self, weight: f32) -> Branch {
        Branch {
            depth: self.depth + 1,
            weight,
            ..self
        }
    }
}
