//! raylab: a Whitted ray tracer after Hill & Kelley's lecture (ch. 12). The data flows one way:
//!
//! ```text
//! scene file → Scene → Bvh → whitted tracer → progressive renderer → Film → image file
//!                                   ↑                   ↑
//!                                   └────── inspect ────┘  (ray trees, debug views)
//! ```
//!
//! and the modules depend on each other in that order only, each on those listed before it
//! (`tests/library/module_order.rs` checks it):
//!
//! - Basics: [`color`] (linear RGB and its 8-bit sRGB encoding), [`ray`], [`aabb`],
//!   [`tone`] (exposure and tone curves), [`transform`], [`limits`], [`memory`], [`output`]
//!   (writing files safely), [`camera`] (the one place a pixel becomes an eye ray), [`views`]
//!   (bookmarked cameras, and the cameras of a turntable or a path through them), [`sampling`]
//!   (where a pixel's samples lie), [`tiles`] (an image cut into rectangles rendered apart,
//!   and checking that parts cover it once) and [`srgb_image`] (any image file read as 8-bit
//!   sRGB pixels, for textures and for comparing images).
//! - The scene: [`shapes`], [`mesh`], [`primitive`], [`light`], [`medium`] (fog), [`material`],
//!   [`noise`] and the [`texture`]s made of it, [`settings`] and [`scene::Scene`], which
//!   [`formats`] reads from TOML, OBJ, NFF, SPD and SDL files (or [`large_mesh`] generates, for
//!   benchmarks).
//! - Tracing: [`bvh::Bvh`] finds what a ray hits, [`stats`] counts rays, an
//!   [`item_buffer::ItemBuffer`] holds the first hits a raster pass found (the lecture's modified
//!   Z-buffer) and a [`photon_map::PhotonMap`] holds the light of caustics; [`whitted`] builds each eye ray's ray
//!   tree with them, adding the caustics, and tells a [`whitted::TreeObserver`] what it does;
//!   [`photon`] fills the photon map beforehand by shooting photons from the lights with the
//!   same tracer.
//! - Rendering: [`render`] assembles what a render needs from a scene (its BVH, its caustic
//!   photons, the tracer over them) for every program; a [`film::Film`] holds the image; [`gpu`]
//!   (under the `gpu` feature) holds the GPU tracer's parts, each the twin of a CPU part above
//!   and tested against it, the film included; [`progressive`] refines the image pass after
//!   pass (the plan and control of any backend, the CPU sweep on all cores, the GPU sweep), each
//!   CPU pixel sample coloured by a [`progressive::SampleColoring`] (the shaded image is
//!   [`progressive::Shaded`]); [`formats::image`] saves it.
//! - Looking inside: [`inspect`] records one pixel's ray tree with a tree observer and renders
//!   debug views as shaders of the same renderer; [`figure`] draws that ray tree in the scene
//!   as the lecture's figure, seen from an observer camera; [`compare`] measures how another image
//!   differs from raylab's, and [`grade`] grades a class's images with it, for a teacher's
//!   report. Nothing above depends on them.
//! - Where the back ends meet: [`backend`] runs a render's passes on the CPU or on the GPU, with
//!   first hits from the rays or the item buffer, in any of [`inspect`]'s views; every program
//!   renders through it, and nothing else chooses between the tracers.
//!
//! Nothing here knows about windows, and only [`gpu`] about GPUs.

pub mod aabb;
pub mod backend;
pub mod bvh;
pub mod camera;
pub mod color;
pub mod compare;
pub mod figure;
pub mod film;
pub mod formats;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod grade;
pub mod inspect;
pub mod item_buffer;
pub mod large_mesh;
pub mod light;
pub mod limits;
pub mod material;
pub mod medium;
pub mod memory;
pub mod mesh;
pub mod noise;
pub mod output;
pub mod photon;
pub mod photon_map;
pub mod primitive;
pub mod progressive;
pub mod ray;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod settings;
pub mod shapes;
pub mod srgb_image;
pub mod stats;
pub mod texture;
pub mod tiles;
pub mod tone;
pub mod transform;
pub mod views;
pub mod whitted;
