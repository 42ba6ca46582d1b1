//! What the user sees besides the image (egui): the side panel, the status line, the ray tree
//! panel, the overlay drawn over the image, the legend's colour bar, colour swatches, and where
//! the image sits in the window.

pub mod layout;
pub mod legend_bar;
pub mod overlay;
pub mod panels;
pub mod ray_tree_panel;
pub mod status;
pub mod swatch;
