//! Following photons from the lights through mirrors and glass: at each surface a photon is
//! stored if it has been turned by a specular surface before and the surface has a diffuse
//! part, then carries on by the surface's reflection or transmission, picked by Russian
//! roulette with the same weights the Whitted tracer gives its reflected and transmitted rays,
//! so that the power the photons carry on average is the power the light keeps. Between
//! surfaces a photon loses power to the medium it runs through, the fog or the medium inside
//! an object, by Beer–Lambert (the same rule as the Whitted tracer's, see [`crate::medium`]);
//! a directional light's photon, on its way to its first surface, to the fog its light
//! crosses from the backdrop.

use rayon::prelude::*;

use super::emit::{Emitter, Sphere};
use crate::aabb::Aabb;
use crate::color::Color;
use crate::material::Material;
use crate::photon_map::Photon;
use crate::primitive::PrimId;
use crate::ray::{Ray, offset_origin};
use crate::sampling::random;
use crate::scene::Scene;
use crate::shapes::Shape;
use crate::whitted::{Tracer, Within, reflect, scattering};

/// The most surfaces a photon visits.
const MAX_BOUNCES: u32 = 16;

/// With more specular objects than this, photons aim at the sphere around them all.
const MAX_TARGETS: usize = 64;

/// How many photons are traced together on one thread.
const CHUNK: u32 = 4096;

/// The lights that can send photons to something specular, and how often each is picked.
#[derive(Clone, Debug, PartialEq)]
pub struct PhotonSource {
    emitters: Vec<Emitter>,
    /// Each emitter's chance of being picked, in proportion to the power it aims.
    chances: Vec<f32>,
}

impl PhotonSource {
    /// The photon source of `scene`; `None` when no light can send a photon to anything
    /// specular (reflective or transparent).
    pub fn new(scene: &Scene) -> Option<PhotonSource> {
        let specular = specular_spheres(scene);
        if specular.is_empty() {
            return None;
        }
        let bounds = scene.geometry.finite_bounds();
        let emitters: Vec<Emitter> = scene
            .lights
            .iter()
            .filter_map(|light| Emitter::new(light, &specular, &bounds))
            .filter(|e| e.power() > 0.0)
            .collect();
        let total: f32 = emitters.iter().map(Emitter::power).sum();
        if emitters.is_empty() || !total.is_finite() {
            return None;
        }
        let chances = emitters.iter().map(|e| e.power() / total).collect();
        Some(PhotonSource { emitters, chances })
    }

    /// Shoots the photons numbered `first..first + count` through the scene (on all cores,
    /// the same photons whatever the thread count) and adds those stored to `stored`, in order.
    pub fn shoot(&self, tracer: &Tracer, first: u32, count: u32, stored: &mut Vec<Photon>) {
        let end = first.saturating_add(count);
        let chunks: Vec<u32> = (first..end).step_by(CHUNK as usize).collect();
        let each: Vec<Vec<Photon>> = chunks
            .into_par_iter()
            .map(|start| {
                let mut stored = Vec::new();
                for index in start..end.min(start.saturating_add(CHUNK)) {
                    self.trace(tracer, index, &mut stored);
                }
                stored
            })
            .collect();
        for chunk in each {
            stored.extend(chunk);
        }
    }

