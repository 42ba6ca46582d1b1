//! The lecture's parallel hardware, under the `gpu` feature: the GPU tracer, each part the twin
//! of a CPU part and tested against it on the same input. A compute device found without any
//! window ([`device`]); the objects' records and the shapes' WGSL ([`shapes`]); the BVH's nodes
//! and leaves ([`bvh`]); the textures' records and texels ([`texture`]); the caustic photon
//! map's photons ([`caustics`]); the whole scene on the GPU ([`scene`]); the ray tree's
//! pipeline and the colours of pixel samples ([`tracer`]); the film the colours go into on the
//! GPU, and how it reaches a texture ([`film`]); the raster pass that draws the item buffer
//! (the lecture's modified Z-buffer, [`item_raster`]); and test entry points for the closest hits and
//! the textures' colours ([`probe`]). The WGSL is in `shaders/`, split as the Rust it mirrors; every number
//! the two share is written once, in Rust, and given to the WGSL by [`prelude`].

pub mod bvh;
pub mod caustics;
pub mod device;
pub mod film;
pub mod frame;
pub mod item_raster;
pub mod materials;
pub mod prelude;
pub mod probe;
pub mod record;
pub mod scene;
pub mod shapes;
pub mod storage;
pub mod texture;
pub mod tracer;
pub mod wgsl_names;
