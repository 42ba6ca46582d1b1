//! The state the book's parser keeps while it reads, and the scene it builds: the current
//! material (which `push`/`pop` do not save), the stack of current transforms, and the objects,
//! each placed by the transform on top of the stack when it is made.

use std::collections::HashMap;

use glam::Affine3A;

use crate::camera::{Camera, CameraSpec};
use crate::color::Color;
use crate::limits;
use crate::material::Material;
use crate::memory;
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::settings::RenderSettings;
use crate::shapes::{Csg, Shape};
use crate::transform::{Transform, TransformStep};

/// Memory a triangle of a mesh takes, at most, with its share of the BVH (an estimate).
const BYTES_PER_TRIANGLE: u64 = 256;

/// The most triangles the meshes of an SDL scene may hold (2500 teapots).
pub const MAX_TRIANGLES: u64 = 10_000_000;

/// How many triangles a scene may have before their memory is checked.
const FIRST_MEMORY_CHECK: u64 = 1 << 20;

/// The book's material: colours for each term of its shading model, as `Material::setDefault`
/// sets them.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SdlMaterial {
    pub ambient: Color,
    pub diffuse: Color,
    pub specular: Color,
    pub specular_exponent: f32,
    pub reflectivity: f32,
    pub transparency: f32,
    /// The speed of light in the material, relative to its speed outside.
    pub speed_of_light: f32,
}

impl Default for SdlMaterial {
    fn default() -> Self {
        SdlMaterial {
            ambient: Color::splat(0.1),
            diffuse: Color::splat(0.8),
            specular: Color::ZERO,
            specular_exponent: 1.0,
            reflectivity: 0.0,
            transparency: 0.0,
            speed_of_light: 1.0,
        }
    }
}

impl SdlMaterial {
    /// raylab's nearest material. raylab's surface has one colour that its ambient and diffuse
    /// coefficients scale: the diffuse colour, with `ka` the ambient colour's mean over the
    /// diffuse colour's mean. The specular colour becomes the highlight's colour, its largest
    /// component `ks`; the index of refraction is the inverse of the speed of light.
    pub fn to_material(&self) -> Material {
        let mean = |c: Color| (c.x + c.y + c.z) / 3.0;
        let ambient = if mean(self.diffuse) > 0.0 {
            mean(self.ambient) / mean(self.diffuse)
        } else {
            0.0
        };
        let specular = self.specular.max_element().max(0.0);
        Material {
            color: self.diffuse,
            texture: None,
            ambient,
            diffuse: 1.0,
            specular,
            specular_color: if specular > 0.0 {
                self.specular / specular
            } else {
                Color::ONE
            },
            shininess: self.specular_exponent,
            reflectivity: self.reflectivity,
            transparency: self.transparency,
            ior: 1.0 / self.speed_of_light,
            fresnel: false,
        }
    }
}

/// The scene being built, and the reader's state.
#[derive(Debug)]
pub(crate) struct Builder {
    pub scene: Scene,
    pub material: SdlMaterial,
    /// The last material given to the scene, and its index, shared by the shapes that follow
    /// while the material stays the same.
    added: Option<(SdlMaterial, u32)>,
    /// The stack of current transforms (object to world); never empty.
    stack: Vec<Affine3A>,
    /// `minReflectivity` and `minTransparency`: raylab's one cut-off is the smaller.
    pub min_reflectivity: f32,
    pub min_transparency: f32,
    /// Triangles in the scene's meshes so far, and how many there must be to check the memory
    /// they take again.
    triangles: u64,
    next_memory_check: u64,
    /// Polyhedra and the teapot, made once per file.
    solids: HashMap<String, Mesh>,
}

impl Builder {
    /// An empty scene with the book's defaults (`Scene::Scene`) and a placeholder camera.
    pub fn new() -> Builder {
        let settings = RenderSettings {
            max_depth: 3,
            min_weight: 0.5,
            background: Color::new(0.0, 0.0, 0.6),
            ambient: Color::splat(0.1),
            ..RenderSettings::default()
        };
        let camera = Camera::new(CameraSpec::default()).expect("the default camera is valid");
        Builder {
            scene: Scene::new(settings, camera),
            material: SdlMaterial::default(),
            added: None,
            stack: vec![Affine3A::IDENTITY],
            min_reflectivity: 0.5,
            min_transparency: 0.5,
            triangles: 0,
            next_memory_check: FIRST_MEMORY_CHECK,
            solids: HashMap::new(),
        }
    }

    fn top(&mut self) -> &mut Affine3A {
        self.stack.last_mut().expect("the stack is never empty")
    }

