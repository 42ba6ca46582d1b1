//! The one entry point for every scene raylab reads, for the command line and the viewer alike:
//! a built-in SPD scene by name (`spd:balls`, `spd:tree:6`), an NFF file (by its `.nff`
//! extension), an SDL file (`.dat` or `.sdl`), or a TOML scene file.

use std::path::Path;

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
    if name.starts_with(SCENE_PREFIX) {
        return load_spd(name, lighting);
    }
    let path = Path::new(name);
    let extension = path.extension().and_then(|ext| ext.to_str());
    let is = |wanted: &str| extension.is_some_and(|ext| ext.eq_ignore_ascii_case(wanted));
    if is("nff") {
        load_nff(path, lighting)
    } else if is("dat") || is("sdl") {
        load_sdl(path)
    } else {
        load_scene(path)
    }
}
