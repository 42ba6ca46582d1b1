//! What the user (or a script) asks for and how it is carried out: the mouse and keys over the
//! image, the scripted steps and clicks, the [`action::Action`]s they all become, and what the
//! actions do (camera navigation, picking a surface point, the ray tree's pixel, open, save).

pub mod action;
pub mod apply;
#[cfg(test)]
pub mod harness;
pub mod mouse_and_keys;
pub mod navigation;
pub mod pick;
pub mod script;
pub mod synthetic;
