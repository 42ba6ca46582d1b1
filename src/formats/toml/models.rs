//! Model files (OBJ, PLY, glTF) in a scene: placed as objects of a TOML scene
//! (`type = "obj"`, `"ply"`, `"gltf"`), and opened as a scene of their own
//! ([`build_model_scene`]), where a glTF file's camera and lights are used and the other
//! formats' models are framed and lit from the eye.

use std::path::Path;

use toml::Spanned;

use super::build::{DEFAULT_MATERIAL, GeometryBuilder, MeshSpans, Names, file_error};
use crate::camera::Camera;
use crate::color::Color;
use crate::formats::SceneFiles;
use crate::formats::gltf::lights::{camera_view, whitted_light};
use crate::formats::gltf::{GltfModel, NO_MATERIAL, read_gltf};
use crate::formats::obj::{ObjError, load_obj};
use crate::formats::ply::parse_ply;
use crate::formats::{SceneError, Source};
use crate::formats::{known_format, not_the_format};
use crate::light::Light;
use crate::limits;
use crate::material::Material;
use crate::memory;
use crate::primitive::Geometry;
use crate::scene::Scene;
use crate::settings::RenderSettings;
use crate::transform::Transform;
use crate::views::VIEW_NUMBERS;

/// What a triangle and a vertex of a placed glTF mesh take in memory until the BVH is built,
/// at most: the mesh's vertices and faces, the triangles' records and the build's working set.
const PLACED_BYTES_PER_TRIANGLE: u64 = 100;
const PLACED_BYTES_PER_VERTEX: u64 = 48;

/// The colour of the light a model file opened as a scene is lit by: white, at the eye.
const MODEL_LIGHT: Color = Color::splat(1.0);

/// The formats of model files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelFormat {
    Obj,
    Ply,
    Gltf,
}

/// The model file at `path` as a scene of its own: its meshes with their materials (OBJ's MTL
/// materials, glTF's by the rule of [`crate::formats::gltf::materials`]; the default material
/// where there are none) and the default render settings. A glTF file's first perspective
/// camera and its lights are used; where a file has no camera, the camera frames the model as
/// the viewer's F does, and where it has no lights, a white point light at the eye lights it,
/// which a warning tells of.
pub fn build_model_scene(
    path: &Path,
    files: SceneFiles,
    format: ModelFormat,
) -> Result<Scene, SceneError> {
    let source = Source {
        origin: path,
        text: "",
    };
    let mut builder = GeometryBuilder {
        source,
        files,
        material_names: Names::new("material", std::iter::empty(), DEFAULT_MATERIAL + 1),
        materials: vec![Material::default()],
        names: vec!["default".to_string()],
        geometry: Geometry::default(),
        warnings: Vec::new(),
        notes: Vec::new(),
        textures: Vec::new(),
    };
    let name = path.file_name().unwrap_or(path.as_os_str());
    let name = Spanned::new(0..0, name.to_string_lossy().into_owned());
    let added = match format {
        ModelFormat::Obj => builder.add_obj(name, None, None).map(|()| None),
        ModelFormat::Ply => builder.add_ply(name, None, None).map(|()| None),
        ModelFormat::Gltf => builder.add_gltf(name, None, None).map(Some),
    };
    let gltf = added.map_err(|error| {
        // An error about the whole file has no line of its own to show.
        match error.source_line.as_deref() {
            Some("") => SceneError::whole_file(path, error.message),
            _ => error,
        }
    })?;
    let mut scene = Scene::new(RenderSettings::default(), Camera::default());
    scene.materials = builder.materials;
    scene.material_names = builder.names;
    scene.geometry = builder.geometry;
    scene.warnings = builder.warnings;
    scene.notes = builder.notes;
    scene.textures = builder.textures;
    let has_camera = match &gltf {
        Some(model) => use_gltf_camera_and_lights(&mut scene, model)
            .map_err(|e| SceneError::whole_file(path, e))?,
        None => false,
    };
    if !has_camera {
        scene.camera = scene.framing_camera();
    }
    if scene.lights.is_empty() {
        scene.lights.push(Light::Point {
            position: scene.camera.eye,
            color: MODEL_LIGHT,
        });
        let kind = match format {
            ModelFormat::Obj => "an OBJ",
            ModelFormat::Ply => "a PLY",
            ModelFormat::Gltf => "a glTF",
        };
        let what = if has_camera {
            "no lights: raylab lit it"
        } else {
            "no lights or camera: raylab framed the model and lit it"
        };
        scene.warnings.push(format!(
            "{}: {kind} file has {what} with a white point light at the eye",
            path.display()
        ));
    } else if !has_camera {
        scene.warnings.push(format!(
            "{}: the file has no perspective camera: raylab framed the model",
            path.display()
        ));
    }
    Ok(scene)
}

