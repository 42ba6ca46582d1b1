//! The GPU tracer against the CPU tracer on the same input: each shape's hits, the film, the
//! item buffer's first hits, whole images, and the backend that chooses between them. The tests need a Vulkan, Metal or DX12 adapter
//! (Mesa's software Vulkan, lavapipe, is enough); without one they fail, saying what to install.

use std::sync::{Arc, OnceLock};

use raylab::gpu::device::GpuDevice;

#[path = "../common/mod.rs"]
mod common;

mod backend;
mod film;
mod images;
mod item_buffer;
mod kinds;
mod shapes;

/// The GPU every test shares, found once: each pipeline is then compiled once for all the tests
/// (a software GPU takes a while to compile the tracer).
pub fn gpu() -> Arc<GpuDevice> {
    static GPU: OnceLock<Arc<GpuDevice>> = OnceLock::new();
    GPU.get_or_init(|| {
        Arc::new(GpuDevice::new().unwrap_or_else(|e| panic!("these tests run on a GPU: {e}")))
    })
    .clone()
}