    /// `translate`, `scale`, `rotate`: multiplies the current transform on the right, so the
    /// step written last before a shape is applied to it first.
    pub fn transform(&mut self, step: TransformStep) -> Result<(), String> {
        let step = Transform::from_steps(&[step]).map_err(|e| e.to_string())?;
        let top = self.top();
        *top *= step.world_from_object;
        Ok(())
    }

    pub fn push(&mut self) {
        let top = *self.top();
        self.stack.push(top);
    }

    /// `pop`; `false` when there was nothing to pop (the stack keeps its identity).
    pub fn pop(&mut self) -> bool {
        if self.stack.len() > 1 {
            self.stack.pop();
            true
        } else {
            *self.top() = Affine3A::IDENTITY;
            false
        }
    }

    pub fn identity(&mut self) {
        *self.top() = Affine3A::IDENTITY;
    }

    /// How many `push`es were never popped.
    pub fn open_pushes(&self) -> usize {
        self.stack.len() - 1
    }

    /// The current material's index in the scene.
    fn material_index(&mut self) -> u32 {
        match &self.added {
            Some((material, index)) if *material == self.material => *index,
            _ => {
                let index = self.scene.add_material(self.material.to_material());
                self.added = Some((self.material.clone(), index));
                index
            }
        }
    }

    /// The current transform, checked: it must be invertible.
    fn current(&mut self, frame: Affine3A) -> Result<Transform, String> {
        let transform = Transform::from_affine(*self.top() * frame);
        if !transform.object_from_world.is_finite() {
            return Err("the current transform cannot be undone in single precision (a scale too large or too small)".to_string());
        }
        Ok(transform)
    }

    /// Adds a shape in its object space, placed by the current transform, in the current
    /// material.
    pub fn shape(&mut self, shape: Shape) -> Result<(), String> {
        self.shape_in_frame(shape, Affine3A::IDENTITY)
    }

    /// [`Self::shape`] for a shape that raylab models in another frame than the book does:
    /// `frame` takes raylab's frame of the shape into the book's object space.
    pub fn shape_in_frame(&mut self, shape: Shape, frame: Affine3A) -> Result<(), String> {
        let transform = self.current(frame)?;
        if let Some(bounds) = shape.bounds() {
            let bounds = transform.bounds_to_world(&bounds);
            limits::check_bounds(&format!("the {}", shape.name()), &bounds)?;
        }
        let material = self.material_index();
        self.scene.add_object(shape, Some(transform), material);
        Ok(())
    }

    /// Adds a boolean object. As in the book, the node has no transform or material of its own:
    /// each operand keeps the ones in force when it was read.
    pub fn boolean(&mut self, csg: Csg) -> Result<(), String> {
        let shape = Shape::Csg(Box::new(csg));
        if let Some(bounds) = shape.bounds() {
            limits::check_bounds("the boolean object", &bounds)?;
        }
        let material = self.material_index();
        self.scene.add_object(shape, None, material);
        Ok(())
    }

    /// Adds a mesh in its object space, placed and coloured as [`Self::shape`] does. A few
    /// `use`s of a teapot can ask for billions of triangles: there may be at most
    /// [`MAX_TRIANGLES`], and each time they double, the memory they take is checked.
    pub fn mesh(&mut self, mut mesh: Mesh) -> Result<(), String> {
        self.triangles += mesh.faces.len() as u64;
        if self.triangles > MAX_TRIANGLES {
            return Err(format!(
                "the scene's meshes would hold more than {MAX_TRIANGLES} triangles \
                 (raylab's limit for an SDL scene)"
            ));
        }
        if self.triangles >= self.next_memory_check {
            self.next_memory_check = self.triangles * 2;
            memory::check(
                &format!("{} triangles", self.triangles),
                self.triangles * BYTES_PER_TRIANGLE,
            )?;
        }
        mesh.transform(&self.current(Affine3A::IDENTITY)?);
        mesh.validate().map_err(|e| e.to_string())?;
        mesh.material = self.material_index();
        self.scene.geometry.add_mesh(mesh);
        Ok(())
    }

    /// A polyhedron or the teapot, made by `make` the first time the file names it.
    pub fn solid(&mut self, name: &str, make: impl FnOnce() -> Mesh) -> Result<(), String> {
        let mesh = self
            .solids
            .entry(name.to_string())
            .or_insert_with(make)
            .clone();
        self.mesh(mesh)
    }

    /// Sets raylab's adaptive cut-off from `minReflectivity` and `minTransparency`: the smaller.
    pub fn set_cutoff(&mut self) {
        self.scene.settings.min_weight = self.min_reflectivity.min(self.min_transparency);
    }
}
