//! The one entry point for every scene raylab reads, for the command line and the viewer alike:
//! a built-in SPD scene by name (`spd:balls`, `spd:tree:6`), an NFF file (by its `.nff`
//! extension), an SDL file (`.dat` or `.sdl`), an OBJ, PLY or glTF model (`.obj`, `.ply`,
//! `.gltf`, `.glb`: framed and lit by a light at the eye where the file has no camera or
//! lights), or a TOML scene file; with the camera of a
//! `NAME.camera.toml` beside the file, and the default framing ([`with_framing_camera`]) for a
//! format that has no camera (SDL).

use std::path::{Path, PathBuf};

use strum::VariantNames;

use super::SceneError;
use super::nff::{NffLighting, load_nff};
use super::sdl::load_sdl;
use super::spd::{SCENE_PREFIX, load_spd};
use super::toml::{ModelFormat, load_camera, load_model_scene, load_scene};
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
/// (TOML scenes say their own). A scene file's camera is replaced by the one of its
/// [`camera_file_beside`], when there is one; a built-in SPD scene (no file) keeps its own.
pub fn load_any_with(name: &str, lighting: NffLighting) -> Result<Scene, SceneError> {
    load_any_as(name, lighting, None)
}

/// A scene file's format, for reading a file whatever its name ends in; named in lower case
/// (`toml`).
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase", parse_err_ty = String, parse_err_fn = unknown_format)]
pub enum SceneFormat {
    Toml,
    Nff,
    /// Hill & Kelley's SDL.
    Sdl,
    /// A Wavefront OBJ model on its own.
    Obj,
    /// A PLY model (the Stanford format) on its own.
    Ply,
    /// A glTF 2.0 model on its own, `.gltf` or `.glb`.
    Gltf,
}

/// The extensions of the scene files raylab reads, in lower case, and their formats.
pub const SCENE_EXTENSIONS: [(&str, SceneFormat); 8] = [
    ("toml", SceneFormat::Toml),
    ("nff", SceneFormat::Nff),
    ("dat", SceneFormat::Sdl),
    ("sdl", SceneFormat::Sdl),
    ("obj", SceneFormat::Obj),
    ("ply", SceneFormat::Ply),
    ("gltf", SceneFormat::Gltf),
    ("glb", SceneFormat::Gltf),
];

impl SceneFormat {
    /// The format a file's extension names ([`SCENE_EXTENSIONS`], in any case); TOML for any
    /// other.
    pub fn of(path: &Path) -> SceneFormat {
        let extension = path.extension().and_then(|ext| ext.to_str());
        SCENE_EXTENSIONS
            .iter()
            .find(|(name, _)| extension.is_some_and(|ext| ext.eq_ignore_ascii_case(name)))
            .map_or(SceneFormat::Toml, |&(_, format)| format)
    }
}

/// Why `text` is no format's name.
fn unknown_format(text: &str) -> String {
    let (last, others) = SceneFormat::VARIANTS
        .split_last()
        .expect("there are formats");
    format!(
        "unknown scene format `{text}` (expected {} or {last})",
        others.join(", ")
    )
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
    let mut scene = match format.unwrap_or_else(|| SceneFormat::of(path)) {
        SceneFormat::Nff => load_nff(path, lighting),
        SceneFormat::Sdl => load_sdl(path).map(with_framing_camera),
        SceneFormat::Toml => load_scene(path),
        SceneFormat::Obj => load_model_scene(path, ModelFormat::Obj),
        SceneFormat::Ply => load_model_scene(path, ModelFormat::Ply),
        SceneFormat::Gltf => load_model_scene(path, ModelFormat::Gltf),
    }?;
    if let Some(camera_file) = camera_file_beside(name) {
        scene.camera = load_camera(&camera_file, scene.camera.spec)?;
    }
    Ok(scene)
}

/// The camera file of the scene file `name`, [`camera_path`] beside it, if there is one; `None`
/// for a built-in SPD scene. Its `[camera]` table takes the place of the scene's camera, key by
/// key.
pub fn camera_file_beside(name: &str) -> Option<PathBuf> {
    if name.starts_with(SCENE_PREFIX) {
        return None;
    }
    let path = camera_path(Path::new(name));
    path.is_file().then_some(path)
}

/// Where the camera of `file` (a scene file, or an image the viewer saves) goes: beside it,
/// `NAME.camera.toml` (`room.camera.toml` for `room.toml`, `room.dat` or `room.png`).
pub fn camera_path(file: &Path) -> PathBuf {
    file.with_extension("camera.toml")
}

/// Where the views of the scene file `file` go (the viewer's bookmarked cameras): beside it,
/// `NAME.views.toml` (`room.views.toml` for `room.toml`, `room.nff` or `room.dat`).
pub fn views_path(file: &Path) -> PathBuf {
    file.with_extension("views.toml")
}

/// The scene with the default framing camera ([`crate::camera::frame`]): a three-quarter view of its
/// finite objects at its image's aspect. The reader of a format without a camera ends with it:
/// `load_sdl(path).map(with_framing_camera)`.
pub fn with_framing_camera(mut scene: Scene) -> Scene {
    scene.camera = scene.framing_camera();
    scene
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::IntoEnumIterator;

    #[test]
    fn formats_read_and_print_their_names() {
        for format in SceneFormat::iter() {
            assert_eq!(format.to_string().parse::<SceneFormat>(), Ok(format));
        }
        assert_eq!(
            SceneFormat::VARIANTS,
            ["toml", "nff", "sdl", "obj", "ply", "gltf"]
        );
        assert_eq!(
            "stl".parse::<SceneFormat>(),
            Err(
                "unknown scene format `stl` (expected toml, nff, sdl, obj, ply or gltf)"
                    .to_string()
            )
        );
        assert_eq!(SceneFormat::of(Path::new("Bunny.PLY")), SceneFormat::Ply);
        assert_eq!(SceneFormat::of(Path::new("room.dat")), SceneFormat::Sdl);
        assert_eq!(SceneFormat::of(Path::new("duck.GLB")), SceneFormat::Gltf);
        assert_eq!(SceneFormat::of(Path::new("room")), SceneFormat::Toml);
    }
}
