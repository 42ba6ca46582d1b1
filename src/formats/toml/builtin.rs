//! The built-in default scene, compiled into the binary with the texture and model it uses, so
//! `raylab` shows it from any directory.

use std::path::Path;

use super::load::parse_scene_with;
use crate::formats::SceneError;
use crate::formats::SceneFiles;
use crate::scene::Scene;

/// The default scene's text, as in `assets/scenes/default.toml`.
pub const DEFAULT_SCENE_TEXT: &str = include_str!("../../../assets/scenes/default.toml");

/// The files the default scene names, by the names it uses for them.
const DEFAULT_SCENE_FILES: &[(&str, &[u8])] = &[
    (
        "../textures/bricks.png",
        include_bytes!("../../../assets/textures/bricks.png"),
    ),
    (
        "../models/torus.obj",
        include_bytes!("../../../assets/models/torus.obj"),
    ),
];

/// The default scene: every idea of the lecture in one picture.
pub fn default_scene() -> Result<Scene, SceneError> {
    parse_scene_with(
        DEFAULT_SCENE_TEXT,
        Path::new("builtin:default.toml"),
        SceneFiles::Builtin(DEFAULT_SCENE_FILES),
    )
}
