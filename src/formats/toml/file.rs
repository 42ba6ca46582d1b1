//! The scene file's schema: the tables and keys serde reads from the TOML, before names are
//! resolved and defaults filled in (see [`super::build`]). Every table denies unknown keys, so a
//! misspelt key is an error rather than a silently ignored line.
//!
//! Lights, textures and objects say what kind they are with `type = "…"`. The file writes that
//! tag inside the table; [`super::retag`] moves it outside before serde reads the document, so
//! the kinds here are ordinary (externally tagged) serde enums: adding a kind is adding a
//! variant.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::object_file::ObjectFile;
use super::values::{
    ColorValue, Direction, Exact, Fraction, NonNegative, Positive, PositiveOrInfinite, Vector,
};

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    #[serde(default)]
    pub render: RenderFile,
    pub camera: Option<Spanned<CameraFile>>,
    #[serde(default)]
    pub lights: Vec<LightFile>,
    pub atmosphere: Option<AtmosphereFile>,
    /// By name; the scene's textures are numbered in name order.
    #[serde(default)]
    pub textures: BTreeMap<String, TextureFile>,
    /// By name; the scene's materials are numbered in name order, after the default material.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialFile>,
    #[serde(default)]
    pub objects: Vec<ObjectFile>,
}

/// A `NAME.camera.toml` file beside a scene (what the viewer saves): only a `[camera]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSnippetFile {
    pub camera: Spanned<CameraFile>,
}

/// A `NAME.views.toml` file beside a scene (what the viewer saves): `[view.N]` camera tables,
/// by number (checked when the views are built).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ViewsFile {
    #[serde(default)]
    pub view: BTreeMap<Spanned<String>, Spanned<CameraFile>>,
}

/// `[render]`: the fields of [`crate::settings::RenderSettings`], each optional.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderFile {
    pub width: Option<Spanned<u32>>,
    pub height: Option<Spanned<u32>>,
    pub max_depth: Option<Spanned<u32>>,
    pub min_weight: Option<Spanned<f32>>,
    pub block_size: Option<Spanned<u32>>,
    pub samples: Option<Spanned<u32>>,
    pub aa_threshold: Option<Spanned<f32>>,
    pub background: Option<Spanned<ColorValue>>,
    /// PNG, JPEG or BMP, relative to the scene file's folder: stands on the image plane, as
    /// tall as the view, centred at its own aspect ratio, the background colour around it.
    pub background_image: Option<Spanned<String>>,
    pub ambient: Option<Spanned<ColorValue>>,
    pub shadows: Option<Spanned<bool>>,
    pub reflections: Option<Spanned<bool>>,
    /// Older files call it `refractions` (see [`super::retag`]).
    pub transmission: Option<Spanned<bool>>,
    pub textures: Option<Spanned<bool>>,
    pub fog_steps: Option<Spanned<u32>>,
    pub caustic_photons: Option<Spanned<u32>>,
    pub caustic_gather: Option<Spanned<u32>>,
}

/// `[atmosphere]`: the fields of [`crate::medium::Atmosphere`]; `density` is required.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtmosphereFile {
    pub density: NonNegative,
    pub albedo: Option<Fraction>,
    pub color: Option<ColorValue>,
    /// How far along a ray that meets nothing the background lies; `inf` for nowhere.
    pub background_distance: Option<PositiveOrInfinite>,
}

/// A material's `medium = { … }`: the fields of [`crate::medium::Medium`]; `density` is
/// required.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a medium: a table like { density = 0.5, albedo = 0.8, color = [1, 1, 1] }"
)]
pub struct MediumFile {
    pub density: NonNegative,
    pub albedo: Option<Fraction>,
    pub color: Option<ColorValue>,
}

/// `[camera]`: the fields of [`crate::camera::CameraSpec`], each optional.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraFile {
    pub eye: Option<Spanned<Vector>>,
    pub look_at: Option<Spanned<Vector>>,
    pub up: Option<Spanned<Vector>>,
    /// Vertical, in degrees.
    pub view_angle: Option<Spanned<f32>>,
    pub near: Option<Spanned<f32>>,
}

/// `[[lights]]`: `intensity` multiplies `color`.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum LightFile {
    Point {
        position: Vector,
        color: Option<ColorValue>,
        intensity: Option<NonNegative>,
    },
    Directional {
        /// Towards the light.
        direction: Direction,
        color: Option<ColorValue>,
        intensity: Option<NonNegative>,
    },
    /// A point light shining into a cone; see [`crate::light::Spot`].
    Spot {
        position: Vector,
        /// Along the cone's axis, away from the light.
        direction: Direction,
        /// Half-angle of the cone in degrees, more than 0 and at most 90.
        angle: Spanned<f32>,
        /// Degrees of soft edge inside `angle`, from 0 (a hard edge, the default) to `angle`.
        falloff: Option<Spanned<f32>>,
        color: Option<ColorValue>,
        intensity: Option<NonNegative>,
    },
}

/// `[textures.NAME]`.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TextureFile {
    Checker3d {
        a: Option<ColorValue>,
        b: Option<ColorValue>,
        size: Option<Positive>,
    },
    CheckerUv {
        a: Option<ColorValue>,
        b: Option<ColorValue>,
        u_count: Option<Positive>,
        v_count: Option<Positive>,
    },
    /// Hill & Kelley's wood grain, ringing the object's z axis (turn the object to turn it).
    Wood {
        a: Option<ColorValue>,
        b: Option<ColorValue>,
    },
    /// Hill & Kelley's marble, veined across the object's z axis.
    Marble { color: Option<ColorValue> },
    Image {
        /// PNG, JPEG or BMP, relative to the scene file's folder.
        file: Spanned<String>,
        wrap: Option<WrapFile>,
        /// `[su, sv]`: how many times the image repeats across texture space.
        scale: Option<Exact<Positive, 2>>,
    },
}

/// `wrap = "repeat" | "clamp" | "mirror"`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WrapFile {
    Repeat,
    Clamp,
    Mirror,
}

/// `[materials.NAME]`: the fields of [`crate::material::Material`], each optional.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialFile {
    pub color: Option<ColorValue>,
    /// A name from `[textures]`.
    pub texture: Option<Spanned<String>>,
    /// Where the texture's alpha is below this, the surface is cut away.
    pub alpha_cutoff: Option<NonNegative>,
    /// Light the surface gives off of itself.
    pub emission: Option<ColorValue>,
    /// A name from `[textures]` the emission is multiplied by.
    pub emission_texture: Option<Spanned<String>>,
    pub ambient: Option<NonNegative>,
    pub diffuse: Option<NonNegative>,
    pub specular: Option<NonNegative>,
    pub specular_color: Option<ColorValue>,
    pub shininess: Option<NonNegative>,
    pub reflectivity: Option<Fraction>,
    /// The colour the mirror reflection is tinted by.
    pub reflection_color: Option<ColorValue>,
    pub transparency: Option<Fraction>,
    pub ior: Option<Positive>,
    pub fresnel: Option<bool>,
    /// The medium filling the object inside.
    pub medium: Option<MediumFile>,
}
