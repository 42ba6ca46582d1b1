//! The scene being shown: loading scene files (or the built-in scene) in the background, watching
//! the file for changes, and the controls (camera, settings, lights, view) the user edits.

pub mod controls;
pub mod source;
pub mod watch;
