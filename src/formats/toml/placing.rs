//! What the builder keeps of the objects it has placed, for the objects that place them again:
//! the model files read (each read once, however often placed), what each object became, and
//! how often the scene places each thing, counted before anything is built: a thing placed
//! once is stored where it stands, one placed more often is stored once and placed by
//! instances.

use std::path::PathBuf;

use toml::Spanned;

use crate::mesh::Mesh;
use crate::transform::Transform;

/// The formats of model files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelFormat {
    Obj,
    Ply,
    Gltf,
}

/// What an object places, as the count of placements tells things apart.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) enum Target {
    /// A model file, by its path.
    File(PathBuf),
    /// The scene file's object at this index: its own mesh or shape.
    Object(usize),
}

/// What an object of the scene became, for instances of it.
#[derive(Clone, Debug)]
pub(super) enum Placed {
    /// A model file (named at `file`), in `material` or the file's own.
    File {
        path: PathBuf,
        file: Spanned<String>,
        material: Option<u32>,
    },
    /// A mesh of the scene file, stored once as this model of the geometry, in `material` or
    /// the default.
    Model { model: u32, material: Option<u32> },
    /// A mesh of the scene file that nothing places again, stored where it stands.
    Mesh,
    /// An analytic object: its index among the geometry's objects.
    Object(usize),
}

/// A model file read for a scene: its meshes in the file's own space, grouped into the parts
/// the file places (an OBJ or PLY file is one part, a glTF file has one per glTF mesh), with
/// their materials the scene's, and where the file places each part.
pub(super) struct ModelFile {
    pub(super) parts: Vec<Vec<Mesh>>,
    /// Each part the file places, with the node's transform (none for OBJ and PLY).
    pub(super) placements: Vec<(usize, Option<Transform>)>,
    /// The model each part became in the geometry, once it is placed more than once.
    pub(super) models: Vec<Option<u32>>,
    /// What the file is, for errors: "OBJ file", "PLY file", "glTF file".
    pub(super) what: &'static str,
}

impl ModelFile {
    /// A file of one part, placed as it is.
    pub(super) fn one_part(meshes: Vec<Mesh>, what: &'static str) -> ModelFile {
        ModelFile {
            parts: vec![meshes],
            placements: vec![(0, None)],
            models: vec![None],
            what,
        }
    }

    /// How often the file itself places `part`.
    pub(super) fn placed(&self, part: usize) -> usize {
        self.placements.iter().filter(|(p, _)| *p == part).count()
    }
}
