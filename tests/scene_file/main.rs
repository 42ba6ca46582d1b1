//! The TOML scene format end to end: the shipped scenes load, a full-feature file becomes the
//! expected `Scene`, OBJ and image files are found relative to the scene file, every kind of
//! mistake is reported at its line and column, and no input makes the reader panic.

#[path = "../common/mod.rs"]
mod common;
mod harness;

mod errors;
mod full_feature;
mod media_and_settings;
mod obj_files;
mod robustness;
mod shapes_and_lights;
mod shipped;
