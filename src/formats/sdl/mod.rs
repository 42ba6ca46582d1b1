//! Hill & Kelley's SDL, the scene language of *Computer Graphics using OpenGL* (`.dat` and
//! `.sdl` files): read as the book's `SDL.cpp` reads it ([`lexer`] splits the text, [`expand`]
//! runs `def`/`use`, [`parse`] reads the statements, [`build`] keeps the reader's state and makes
//! the scene, [`solids`] has the shapes in object space, [`mesh_3vn`] reads `.3vn` meshes).
//! SDL has no camera: the scene gets a placeholder, to be set from outside.

mod build;
mod expand;
mod lexer;
mod mesh_3vn;
mod parse;
mod solids;
mod suggest;

use std::path::Path;

pub use build::MAX_TRIANGLES;
pub use expand::{MAX_EXPANDED_TOKENS, MAX_USE_DEPTH};

use crate::formats::{SceneError, SceneFiles, Source, ascii_text};
use crate::scene::Scene;

/// Reads the SDL file at `path`; its meshes are read from beside it.
pub fn load_sdl(path: &Path) -> Result<Scene, SceneError> {
    let bytes = std::fs::read(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read the scene file: {e}")))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    parse_sdl(&ascii_text(&bytes), path, SceneFiles::Folder(folder))
}

/// Reads a scene from SDL text; `origin` names it in messages, `files` gives its mesh files.
pub fn parse_sdl(text: &str, origin: &Path, files: SceneFiles) -> Result<Scene, SceneError> {
    parse::parse(Source { origin, text }, files)
}
