//! The tracing behind the window: the render worker refining the image, the render in progress,
//! the scene copies the tracing threads keep, and the picked pixel whose ray tree is traced on
//! its own thread.

pub mod picked_pixel;
pub mod ray_tree_thread;
pub mod rendering;
pub mod worker;
pub mod working_scene;
