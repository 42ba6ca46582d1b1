//! Everything that talks to the GPU (wgpu): the device, the window's surface, the image quad and
//! egui drawn into a frame, the film's upload into the image texture, and screenshots read back
//! from the GPU.

pub mod device;
pub mod painter;
pub mod quad;
pub mod screenshot;
pub mod surface;
pub mod upload;
