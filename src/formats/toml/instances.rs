//! Objects placed more than once: a model file named by several objects, a mesh or any object
//! placed again by `type = "instance"`, `of = "NAME"`. Before anything is built the scene's
//! placements are counted ([`GeometryBuilder::count_placements`]); a mesh placed more than
//! once is stored once, as a model of the geometry, and each placement is an instance of it
//! ([`crate::primitive::instance`]).

use std::ops::Range;

use toml::Spanned;

use super::build::{DEFAULT_MATERIAL, GeometryBuilder, MeshSpans};
use super::object_file::{ObjectFile, ShapeFile};
use super::placing::{Placed, Target};
use crate::formats::SceneError;
use crate::limits;
use crate::mesh::Mesh;
use crate::primitive::{Geometry, Instance};
use crate::transform::Transform;

impl GeometryBuilder<'_> {
    /// Counts how often the scene's `objects` place each model file and each object, through
    /// instances too; an error for two objects of one name, or an instance of a name no
    /// object above it has.
    pub(super) fn count_placements(&mut self, objects: &[ObjectFile]) -> Result<(), SceneError> {
        let mut targets: Vec<(Option<&Spanned<String>>, Target)> = Vec::new();
        for (index, object) in objects.iter().enumerate() {
            let target = match object.shape.get_ref() {
                ShapeFile::Obj { file } | ShapeFile::Ply { file } | ShapeFile::Gltf { file } => {
                    Target::File(self.files.path(file.get_ref()))
                }
                ShapeFile::Instance { of } => {
                    let named = targets
                        .iter()
                        .rev()
                        .find(|(name, _)| name.is_some_and(|name| name.get_ref() == of.get_ref()));
                    match named {
                        Some((_, target)) => target.clone(),
                        None => return Err(self.no_object_named(of)),
                    }
                }
                _ => Target::Object(index),
            };
            *self.uses.entry(target.clone()).or_insert(0) += 1;
            let name = object.name.as_ref();
            if let Some(name) = name
                && let Some((Some(first), _)) = targets
                    .iter()
                    .find(|(other, _)| other.is_some_and(|o| o.get_ref() == name.get_ref()))
            {
                let line = self.source.error(first.span(), "").line;
                return Err(self.source.error(
                    name.span(),
                    format!(
                        "an object above (line {line}) is named `{}` already",
                        name.get_ref()
                    ),
                ));
            }
            targets.push((name, target));
        }
        Ok(())
    }

    /// The error for `of = NAME` naming no object above it.
    fn no_object_named(&self, of: &Spanned<String>) -> SceneError {
        self.source.error(
            of.span(),
            format!(
                "no object above this one is named `{}` (give it `name = \"{}\"`)",
                of.get_ref(),
                of.get_ref()
            ),
        )
    }

    /// Adds the mesh the scene file writes out for object `index`: stored where it stands when
    /// nothing places it again, else stored once as a model and placed by an instance.
    pub(super) fn add_scene_mesh(
        &mut self,
        index: usize,
        mesh: Mesh,
        material: Option<u32>,
        transform: Option<Transform>,
        spans: &MeshSpans,
    ) -> Result<Placed, SceneError> {
        if self.uses.get(&Target::Object(index)).copied().unwrap_or(1) == 1 {
            let in_material = material.unwrap_or(DEFAULT_MATERIAL);
            self.add_mesh(mesh, in_material, transform, spans)?;
            return Ok(Placed::Mesh);
        }
        let mesh = Mesh {
            material: DEFAULT_MATERIAL,
            ..mesh
        };
        let model = self.add_model(vec![mesh], spans)?;
        self.add_instance(model, material, transform, spans.whole.clone())?;
        Ok(Placed::Model { model, material })
    }

    /// Places the object named `of` again, by `transform`, in `material` or else in that
    /// object's.
    pub(super) fn add_instance_of(
        &mut self,
        of: &Spanned<String>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<Placed, SceneError> {
        let named = self
            .placed
            .iter()
            .rev()
            .find(|(name, _)| name.as_deref() == Some(of.get_ref().as_str()));
        let Some((_, placed)) = named.cloned() else {
            return Err(self.no_object_named(of));
        };
        Ok(match placed {
            Placed::File {
                path,
                file,
                material: own,
            } => {
                let material = material.or(own);
                self.place_model_file(&path, &file, material, transform)?;
                Placed::File {
                    path,
                    file,
                    material,
                }
            }
            Placed::Model {
                model,
                material: own,
            } => {
                let material = material.or(own);
                self.add_instance(model, material, transform, of.span())?;
                Placed::Model { model, material }
            }
            Placed::Mesh => unreachable!("a mesh placed again is stored as a model"),
            Placed::Object(index) => {
                let object = &self.geometry.objects[index];
                let shape = object.shape.clone();
                let material = material.or(Some(object.material));
                self.add_shape(shape, of.span(), material, transform)?;
                Placed::Object(self.geometry.objects.len() - 1)
            }
        })
    }

    /// Adds `meshes`, in their own space, as a model for instances to place; errors about a
    /// mesh are reported at `spans`.
    pub(super) fn add_model(
        &mut self,
        meshes: Vec<Mesh>,
        spans: &MeshSpans,
    ) -> Result<u32, SceneError> {
        let mut model = Geometry::default();
        for mesh in meshes {
            mesh.validate()
                .map_err(|e| self.source.error(spans.of(&e), e.to_string()))?;
            model.add_mesh(mesh);
        }
        Ok(self.geometry.add_model(model))
    }

    /// Places `model` by `transform` (none: where it stands), in `material` (none: its meshes'
    /// own); an error at `span` when it would reach past [`limits::MAX_COORDINATE`] or pass
    /// the limits on instances.
    pub(super) fn add_instance(
        &mut self,
        model: u32,
        material: Option<u32>,
        transform: Option<Transform>,
        span: Range<usize>,
    ) -> Result<(), SceneError> {
        let transform = transform.unwrap_or(Transform::IDENTITY);
        let bounds = transform.bounds_to_world(&self.geometry.model_bounds(model as usize));
        limits::check_bounds("the placed model", &bounds)
            .map_err(|message| self.source.error(span.clone(), message))?;
        let instance = Instance {
            model,
            transform,
            material,
        };
        self.geometry
            .add_instance(instance)
            .map_err(|message| self.source.error(span, message))
    }
}