    /// Traces photon `index`, adding where it is stored to `stored`.
    fn trace(&self, tracer: &Tracer, index: u32, stored: &mut Vec<Photon>) {
        let u = |dim: u32| random(index, dim);
        // Pick a light, then let it emit; the power is the light's over the chance of picking it.
        let mut pick = u(0);
        let mut light = self.emitters.len() - 1;
        for (i, chance) in self.chances.iter().enumerate() {
            if pick < *chance {
                light = i;
                break;
            }
            pick -= chance;
        }
        let emitter = &self.emitters[light];
        let (mut ray, power) = emitter.emit([u(1), u(2), u(3)]);
        let mut power = power / self.chances[light];
        let mut turned = false;
        let mut within = Within::Fog;
        let scene = tracer.scene;
        let settings = &scene.settings;
        for bounce in 0..MAX_BOUNCES {
            if power == Color::ZERO {
                return;
            }
            let Some(hit) = tracer.closest_hit(&ray, 0.0) else {
                return;
            };
            let dir = ray.dir.normalize();
            let fog = tracer.fog.as_ref();
            let end = hit.t * ray.dir.length();
            let materials = &scene.materials;
            let surface = scene.geometry.surface(&ray, &hit);
            if bounce == 0 && emitter.is_afar() {
                // It starts at no particular distance: it crosses the fog that the light's own
                // light crosses to reach the hit, from the backdrop.
                if let Some(fog) = fog {
                    power *= fog.transmittance(surface.point, -dir, 0.0, f32::INFINITY);
                }
            } else if let Some((medium, segment)) =
                within.segment(fog, materials, ray.origin, dir, end)
            {
                power *= medium.transmittance(segment.length());
            }
            let material = &scene.materials[surface.material as usize];
            if turned && material.diffuse > 0.0 {
                stored.push(Photon {
                    position: surface.point,
                    power,
                    dir,
                });
            }
            let entering = dir.dot(surface.geometric_normal) < 0.0;
            let side = if entering { 1.0 } else { -1.0 };
            let (normal, geometric_normal) =
                (surface.normal * side, surface.geometric_normal * side);
            let split = scattering(material, dir, normal, entering);
            let reflected = if settings.reflections {
                split.reflect
            } else {
                0.0
            };
            let refracted = split.refracted.filter(|_| settings.transmission);
            let transmitted = refracted.map_or(0.0, |_| split.transmit);
            // Russian roulette: carry on with the chance `survive`, the power divided by it.
            let kept = reflected + transmitted;
            let survive = kept.min(1.0);
            let roll = u(4 + 2 * bounce) * kept;
            if kept <= 0.0 || u(5 + 2 * bounce) >= survive {
                return;
            }
            if roll < reflected {
                power *= split.reflect_color / split.reflect * (kept / survive);
                ray = Ray::new(
                    offset_origin(surface.point, geometric_normal),
                    reflect(dir, normal),
                );
                turned = true;
            } else if let Some(refracted) = refracted {
                power *= tracer.base_color(material, &surface) * (kept / survive);
                ray = Ray::new(offset_origin(surface.point, -geometric_normal), refracted);
                within = Within::after_crossing(&scene.materials, surface.material, entering);
                // Glass that does not bend light (index 1) lets shadow rays through instead.
                turned |= material.bends_light();
            }
        }
    }
}

/// Whether a material turns light specularly: a mirror or glass.
fn is_specular(material: &Material) -> bool {
    material.reflectivity > 0.0 || material.transparency > 0.0
}

/// The spheres around the specular objects, meshes and instances (`None` for one without bounds): a
/// sphere itself, the sphere around the box of anything else; one sphere around them all when
/// there are too many to aim at one by one.
fn specular_spheres(scene: &Scene) -> Vec<Option<Sphere>> {
    let geometry = &scene.geometry;
    let specular = |index: u32| is_specular(&scene.materials[index as usize]);
    let mut spheres: Vec<Option<Sphere>> = Vec::new();
    for (i, object) in geometry.objects.iter().enumerate() {
        let materials = match &object.shape {
            Shape::Csg(csg) => csg.leaves().iter().map(|l| l.material).collect(),
            _ => vec![object.material],
        };
        if !materials.into_iter().any(specular) {
            continue;
        }
        spheres.push(match (&object.shape, &object.transform) {
            (Shape::Sphere(s), None) => Some(Sphere {
                center: s.center,
                radius: s.radius,
            }),
            _ => geometry
                .bounds(PrimId::object(i))
                .filter(Aabb::is_finite)
                .map(|b| Sphere::around(&b)),
        });
    }
    for (m, mesh) in geometry.meshes.iter().enumerate() {
        if specular(mesh.material) {
            let start = geometry.mesh_starts[m] as usize;
            let end = geometry
                .mesh_starts
                .get(m + 1)
                .map_or(geometry.triangle_count(), |&e| e as usize);
            let around = (start..end)
                .filter_map(|t| geometry.bounds(PrimId::triangle(t)))
                .fold(Aabb::EMPTY, Aabb::union);
            spheres.push((!around.is_empty()).then(|| Sphere::around(&around)));
        }
    }
    for (i, instance) in geometry.instances().iter().enumerate() {
        let meshes = &geometry.models()[instance.model as usize].meshes;
        let is_specular = match instance.material {
            Some(material) => specular(material),
            None => meshes.iter().any(|mesh| specular(mesh.material)),
        };
        if is_specular {
            spheres.push(Some(Sphere::around(&geometry.instance_bounds(i))));
        }
    }
    if spheres.len() > MAX_TARGETS {
        let all = spheres.iter().try_fold(Aabb::EMPTY, |all, s| {
            s.map(|s| all.union(Aabb::new(s.center - s.radius, s.center + s.radius)))
        });
        spheres = vec![all.map(|b| Sphere::around(&b))];
    }
    spheres
}
