//! The scene: everything a render needs, as plain data. It is made from a scene file
//! ([`file`]) or by code, and read by the BVH builder and the tracer.

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
