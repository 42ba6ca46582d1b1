//! raylab's own scene files, in TOML ([`load_scene`], [`parse_scene`]), and a model file opened as
//! a scene of its own ([`load_model_scene`]: OBJ, PLY or glTF); the camera files saved
//! beside them ([`load_camera`]), the views files saved beside them ([`load_views`],
//! [`views_text`]), and the built-in default scene written in one
//! ([`default_scene`]). `load` reads a file in four steps: the
//! text is parsed as TOML, `retag` moves its type tags where serde wants them, serde reads the
//! schema (`file`, its objects in `object_file`, with the checked numbers of `values`), and `build` turns the schema into a
//! [`Scene`](crate::scene::Scene), with `models` placing model files. `edit` writes a viewer's edits of materials and lights back
//! into the file ([`save_edits`]).

mod build;
mod builtin;
mod edit;
mod file;
mod instances;
mod load;
mod models;
mod object_file;
mod placing;
mod retag;
mod values;
mod views;

pub use build::DEFAULT_MATERIAL;
pub use builtin::{DEFAULT_SCENE_TEXT, default_scene};
pub use edit::{Looks, SavedEdits, edit_text, save_edits};
pub use load::{load_camera, load_model_scene, load_scene, parse_scene, parse_scene_with};
pub use models::build_model_scene;
pub use placing::ModelFormat;
pub use views::{camera_table, load_views, parse_views, views_text};
