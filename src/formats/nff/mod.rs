//! NFF, the Neutral File Format of Eric Haines' Standard Procedural Databases (SPD): reading it
//! ([`load_nff`], [`parse_nff`]), its contents as data ([`NffDocument`]), writing it back
//! ([`NffDocument::write_nff`]), and building a [`Scene`] from it
//! ([`NffDocument::to_scene`]) with lights as bright as [`NffLighting`] says.

mod build;
mod document;
mod format_g;
mod lighting;
mod parse;
mod povray;
mod tokens;
mod write;

use std::path::Path;

pub use build::{BuildError, Part, SPD_MAX_DEPTH};
pub use document::{Fill, Item, NffDocument, NffLight, PatchVertex, PrimitiveCounts, View};
pub use lighting::NffLighting;

use crate::formats::{SceneError, Source, ascii_text};
use crate::scene::Scene;
use parse::Locations;

/// Reads the NFF file at `path`. NFF is ASCII: a comment may hold any byte, and a byte-order
/// mark at the start or a DOS end-of-file mark (^Z) at the end is skipped.
pub fn load_nff(path: &Path, lighting: NffLighting) -> Result<Scene, SceneError> {
    let bytes = crate::memory::read_file(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read the scene file: {e}")))?;
    parse_nff(&ascii_text(&bytes), path, lighting)
}

/// Reads a scene from NFF text; `origin` names it in error messages.
pub fn parse_nff(text: &str, origin: &Path, lighting: NffLighting) -> Result<Scene, SceneError> {
    let source = Source { origin, text };
    let (document, locations) = parse::parse(source)?;
    document
        .to_scene(lighting)
        .map_err(|error| locate(error, &locations, source))
}

/// Reads NFF text into a document, without building a scene from it.
pub fn parse_nff_document(text: &str, origin: &Path) -> Result<NffDocument, SceneError> {
    Ok(parse::parse(Source { origin, text })?.0)
}

/// Places an error found while building at the keyword of the part at fault.
fn locate(error: BuildError, locations: &Locations, source: Source) -> SceneError {
    let span = match error.part {
        Part::Document => None,
        Part::View => locations.view.clone(),
        Part::Light(i) => locations.lights.get(i).cloned(),
        Part::Item(i) => locations.items.get(i).cloned(),
    };
    match span {
        Some(span) => source.error(span, error.message),
        None => SceneError::whole_file(source.origin, error.message),
    }
}
