//! The lecture's parallel hardware, under the `gpu` feature: the GPU tracer's parts, each the twin
//! of a CPU part and tested against it on the same input. So far: a compute device found without
//! any window ([`device`]) and the shapes' WGSL ([`shapes`], in `shaders/shapes/`), whose closest
//! hits are checked against the CPU's intersection.

pub mod device;
pub mod shapes;
