//! The scene: everything a render needs, as plain data, read by the BVH builder and the tracer.
//! It is made by code or read from a file by one of the [`crate::formats`] (TOML, NFF, a
//! built-in SPD scene), which depend on it; it knows none of them.

use std::sync::Arc;

use crate::camera::{self, Camera};
use crate::light::Light;
use crate::material::Material;
use crate::medium::Atmosphere;
use crate::primitive::{Geometry, Object};
use crate::settings::RenderSettings;
use crate::shapes::Shape;
use crate::srgb_image::SrgbImage;
use crate::texture::Texture;
use crate::transform::Transform;
use crate::views::Views;

#[derive(Clone, Debug)]
pub struct Scene {
    pub settings: RenderSettings,
    pub camera: Camera,
    pub lights: Vec<Light>,
    /// The fog filling the scene; clear air (density 0) when the file has no `[atmosphere]`.
    pub atmosphere: Atmosphere,
    pub materials: Vec<Material>,
    /// The materials' names, index for index: the scene file's names, "default" for the TOML
    /// reader's default material, "nff #k" for NFF fills, "#k" for materials added by code.
    pub material_names: Vec<String>,
    pub textures: Vec<Texture>,
    /// What rays that leave the scene see, instead of the background colour (SDL's
    /// `backgroundImage`): an image standing on the image plane, as tall as the view and
    /// centred, at its own aspect ratio; the background colour shows around it
    /// ([`Camera::backdrop_uv`]).
    pub background_image: Option<Arc<SrgbImage>>,
    pub geometry: Geometry,
    /// What the reader accepted but a person should hear about (`file:line: message`): a
    /// material an OBJ file names but never defines, a face it dropped. The scene renders as
    /// read; the command line prints these, the viewer shows them.
    pub warnings: Vec<String>,
    /// What the reader made of the file that is not wrong but worth a line (`file: message`):
    /// what a glTF model's materials became. Printed as notes, shown in the viewer.
    pub notes: Vec<String>,
    /// The bookmarked views the file brings: a glTF model's cameras, numbered from 1. A views
    /// file beside the scene (`NAME.views.toml`) takes their place in the viewer.
    pub views: Views,
}

impl Scene {
    /// An empty scene (no lights, no objects) seen by `camera`.
    pub fn new(settings: RenderSettings, camera: Camera) -> Scene {
        Scene {
            settings,
            camera,
            lights: Vec::new(),
            atmosphere: Atmosphere::default(),
            materials: Vec::new(),
            material_names: Vec::new(),
            textures: Vec::new(),
            background_image: None,
            geometry: Geometry::default(),
            warnings: Vec::new(),
            notes: Vec::new(),
            views: Views::default(),
        }
    }

    /// The default framing camera ([`camera::frame`]): a three-quarter view of the finite
    /// objects at the image's aspect, as the viewer's F frames them.
    pub fn framing_camera(&self) -> Camera {
        let aspect = self.settings.width as f32 / self.settings.height as f32;
        camera::frame(&self.geometry.finite_bounds(), aspect)
    }

    /// Adds a material, named "#k" after its index k, and returns its index.
    pub fn add_material(&mut self, material: Material) -> u32 {
        let name = format!("#{}", self.materials.len());
        self.add_named_material(name, material)
    }

    /// Adds a material with a name and returns its index.
    pub fn add_named_material(&mut self, name: String, material: Material) -> u32 {
        self.material_names.push(name);
        self.materials.push(material);
        self.materials.len() as u32 - 1
    }

    /// The name of material `index` (its number if it has none).
    pub fn material_name(&self, index: u32) -> String {
        match self.material_names.get(index as usize) {
            Some(name) => name.clone(),
            None => format!("#{index}"),
        }
    }

    /// Adds an analytic shape, with an optional transform, and returns its object index.
    pub fn add_object(
        &mut self,
        shape: Shape,
        transform: Option<Transform>,
        material: u32,
    ) -> usize {
        self.geometry.objects.push(Object {
            shape,
            transform: transform.map(Box::new),
            material,
        });
        self.geometry.objects.len() - 1
    }
}