impl GeometryBuilder<'_> {
    /// Adds each part of an OBJ file as a mesh. Without a `material` key, parts use their MTL
    /// materials, which are added to the scene's.
    pub(super) fn add_obj(
        &mut self,
        file: Spanned<String>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<(), SceneError> {
        let path = self.files.path(file.get_ref());
        let fail = file_error(self.source, &file, &path, "OBJ file");
        let contents = load_obj(&path, self.files, material.is_none()).map_err(|e| match e {
            ObjError::At(error) => error,
            ObjError::Whole(message) => fail(message),
        })?;
        // A file used twice warns once.
        for warning in contents.warnings {
            if !self.warnings.contains(&warning) {
                self.warnings.push(warning);
            }
        }
        let first_mtl = self.materials.len();
        let mut mtl_count = 0;
        if material.is_none() && contents.parts.iter().any(|p| p.mtl_material.is_some()) {
            let mtl = contents
                .materials
                .map_err(|e| fail(format!("its MTL materials: {e}")))?;
            mtl_count = mtl.len();
            let obj_name = file.get_ref();
            self.names
                .extend((0..mtl_count).map(|i| format!("{obj_name} MTL #{i}")));
            self.materials.extend(mtl);
        }
        for part in contents.parts {
            let part_material = material.unwrap_or_else(|| match part.mtl_material {
                Some(i) if i < mtl_count => (first_mtl + i) as u32,
                _ => DEFAULT_MATERIAL,
            });
            let spans = MeshSpans::all(file.span());
            self.add_mesh(part.mesh, part_material, transform, &spans)
                .map_err(|e| fail(e.message))?;
        }
        Ok(())
    }

    /// Adds the mesh of a PLY file, in `material` or the default one.
    pub(super) fn add_ply(
        &mut self,
        file: Spanned<String>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<(), SceneError> {
        let path = self.files.path(file.get_ref());
        let fail = file_error(self.source, &file, &path, "PLY file");
        let bytes = self.files.read(&path).map_err(&fail)?;
        if let Some(what) = known_format(&bytes).filter(|what| !what.contains("PLY")) {
            return Err(fail(not_the_format(&path, what, "PLY")));
        }
        let mesh = parse_ply(&bytes).map_err(|e| e.in_file(&path, &bytes))?;
        let spans = MeshSpans::all(file.span());
        let material = material.unwrap_or(DEFAULT_MATERIAL);
        self.add_mesh(mesh, material, transform, &spans)
            .map_err(|e| fail(e.message))
    }

    /// Adds the meshes of a glTF file where its default scene's nodes place them, then moved
    /// by `transform`; in `material`, or else in the file's own materials, which are added to
    /// the scene's (named `FILE › NAME`). Returns the model, for its camera and lights.
    pub(super) fn add_gltf(
        &mut self,
        file: Spanned<String>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<GltfModel, SceneError> {
        let path = self.files.path(file.get_ref());
        let fail = file_error(self.source, &file, &path, "glTF file");
        let bytes = self.files.read(&path).map_err(&fail)?;
        if let Some(what) = known_format(&bytes).filter(|what| !what.contains("glTF")) {
            return Err(fail(not_the_format(&path, what, "glTF")));
        }
        let model = read_gltf(&path, &bytes, self.files)?;
        let (mut vertices, mut triangles) = (0u64, 0u64);
        for &(mesh, _) in &model.placements.meshes {
            for primitive in &model.meshes[mesh] {
                vertices += primitive.positions.len() as u64;
                triangles += primitive.faces.len() as u64;
            }
        }
        memory::check(
            &format!("placing its {triangles} triangles"),
            vertices * PLACED_BYTES_PER_VERTEX + triangles * PLACED_BYTES_PER_TRIANGLE,
        )
        .map_err(&fail)?;
        let first = self.materials.len() as u32;
        if material.is_none() {
            let name = file.get_ref();
            self.names
                .extend(model.material_names.iter().map(|n| format!("{name} › {n}")));
            let first_texture = self.textures.len() as u32;
            self.materials
                .extend(model.materials.iter().map(|m| Material {
                    texture: m.texture.map(|t| first_texture + t),
                    ..m.clone()
                }));
            self.textures.extend(model.textures.iter().cloned());
        }
        let spans = MeshSpans::all(file.span());
        for &(mesh, world) in &model.placements.meshes {
            let node = Transform::from_matrix(world).ok_or_else(|| {
                fail(format!(
                    "a node placing mesh {mesh} has a matrix that squashes it flat"
                ))
            })?;
            let placed = match &transform {
                Some(outer) => node.then(outer),
                None => node,
            };
            for primitive in &model.meshes[mesh] {
                let part_material = material.unwrap_or(match primitive.material {
                    NO_MATERIAL => DEFAULT_MATERIAL,
                    index => first + index,
                });
                self.add_mesh(primitive.clone(), part_material, Some(placed), &spans)
                    .map_err(|e| fail(e.message))?;
            }
        }
        let note = format!("{}: {}", path.display(), model.report);
        if !self.notes.contains(&note) {
            self.notes.push(note);
        }
        Ok(model)
    }
}

/// Sets the scene's camera to the glTF file's first perspective camera (its aspect ratio the
/// image's, when the file gives one), its views to the first nine, and adds the file's lights;
/// true if there was a camera.
fn use_gltf_camera_and_lights(scene: &mut Scene, model: &GltfModel) -> Result<bool, String> {
    let centre = scene.geometry.finite_bounds().center();
    for &(index, world) in &model.placements.lights {
        scene
            .lights
            .push(whitted_light(&model.document, index, world, centre)?);
    }
    let cameras: Vec<_> = model
        .placements
        .cameras
        .iter()
        .filter_map(|&(index, world)| camera_view(&model.document, index, world, centre))
        .collect();
    for (number, (spec, _)) in VIEW_NUMBERS.zip(&cameras) {
        scene.views.set(number, *spec)?;
    }
    let Some(&(spec, aspect)) = cameras.first() else {
        return Ok(false);
    };
    if let Some(aspect) = aspect {
        let height = scene.settings.height;
        let width = (height as f32 * aspect)
            .round()
            .clamp(1.0, limits::MAX_IMAGE_SIDE as f32);
        scene.settings.width = width as u32;
    }
    scene.camera = Camera::new(spec).map_err(|e| format!("its camera: {e}"))?;
    Ok(true)
}
