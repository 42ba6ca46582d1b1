//! The scene: everything a render needs, as plain data. It is read from a TOML scene file
//! ([`load_scene`], [`parse_scene`]) or made by code, and read by the BVH builder and the
//! tracer.

mod build;
mod error;
mod file;
mod load;
mod obj;
mod retag;
mod values;

pub use build::DEFAULT_MATERIAL;
pub use error::SceneError;
pub use load::{load_scene, parse_scene};

use crate::camera::Camera;
use crate::light::Light;
use crate::material::Material;
use crate::primitive::Geometry;
use crate::settings::RenderSettings;
use crate::texture::Texture;

#[derive(Clone, Debug)]
pub struct Scene {
    pub settings: RenderSettings,
    pub camera: Camera,
    pub lights: Vec<Light>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub geometry: Geometry,
}
