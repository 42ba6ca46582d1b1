//! Cut-outs: surfaces whose material has an `alpha_cutoff` are not there where their texture's
//! alpha is below it (a leaf drawn on a square, the gaps of a fence). The BVH knows nothing of
//! textures, so a search that ends on a cut-away point goes on from there, past it, until it
//! meets a surface that is there; shadow rays pass cut-away points as clear air. Scenes without
//! such materials skip all of it.

use crate::bvh::cost::TraversalCost;
use crate::primitive::Hit;
use crate::ray::Ray;

use super::Tracer;

/// Most cut-away points one search passes: the next surface it meets is drawn, whatever its
/// alpha. Bounds the work per ray in a forest of leaves seen edge on.
pub const MAX_CUT_OUTS: u32 = 64;

impl Tracer<'_> {
    /// Whether `hit`, a hit along `ray`, falls where its surface is cut away: its material has
    /// an `alpha_cutoff` above the alpha of its texture there (1 without a texture, or with
    /// textures off).
    pub fn cut_away(&self, ray: &Ray, hit: &Hit) -> bool {
        if !self.cut_outs {
            return false;
        }
        let scene = self.scene;
        let material = &scene.materials[scene.geometry.material(hit) as usize];
        let Some(cutoff) = material.alpha_cutoff else {
            return false;
        };
        let alpha = match material.texture {
            Some(t) if scene.settings.textures => {
                let surface = scene.geometry.surface_with(ray, hit, true);
                scene.textures[t as usize].alpha(surface.uv)
            }
            _ => 1.0,
        };
        alpha < cutoff
    }

    /// The first hit along `ray`, from `hit` (the closest hit beyond some `t_min`) on, up to
    /// `t_max`, that is not cut away ([`Self::cut_away`]): the search goes on past each
    /// cut-away hit, at most [`MAX_CUT_OUTS`] times, counted in `cost`.
    pub fn past_cut_outs(
        &self,
        ray: &Ray,
        hit: Option<Hit>,
        t_max: f32,
        cost: &mut impl TraversalCost,
    ) -> Option<Hit> {
        if !self.cut_outs {
            return hit;
        }
        let mut hit = hit;
        for _ in 0..MAX_CUT_OUTS {
            let at = hit?;
            if !self.cut_away(ray, &at) {
                return Some(at);
            }
            hit = self
                .bvh
                .closest_hit_counted(&self.scene.geometry, ray, at.t, t_max, cost);
        }
        hit
    }
}
