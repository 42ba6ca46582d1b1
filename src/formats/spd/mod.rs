//! Eric Haines' Standard Procedural Databases (SPD), built in: generators for the seven
//! benchmark scenes (balls, gears, mount, rings, teapot, tetra, tree), written after the
//! databases' published descriptions, that make the same primitives as SPD's own programs at
//! every size factor. They produce [`NffDocument`]s, so a scene can be written out as NFF or
//! rendered by name (`spd:balls:4`) without a file.

mod balls;
mod conventions;
mod gears;
mod mount;
mod rings;
mod teapot;
mod teapot_patches;
mod tetra;
mod tree;

pub(crate) use teapot::utah_teapot;

use std::path::Path;

use strum::VariantNames;

use crate::formats::SceneError;
use crate::formats::nff::{NffDocument, NffLighting};
use crate::scene::Scene;

/// The prefix of built-in SPD scene names.
pub const SCENE_PREFIX: &str = "spd:";

/// One of the seven SPD benchmark databases, named in lower case (`balls`).
#[derive(
    Clone,
    Copy,
    Debug,
    PartialEq,
    Eq,
    Hash,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase", parse_err_ty = String, parse_err_fn = unknown_database)]
pub enum Database {
    Balls,
    Gears,
    Mount,
    Rings,
    Teapot,
    Tetra,
    Tree,
}

impl Database {
    /// The size factor whose ray statistics the SPD readme publishes (under 10,000 primitives).
    pub fn standard_size(self) -> u32 {
        match self {
            Database::Balls | Database::Gears => 4,
            Database::Mount | Database::Tetra => 6,
            Database::Rings => 7,
            Database::Teapot => 12,
            Database::Tree => 11,
        }
    }

    /// The largest size factor raylab generates: about a million primitives.
    pub fn max_size(self) -> u32 {
        match self {
            Database::Balls => 6,
            Database::Gears => 20,
            Database::Mount => 9,
            Database::Rings => 40,
            Database::Teapot => 128,
            Database::Tetra => 10,
            Database::Tree => 18,
        }
    }

    /// The database at size factor `size` (from 1 to [`Self::max_size`]).
    pub fn generate(self, size: u32) -> Result<NffDocument, String> {
        if !(1..=self.max_size()).contains(&size) {
            return Err(format!(
                "the size of {self} must be from 1 to {}, got {size}",
                self.max_size()
            ));
        }
        Ok(match self {
            Database::Balls => balls::balls(size),
            Database::Gears => gears::gears(size),
            Database::Mount => mount::mount(size),
            Database::Rings => rings::rings(size),
            Database::Teapot => teapot::teapot(size),
            Database::Tetra => tetra::tetra(size),
            Database::Tree => tree::tree(size),
        })
    }
}

/// Why `name` is no database's name.
fn unknown_database(name: &str) -> String {
    format!(
        "unknown SPD database `{name}`; expected one of {}",
        Database::VARIANTS.join(", ")
    )
}

/// The database and size a built-in scene name asks for: `spd:NAME` (the standard size) or
/// `spd:NAME:SIZE`.
pub fn parse_scene_name(name: &str) -> Result<(Database, u32), String> {
    let rest = name
        .strip_prefix(SCENE_PREFIX)
        .ok_or_else(|| format!("an SPD scene name starts with `{SCENE_PREFIX}`"))?;
    let (database, size) = match rest.split_once(':') {
        Some((database, size)) => (database, Some(size)),
        None => (rest, None),
    };
    let database: Database = database.parse()?;
    let size = match size {
        None => database.standard_size(),
        Some(size) => size
            .parse()
            .map_err(|_| format!("the size in `{name}` must be a whole number, got `{size}`"))?,
    };
    Ok((database, size))
}

/// The built-in scene `name` (`spd:balls`, `spd:tree:6`), lit as `lighting` says.
pub fn load_spd(name: &str, lighting: NffLighting) -> Result<Scene, SceneError> {
    let fail = |message: String| SceneError::whole_file(Path::new(name), message);
    let (database, size) = parse_scene_name(name).map_err(fail)?;
    let document = database.generate(size).map_err(fail)?;
    document
        .to_scene(lighting)
        .map_err(|error| fail(error.to_string()))
}
