//! What a glTF material (physically based: base colour, metallic, roughness, transmission,
//! emission) becomes in raylab's Whitted world, by one rule, written down in
//! docs/scene-format.md and here:
//!
//! - the surface colour is the base colour factor;
//! - `alphaMode` MASK cuts the surface away where the base colour's alpha (the factor's times
//!   the texture's) is below `alphaCutoff`: raylab's `alpha_cutoff` is `alphaCutoff` divided by
//!   the factor's alpha (at most [`CUT_ALL`], which cuts it all away), and the texture's alpha is
//!   held to it. BLEND, which needs a renderer that blends, is drawn as MASK at 0.5; OPAQUE
//!   ignores alpha;
//! - reflectivity `kr = F0·(1 − roughness)` with `F0 = 0.04·(1 − metallic) + metallic`: a
//!   smooth metal is a mirror, a smooth dielectric reflects 4 %, a rough surface nothing; the
//!   reflection is white on a dielectric and tinted by the base colour on a metal (gold reflects
//!   gold);
//! - transparency `kt = transmission·(1 − metallic)` with KHR_materials_ior's index (1.5 without
//!   it) and Fresnel;
//! - what is neither reflected nor transmitted is scattered: diffuse `kd = (1 − kr)(1 − kt)`, and
//!   ambient the default's 0.1 times the same share, so a rough surface, metal or not, is
//!   diffuse in its colour;
//! - the Phong highlight `ks = 1 − roughness` with exponent `2/roughness⁴ − 2` (at most
//!   10,000), white on a dielectric and the base colour on a metal;
//! - emission is `emissiveFactor` times KHR_materials_emissive_strength, times the emissive
//!   texture where there is one (`textures`).
//!
//! The rule's result is sorted into mirrors, glass and Phong surfaces for the report a loaded
//! model prints.

use crate::color::Color;
use crate::material::Material;

/// The glTF values the rule reads, with the specification's defaults filled in.
#[derive(Clone, Debug, PartialEq)]
pub struct PbrValues {
    pub base_color: [f32; 4],
    /// `alphaMode`'s cutoff: MASK's `alphaCutoff`, 0.5 for BLEND, none for OPAQUE.
    pub alpha_cutoff: Option<f32>,
    pub metallic: f32,
    pub roughness: f32,
    pub transmission: f32,
    pub ior: f32,
    pub emissive: [f32; 3],
    pub emissive_strength: f32,
}

/// The index of refraction of a glTF material without KHR_materials_ior.
pub const DEFAULT_IOR: f32 = 1.5;
/// The reflectance at normal incidence of a dielectric in glTF's model.
const DIELECTRIC_F0: f32 = 0.04;
/// The `alpha_cutoff` of a masked material whose base colour factor has no alpha: above any
/// texture's alpha.
pub const CUT_ALL: f32 = 2.0;
/// The cutoff BLEND materials are drawn with.
pub const BLEND_CUTOFF: f32 = 0.5;
/// The largest Phong exponent the rule gives (roughness 0).
pub const MAX_SHININESS: f32 = 10_000.0;

