//! The materials, the lights and the triangles' shading on the GPU: records of the WGSL's
//! `Material`, `Light`, `TriangleShading` and `VertexAttributes`, made from the scene's.

use super::record::gpu_record;
use super::texture::NO_TEXTURE;
use crate::light::{Light, LightKind};
use crate::material::Material;

gpu_record! {
    /// WGSL's `Material`.
    pub struct GpuMaterial {
        pub color: [f32; 3],
        pub ambient: f32,
        pub emission: [f32; 3],
        pub diffuse: f32,
        pub specular_color: [f32; 3],
        pub specular: f32,
        pub shininess: f32,
        pub reflectivity: f32,
        pub transparency: f32,
        pub ior: f32,
        pub fresnel: u32,
        /// Its texture record ([`NO_TEXTURE`]: none).
        pub texture: u32,
        /// The medium inside it (a density of zero: none).
        pub medium_density: f32,
        pub medium_albedo: f32,
        pub medium_color: [f32; 3],
        /// `Material::alpha_cutoff` (0: none, as no alpha is below it).
        pub alpha_cutoff: f32,
        pub reflection_color: [f32; 3],
        /// Its emission texture's record ([`NO_TEXTURE`]: none).
        pub emission_texture: u32,
    }
}

impl From<&Material> for GpuMaterial {
    fn from(m: &Material) -> GpuMaterial {
        let medium = m.medium.unwrap_or_default();
        GpuMaterial {
            color: m.color.to_array(),
            ambient: m.ambient,
            emission: m.emission.to_array(),
            diffuse: m.diffuse,
            specular_color: m.specular_color.to_array(),
            specular: m.specular,
            shininess: m.shininess,
            reflectivity: m.reflectivity,
            transparency: m.transparency,
            ior: m.ior,
            fresnel: u32::from(m.fresnel),
            texture: m.texture.unwrap_or(NO_TEXTURE),
            medium_density: medium.density,
            medium_albedo: medium.albedo,
            medium_color: medium.color.to_array(),
            alpha_cutoff: m.alpha_cutoff.unwrap_or(0.0),
            reflection_color: m.reflection_color.to_array(),
            emission_texture: m.emission_texture.unwrap_or(NO_TEXTURE),
        }
    }
}

gpu_record! {
    /// WGSL's `Light`; `kind` is a [`LightKind`] (`LIGHT_*` in the WGSL).
    pub struct GpuLight {
        pub position: [f32; 3],
        pub kind: u32,
        pub direction: [f32; 3],
        pub cos_angle: f32,
        pub color: [f32; 3],
        pub cos_full: f32,
    }
}

impl From<&Light> for GpuLight {
    fn from(light: &Light) -> GpuLight {
        let zero = [0.0; 3];
        match *light {
            Light::Point { position, color } => GpuLight {
                position: position.to_array(),
                kind: LightKind::Point as u32,
                direction: zero,
                cos_angle: 0.0,
                color: color.to_array(),
                cos_full: 0.0,
            },
            Light::Directional { direction, color } => GpuLight {
                position: zero,
                kind: LightKind::Directional as u32,
                direction: direction.to_array(),
                cos_angle: 0.0,
                color: color.to_array(),
                cos_full: 0.0,
            },
            Light::Spot(spot) => GpuLight {
                position: spot.position.to_array(),
                kind: LightKind::Spot as u32,
                direction: spot.direction.to_array(),
                cos_angle: spot.cos_angle,
                color: spot.color.to_array(),
                cos_full: spot.cos_full,
            },
        }
    }
}

gpu_record! {
    /// WGSL's `TriangleShading`: which vertices of [`super::scene::GpuScene`]'s vertex attributes a triangle's
    /// corners are, and its material with [`HAS_NORMALS`], [`HAS_UVS`] and [`HAS_COLORS`].
    pub struct GpuTriangleShading {
        pub corners: [u32; 3],
        pub material: u32,
    }
}

pub const HAS_COLORS: u32 = 1 << 29;
pub const HAS_NORMALS: u32 = 1 << 30;
pub const HAS_UVS: u32 = 1 << 31;

/// The low bits of a triangle's material word that hold the material (the top three are
/// [`HAS_COLORS`], [`HAS_NORMALS`] and [`HAS_UVS`]).
pub const MATERIAL_BITS: u32 = HAS_COLORS - 1;

gpu_record! {
    /// WGSL's `VertexAttributes`: a mesh vertex's normal, texture coordinates and colour.
    pub struct GpuVertexAttributes {
        pub normal: [f32; 3],
        pub u: f32,
        pub v: f32,
        pub red: f32,
        pub green: f32,
        pub blue: f32,
    }
}
