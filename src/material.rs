//! Materials: how a surface answers light, in the terms of the lecture's shading model
//! (emission, ambient, Lambert diffuse, Phong specular) plus mirror reflection and
//! transparency, and the medium that may fill the object inside.

use crate::color::Color;
use crate::medium::Medium;

#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// The surface's colour; a texture, if given, replaces it.
    pub color: Color,
    /// Index into the scene's textures that drives `color`.
    pub texture: Option<u32>,
    /// Cut-outs (a leaf on a square, a fence's gaps; glTF's `alphaMode` MASK): where the alpha
    /// of `texture` ([`crate::texture::Texture::alpha`], 1 without one) is below this, the
    /// surface is not there, for every ray and every shadow ray. `None`: it is there everywhere.
    pub alpha_cutoff: Option<f32>,
    /// Light the surface gives off of itself (the book's `emissive`), seen at every hit
    /// whatever lights it; it lights nothing else (a Whitted tracer has no area lights).
    pub emission: Color,
    /// Index into the scene's textures that the emission is multiplied by (a glTF model's
    /// emissive texture: lit windows, a screen).
    pub emission_texture: Option<u32>,
    /// Ambient coefficient `ka`: the share of the global ambient light reflected.
    pub ambient: f32,
    /// Diffuse (Lambert) coefficient `kd`.
    pub diffuse: f32,
    /// Specular (Phong) coefficient `ks` and the colour of the highlight.
    pub specular: f32,
    pub specular_color: Color,
    /// Phong exponent `f` of `(r·v)^f`.
    pub shininess: f32,
    /// Weight `kr` of the mirror-reflected ray.
    pub reflectivity: f32,
    /// The colour `kr`'s reflection is tinted by: white for most surfaces, a metal's own colour
    /// (gold reflects gold). The light Fresnel's rule or total internal reflection takes from
    /// transmission is reflected untinted.
    pub reflection_color: Color,
    /// Weight `kt` of the transmitted ray; transmitted light is tinted by the surface colour.
    pub transparency: f32,
    /// Index of refraction of the material inside the surface (outside is 1, vacuum).
    pub ior: f32,
    /// Use Schlick's approximation of the Fresnel equations to trade reflection for
    /// transmission with the angle of incidence.
    pub fresnel: bool,
    /// The medium filling the object inside the surface (smoky glass, coloured liquid); `None`
    /// for clear material. See [`crate::medium`] for when a ray is inside it.
    pub medium: Option<Medium>,
}

impl Default for Material {
    fn default() -> Self {
        Material {
            color: Color::splat(0.8),
            texture: None,
            alpha_cutoff: None,
            emission: Color::ZERO,
            emission_texture: None,
            ambient: 0.1,
            diffuse: 0.8,
            specular: 0.0,
            specular_color: Color::ONE,
            shininess: 32.0,
            reflectivity: 0.0,
            reflection_color: Color::ONE,
            transparency: 0.0,
            ior: 1.0,
            fresnel: false,
            medium: None,
        }
    }
}

impl Material {
    /// What the material lets through of the light behind it: `transparency × colour` (zero
    /// for an opaque material).
    pub fn filter(&self) -> Color {
        self.transparency * self.color
    }

    /// Whether the material is transparent and bends the light that passes it (index not 1):
    /// a shadow ray cannot follow that light; caustic photons do.
    pub fn bends_light(&self) -> bool {
        self.transparency > 0.0 && self.ior != 1.0
    }

    /// Schlick's reflectance for a ray meeting the surface with `cos_i = |d·n|`, going from index
    /// `n1` into `n2`.
    pub fn schlick(cos_i: f32, n1: f32, n2: f32) -> f32 {
        let r0 = ((n1 - n2) / (n1 + n2)).powi(2);
        r0 + (1.0 - r0) * (1.0 - cos_i).clamp(0.0, 1.0).powi(5)
    }
}

/// Whether any of `materials` cuts its surface away by its texture's alpha
/// ([`Material::alpha_cutoff`]).
pub fn any_cut_outs(materials: &[Material]) -> bool {
    materials.iter().any(|m| m.alpha_cutoff.is_some())
}

/// Whether every one of `materials` stops all light: lets none through and has no cut-outs. A
/// shadow ray then stops at its first hit.
pub fn all_opaque(materials: &[Material]) -> bool {
    !any_cut_outs(materials) && materials.iter().all(|m| m.filter() == Color::ZERO)
}
