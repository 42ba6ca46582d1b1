//! Reading a scene: the file's text is parsed as TOML, its type tags are moved where serde
//! wants them ([`super::retag`]), serde reads the schema ([`super::file`]) and the schema is
//! built into a [`Scene`] ([`super::build`]).

use std::path::Path;

use serde::Deserialize;
use toml::Spanned;
use toml::de::DeTable;

use super::build::{build_camera, build_scene};
use super::file::{CameraSnippetFile, SceneFile};
use super::models::build_model_scene;
use super::object_file::OBJECT_KEYS;
use super::placing::ModelFormat;
use super::retag::retag_document;
use crate::camera::{Camera, CameraSpec};
use crate::formats::{SceneError, Source};
use crate::formats::{SceneFiles, known_format, not_the_format, utf8_text};
use crate::memory::{self, Bytes};
use crate::scene::Scene;

/// Reads the scene file at `path`, UTF-8 text (a byte-order mark or a DOS end-of-file mark is
/// skipped). Texture and OBJ file names are relative to its folder.
pub fn load_scene(path: &Path) -> Result<Scene, SceneError> {
    let bytes = memory::read_file(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read the scene file: {e}")))?;
    if let Some(what) = known_format(&bytes) {
        let message = not_the_format(path, what, "a scene file");
        let hint = if what.contains("PLY") {
            "raylab reads it when its name ends in .ply"
        } else if what.contains("glTF") {
            "raylab reads it when its name ends in .gltf or .glb"
        } else {
            "raylab reads TOML, NFF, SDL, OBJ, PLY and glTF"
        };
        return Err(SceneError::whole_file(path, format!("{message}: {hint}")));
    }
    let text = utf8_text(&bytes, path)?;
    parse_scene(text, path, path.parent().unwrap_or(Path::new("")))
}

/// Reads the model file at `path` (OBJ, PLY or glTF) as a scene of its own, see
/// [`build_model_scene`].
pub fn load_model_scene(path: &Path, format: ModelFormat) -> Result<Scene, SceneError> {
    let files = SceneFiles::Folder(path.parent().unwrap_or(Path::new("")));
    build_model_scene(path, files, format)
}

/// Reads the `[camera]` table of the file at `path` (a `NAME.camera.toml`, as the viewer saves
/// it); the keys it leaves out are `base`'s. Errors are at the file's line and column.
pub fn load_camera(path: &Path, base: CameraSpec) -> Result<Camera, SceneError> {
    let bytes = memory::read_file(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read the camera file: {e}")))?;
    let text = utf8_text(&bytes, path)?;
    let source = Source { origin: path, text };
    let document = parse_toml(source)?;
    let file = CameraSnippetFile::deserialize(toml::de::Deserializer::from(document))
        .map_err(|e| source.toml_error(&e))?;
    build_camera(Some(file.camera), base, source)
}

/// Reads a scene from `text`. `origin` names it in error messages; texture and OBJ file names
/// are relative to `base_dir`.
pub fn parse_scene(text: &str, origin: &Path, base_dir: &Path) -> Result<Scene, SceneError> {
    parse_scene_with(text, origin, SceneFiles::Folder(base_dir))
}

/// Memory the TOML reader takes per byte of the file, at most (measured: about 40, for files
/// of many small tables, such as a million lights).
const PARSE_BYTES_PER_BYTE: u64 = 48;

/// Parses the TOML of `source`, if there is memory for it.
pub(super) fn parse_toml<'a>(source: Source<'a>) -> Result<Spanned<DeTable<'a>>, SceneError> {
    let size = source.text.len() as u64;
    memory::check(
        &format!("reading this {} file", Bytes(size)),
        size * PARSE_BYTES_PER_BYTE,
    )
    .map_err(|message| SceneError::whole_file(source.origin, message))?;
    DeTable::parse(source.text).map_err(|e| source.toml_error(&e))
}

/// Reads a scene from `text`, taking the files it names from `files`.
pub fn parse_scene_with(text: &str, origin: &Path, files: SceneFiles) -> Result<Scene, SceneError> {
    let source = Source { origin, text };
    let mut document = parse_toml(source)?;
    let shape_keys = retag_document(document.get_mut(), source)?;
    let file = SceneFile::deserialize(toml::de::Deserializer::from(document)).map_err(|e| {
        let mut error = source.toml_error(&e);
        // An error placed on a shape's key is about an unknown key, and serde listed only the
        // shape's own keys as known.
        if e.span().is_some_and(|span| shape_keys.contains(&span)) {
            let common: Vec<String> = OBJECT_KEYS.iter().map(|k| format!("`{k}`")).collect();
            let (last, rest) = common.split_last().expect("objects have common keys");
            error.message += &format!("; every object also takes {} and {last}", rest.join(", "));
        }
        error
    })?;
    build_scene(file, source, files)
}
