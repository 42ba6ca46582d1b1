//! The one entry point for every scene raylab reads, for the command line and the viewer alike:
//! a built-in SPD scene by name (`spd:balls`, `spd:tree:6`), an NFF file (by its `.nff`
//! extension), an SDL file (`.dat` or `.sdl`), or a TOML scene file.

use std::path::Path;
use std::str::FromStr;

use super::SceneError;
use super::nff::{NffLighting, load_nff};
use super::sdl::load_sdl;
use super::spd::{SCENE_PREFIX, load_spd};
use super::toml::load_scene;
use crate::scene::Scene;

/// Reads the scene `name` names, NFF lights as bright as the SPD readme suggests.
///
/// ```
/// use raylab::formats::load_any;
///
/// let balls = load_any("spd:balls:1")?; // a built-in SPD scene: 10 balls and a floor
/// assert_eq!(balls.geometry.objects.len(), 11);
///
/// let default = load_any("assets/scenes/default.toml")?; // a TOML scene file
/// assert!(!default.lights.is_empty());
///
/// let error = load_any("no/such/scene.toml").unwrap_err();
/// assert!(error.to_string().contains("no/such/scene.toml"));
/// # Ok::<(), raylab::formats::SceneError>(())
/// ```
pub fn load_any(name: &str) -> Result<Scene, SceneError> {
    load_any_with(name, NffLighting::default())
}

/// Reads the scene `name` names; `lighting` sets the brightness of NFF and SPD scenes' lights
/// (TOML scenes say their own).
pub fn load_any_with(name: &str, lighting: NffLighting) -> Result<Scene, SceneError> {
    load_any_as(name, lighting, None)
}

/// A scene file's format, for reading a file whatever its name ends in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneFormat {
    Toml,
    Nff,
    /// Hill & Kelley's SDL.
    Sdl,
}

impl SceneFormat {
    /// The format a file's extension names: `.nff`, `.dat` and `.sdl`; TOML for any other.
    pub fn of(path: &Path) -> SceneFormat {
        let extension = path.extension().and_then(|ext| ext.to_str());
        let is = |wanted: &str| extension.is_some_and(|ext| ext.eq_ignore_ascii_case(wanted));
        if is("nff") {
            SceneFormat::Nff
        } else if is("dat") || is("sdl") {
            SceneFormat::Sdl
        } else {
            SceneFormat::Toml
        }
    }
}

impl FromStr for SceneFormat {
    type Err = String;

    fn from_str(text: &str) -> Result<SceneFormat, String> {
        match text {
            "toml" => Ok(SceneFormat::Toml),
            "nff" => Ok(SceneFormat::Nff),
            "sdl" => Ok(SceneFormat::Sdl),
            _ => Err(format!(
                "unknown scene format `{text}` (expected toml, nff or sdl)"
            )),
        }
    }
}

/// [`load_any_with`], reading a file in `format` when given, else in the format its
/// extension names.
pub fn load_any_as(
    name: &str,
    lighting: NffLighting,
    format: Option<SceneFormat>,
) -> Result<Scene, SceneError> {
    if format.is_none() && name.starts_with(SCENE_PREFIX) {
        return load_spd(name, lighting);
    }
    let path = Path::new(name);
    match format.unwrap_or_else(|| SceneFormat::of(path)) {
        SceneFormat::Nff => load_nff(path, lighting),
        SceneFormat::Sdl => load_sdl(path),
        SceneFormat::Toml => load_scene(path),
    }
}
