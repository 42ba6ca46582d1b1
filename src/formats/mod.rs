//! Scene formats: everything raylab reads a [`Scene`](crate::scene::Scene) from or writes an
//! image to. [`load_any`] reads any scene raylab knows by its name: a built-in SPD scene
//! ([`spd`]), an NFF file ([`nff`]), an SDL file ([`sdl`]), a model ([`ply`], [`gltf`] or OBJ)
//! or a TOML scene file ([`toml`], which places models in its scenes); [`image`] writes the
//! rendered picture. Every reader reports bad input as a
//! [`SceneError`] at its `file:line:column`. The formats depend on the scene; the scene knows
//! none of them.

mod error;
mod files;
pub mod gltf;
pub mod image;
mod load_any;
pub mod nff;
mod obj;
pub mod part;
pub mod ply;
pub mod sdl;
mod sniff;
pub mod spd;
pub mod toml;

pub(crate) use error::Source;
pub use error::{SceneError, printable};
pub use files::{SceneFiles, ascii_text, utf8_text};
pub use load_any::{
    SCENE_EXTENSIONS, SceneFormat, camera_file_beside, camera_path, load_any, load_any_as,
    load_any_with, views_path, with_framing_camera,
};
pub use sniff::{known_format, not_the_format};
