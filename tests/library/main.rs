//! The library as a program uses it, without the command line or a window: shapes, the BVH,
//! shading, the camera, the scene readers, the progressive sweep, images against references a
//! person looked at, and the rules the source tree keeps.

#[path = "../common/mod.rs"]
mod common;

mod bvh;
mod camera;
mod caustics;
mod csg;
mod cut_outs;
mod debug_views;
mod device_seam;
mod figure;
mod fog;
mod fuzz_corpus;
mod gltf_models;
mod images;
mod inspect;
mod inspect_image;
mod instances;
mod limits;
mod media;
mod models;
mod module_cycles;
mod module_order;
mod nff;
mod progressive;
mod rust_source;
mod sdl;
mod shading;
mod shapes_props;
mod spd;
mod spd_povray;
mod spot_light;
mod tiles;
mod watertight;