impl PbrValues {
    /// The values of one material of a file, clamped to the ranges the specification allows
    /// (a file may still hold others: validation does not check numbers).
    pub fn of(material: &gltf::Material) -> PbrValues {
        let pbr = material.pbr_metallic_roughness();
        let unit = |x: f32| {
            if x.is_finite() {
                x.clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let ior = material.ior().unwrap_or(DEFAULT_IOR);
        let strength = material.emissive_strength().unwrap_or(1.0);
        let alpha_cutoff = match material.alpha_mode() {
            gltf::material::AlphaMode::Opaque => None,
            gltf::material::AlphaMode::Mask => Some(unit(material.alpha_cutoff().unwrap_or(0.5))),
            gltf::material::AlphaMode::Blend => Some(BLEND_CUTOFF),
        };
        PbrValues {
            base_color: pbr.base_color_factor().map(unit),
            alpha_cutoff,
            metallic: unit(pbr.metallic_factor()),
            roughness: unit(pbr.roughness_factor()),
            transmission: material
                .transmission()
                .map_or(0.0, |t| unit(t.transmission_factor())),
            ior: if ior.is_finite() && ior >= 1.0 {
                ior
            } else {
                DEFAULT_IOR
            },
            emissive: material.emissive_factor().map(unit),
            emissive_strength: if strength.is_finite() {
                strength.max(0.0)
            } else {
                1.0
            },
        }
    }
}

/// The raylab material of the glTF values, by the rule in this module's documentation.
pub fn whitted_material(values: &PbrValues) -> Material {
    let [r, g, b, alpha] = values.base_color;
    let base = Color::new(r, g, b);
    let (m, rough) = (values.metallic, values.roughness);
    let f0 = DIELECTRIC_F0 * (1.0 - m) + m;
    let reflectivity = f0 * (1.0 - rough);
    let transparency = values.transmission * (1.0 - m);
    let scattered = (1.0 - reflectivity) * (1.0 - transparency);
    let shininess = if rough > 0.0 {
        (2.0 / rough.powi(4) - 2.0).clamp(1.0, MAX_SHININESS)
    } else {
        MAX_SHININESS
    };
    let [er, eg, eb] = values.emissive;
    Material {
        color: base,
        texture: None,
        alpha_cutoff: values
            .alpha_cutoff
            .filter(|&cutoff| cutoff > 0.0)
            .map(|cutoff| (cutoff / alpha).min(CUT_ALL)),
        emission: Color::new(er, eg, eb) * values.emissive_strength,
        emission_texture: None,
        ambient: Material::default().ambient * scattered,
        diffuse: scattered,
        specular: 1.0 - rough,
        specular_color: Color::ONE * (1.0 - m) + base * m,
        reflection_color: Color::ONE * (1.0 - m) + base * m,
        shininess,
        reflectivity,
        transparency,
        ior: values.ior,
        fresnel: transparency > 0.0,
        medium: None,
    }
}

/// What the rule made of a material, for the report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Reflects at least half the light as a mirror.
    Mirror,
    /// Lets light through.
    Glass,
    /// Everything else: a diffuse surface with a Phong highlight.
    Phong,
}

impl Kind {
    pub fn of(material: &Material) -> Kind {
        if material.transparency > 0.0 {
            Kind::Glass
        } else if material.reflectivity >= 0.5 {
            Kind::Mirror
        } else {
            Kind::Phong
        }
    }
}

/// The report's part about materials: `14 materials → 2 mirrors, 1 glass, 11 Phong`.
pub fn materials_report(materials: &[Material]) -> String {
    let count = |kind| materials.iter().filter(|m| Kind::of(m) == kind).count();
    let plural =
        |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    let mut kinds = Vec::new();
    for (kind, one, many) in [
        (Kind::Mirror, "mirror", "mirrors"),
        (Kind::Glass, "glass", "glass"),
        (Kind::Phong, "Phong", "Phong"),
    ] {
        let n = count(kind);
        if n > 0 {
            kinds.push(plural(n, one, many));
        }
    }
    let head = plural(materials.len(), "material", "materials");
    if kinds.is_empty() {
        head
    } else {
        format!("{head} → {}", kinds.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(metallic: f32, roughness: f32, transmission: f32) -> PbrValues {
        PbrValues {
            base_color: [0.8, 0.2, 0.1, 1.0],
            alpha_cutoff: None,
            metallic,
            roughness,
            transmission,
            ior: DEFAULT_IOR,
            emissive: [0.0; 3],
            emissive_strength: 1.0,
        }
    }

    #[test]
    fn a_smooth_metal_is_a_mirror_and_a_rough_surface_is_diffuse() {
        let mirror = whitted_material(&values(1.0, 0.0, 0.0));
        assert_eq!(mirror.reflectivity, 1.0);
        assert_eq!(mirror.diffuse, 0.0);
        assert_eq!(Kind::of(&mirror), Kind::Mirror);
        assert_eq!(mirror.specular_color, Color::new(0.8, 0.2, 0.1));
        for metallic in [0.0, 1.0] {
            let rough = whitted_material(&values(metallic, 1.0, 0.0));
            assert_eq!(rough.reflectivity, 0.0);
            assert_eq!(rough.specular, 0.0);
            assert_eq!(rough.diffuse, 1.0);
            assert_eq!(Kind::of(&rough), Kind::Phong);
        }
    }

    #[test]
    fn transmission_becomes_transparency_with_fresnel_and_diffuse_takes_only_the_rest() {
        let glass = whitted_material(&values(0.0, 0.0, 1.0));
        assert_eq!(glass.transparency, 1.0);
        assert!(glass.fresnel);
        assert_eq!(glass.ior, DEFAULT_IOR);
        assert_eq!(Kind::of(&glass), Kind::Glass);
        for (m, r, t) in [(0.3, 0.2, 0.5), (0.0, 0.5, 0.0), (1.0, 0.1, 1.0)] {
            let mat = whitted_material(&values(m, r, t));
            assert!(mat.reflectivity + mat.diffuse <= 1.0 + 1e-6);
            assert!(mat.transparency + mat.diffuse <= 1.0 + 1e-6);
        }
    }

    #[test]
    fn the_mask_cutoff_is_held_to_the_textures_alpha_divided_by_the_factors() {
        let masked = |alpha: f32, cutoff: Option<f32>| {
            let mut v = values(0.0, 1.0, 0.0);
            v.base_color[3] = alpha;
            v.alpha_cutoff = cutoff;
            whitted_material(&v).alpha_cutoff
        };
        assert_eq!(masked(1.0, None), None);
        assert_eq!(masked(0.5, None), None);
        assert_eq!(masked(1.0, Some(0.5)), Some(0.5));
        assert_eq!(masked(0.5, Some(0.25)), Some(0.5));
        assert_eq!(masked(0.2, Some(0.5)), Some(CUT_ALL));
        assert_eq!(masked(0.0, Some(0.5)), Some(CUT_ALL));
        assert_eq!(masked(0.0, Some(0.0)), None);
    }

    #[test]
    fn the_report_counts_each_kind() {
        let materials = [
            whitted_material(&values(1.0, 0.0, 0.0)),
            whitted_material(&values(0.0, 0.0, 1.0)),
            whitted_material(&values(0.0, 0.5, 0.0)),
            whitted_material(&values(0.0, 0.9, 0.0)),
        ];
        assert_eq!(
            materials_report(&materials),
            "4 materials → 1 mirror, 1 glass, 2 Phong"
        );
    }
}
