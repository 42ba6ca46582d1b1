//! Hill & Kelley's SDL, the scene language of *Computer Graphics using OpenGL* (`.dat` and
//! `.sdl` files): read as the book's `SDL.cpp` reads it (`lexer` splits the text, `expand`
//! runs `def`/`use`, `parse` reads the statements, `build` keeps the reader's state and makes
//! the scene, `solids` has the shapes in object space, `mesh_3vn` reads `.3vn` meshes).
//! SDL has no camera: [`parse_sdl`] gives the scene a placeholder, and
//! [`load_any`](crate::formats::load_any) the default framing camera, or the one of a
//! `NAME.camera.toml` beside the file, or the command line's.
//!
//! Where raylab differs from the book's reader:
//! - Where the book stops reading without a word (an unknown keyword, a missing `{`, an
//!   undefined `use`) or ends the program (a bad number), raylab reports `file:line:column`,
//!   what it expected, a near-miss keyword or name, and the `def`s an expanded word came from.
//! - A `def` that uses itself is an error, and expansion is bounded ([`MAX_USE_DEPTH`],
//!   [`MAX_EXPANDED_TOKENS`]), as are the meshes' triangles ([`MAX_TRIANGLES`]).
//! - A last word with no whitespace after it is read (the book drops it).
//! - `pop` with nothing pushed resets the transform and warns (the book crashes later); a
//!   `push` never popped is a warning; a missing mesh file is a warning, once per file.
//! - A zero scale is an error (the book divides by it and carries on).
//! - raylab's materials have one colour: the diffuse colour, the ambient colour becoming the
//!   ambient coefficient (its mean over the diffuse colour's mean), the specular colour the
//!   highlight's colour, `emissive` the material's emission, added at every hit as the book's
//!   shading adds it. `exponent` (the book's own `bookScene.dat` writes it) is read as
//!   `specularExponent`, with a warning. `minReflectivity` and `minTransparency` become
//!   raylab's one adaptive cut-off, the smaller of the two.
//! - Textures mean what they mean in the book's ray tracer (`Scene::texture`, `Scene::shade`):
//!   −1 the checkerboard (its cells counted with `floor`, where the book truncates towards
//!   zero and doubles the cells through the origin), −2 wood, −3 marble (the book's ring and
//!   vein recipes with raylab's noise, wood's rings alternating in two colours), N > 0 pixmap N,
//!   mapped by `parameters` on squares and (tapered) cylinders and by the shape's own texture
//!   coordinates elsewhere, repeated and filtered rather than read off by the nearest pixel.
//!   Solid textures see a mesh (the polyhedra, the teapot, `.3vn` files) in world space.
//!   `makePixmap` also takes the third number of the other version of the book's code. A pixmap
//!   or background image that cannot be read, a pixmap number no `makePixmap` filled, and an
//!   unknown texture number are warnings (the book stops reading, or reads past its array).
//! - `backgroundImage` stands on the image plane, as tall as the view and centred at its own
//!   aspect ratio (the book copies it pixel for pixel from the image's corner), so it follows
//!   any image size; the background colour shows around it.
//! - The polyhedra are generated (the convex hulls of their corners), not read from files.
//! - `torus` is raylab's exact torus, turned to ring the z axis as GLUT's does (ring radius 1,
//!   tube 0.2); the book's own `Torus::hit` was a stub.
//! - `union`, `intersection` and `difference` are exact boolean objects (the book's copies
//!   only drew both operands, or stubbed them out); an operand that is a mesh is an error.
//! - `taperedTube s t` is the tapered cylinder with its wall `t` thick everywhere (the book's
//!   inner wall starts at the outer one's radius); a wall of 1 or more is an error.
//! - The other versions' extensions (`extrude`, `texturedCube`, `wineglass`, …) are unknown
//!   words.

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
    let bytes = crate::memory::read_file(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read the scene file: {e}")))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    parse_sdl(&ascii_text(&bytes), path, SceneFiles::Folder(folder))
}

/// Reads a scene from SDL text; `origin` names it in messages, `files` gives its mesh files.
pub fn parse_sdl(text: &str, origin: &Path, files: SceneFiles) -> Result<Scene, SceneError> {
    parse::parse(Source { origin, text }, files)
}
