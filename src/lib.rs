//! raylab: a Whitted ray tracer after Hill & Kelley's lecture (ch. 12). The data flows one way:
//! scene file → [`scene::Scene`] → [`bvh::Bvh`] → [`whitted`] tracer → [`film::Film`] → image.
//! Nothing here knows about windows or GPUs.

pub mod aabb;
pub mod bvh;
pub mod camera;
pub mod color;
pub mod film;
pub mod inspect;
pub mod large_mesh;
pub mod light;
pub mod limits;
pub mod material;
pub mod memory;
pub mod mesh;
pub mod nff;
pub mod output;
pub mod primitive;
pub mod progressive;
pub mod ray;
pub mod sampling;
pub mod scene;
pub mod settings;
pub mod shapes;
pub mod spd;
pub mod stats;
pub mod texture;
pub mod transform;
pub mod whitted;
