//! Model files (OBJ, PLY, glTF) in a scene: placed as objects of a TOML scene
//! (`type = "obj"`, `"ply"`, `"gltf"`), and opened as a scene of their own
//! ([`build_model_scene`]), where a glTF file's camera and lights are used and the other
//! formats' models are framed and lit from the eye.

use std::path::Path;

use toml::Spanned;

use super::build::{DEFAULT_MATERIAL, GeometryBuilder, MeshSpans, Names, file_error};
use super::placing::{ModelFile, ModelFormat, Target};
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
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::settings::RenderSettings;
use crate::transform::Transform;
use crate::views::VIEW_NUMBERS;

/// What a triangle and a vertex of a mesh copied into the world take in memory until the BVH is
/// built, at most: the mesh's vertices and faces, the triangles' records and the build's
/// working set.
const PLACED_BYTES_PER_TRIANGLE: u64 = 100;
const PLACED_BYTES_PER_VERTEX: u64 = 48;

/// The colour of the light a model file opened as a scene is lit by: white, at the eye.
const MODEL_LIGHT: Color = Color::splat(1.0);

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
    let mut builder = GeometryBuilder::new(
        source,
        files,
        Names::new("material", std::iter::empty(), DEFAULT_MATERIAL + 1),
        (vec![Material::default()], vec!["default".to_string()]),
        Vec::new(),
        Vec::new(),
    );
    let name = path.file_name().unwrap_or(path.as_os_str());
    let name = Spanned::new(0..0, name.to_string_lossy().into_owned());
    let added = builder.add_model_file(format, &name, None, None);
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
    /// Adds the model file `file` of `format` where it places its meshes, moved by `transform`,
    /// in `material` or else in the file's own materials (added to the scene's once). A file
    /// placed more than once in the scene, and a glTF mesh its nodes place more than once, is
    /// stored once and placed by instances. Returns a glTF file's model, for its camera and
    /// lights.
    pub(super) fn add_model_file(
        &mut self,
        format: ModelFormat,
        file: &Spanned<String>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<Option<GltfModel>, SceneError> {
        let path = self.files.path(file.get_ref());
        let mut gltf = None;
        if !self.model_files.contains_key(&path) {
            let with_materials = material.is_none() || self.uses(&path) > 1;
            let read = match format {
                ModelFormat::Obj => self.read_obj(file, &path, with_materials)?,
                ModelFormat::Ply => self.read_ply(file, &path)?,
                ModelFormat::Gltf => {
                    let (read, model) = self.read_gltf(file, &path, with_materials)?;
                    gltf = Some(model);
                    read
                }
            };
            self.model_files.insert(path.clone(), read);
        }
        self.place_model_file(&path, file, material, transform)?;
        Ok(gltf)
    }

    /// How often the scene places the model file at `path`: by objects naming it and by
    /// instances of those.
    fn uses(&self, path: &Path) -> usize {
        let file = Target::File(path.to_path_buf());
        self.uses.get(&file).copied().unwrap_or(1)
    }

    /// Places the model file at `path` (already read) again, as [`Self::add_model_file`] does;
    /// errors are reported at `file`.
    pub(super) fn place_model_file(
        &mut self,
        path: &Path,
        file: &Spanned<String>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<(), SceneError> {
        let uses = self.uses(path);
        let Some(mut model_file) = self.model_files.remove(path) else {
            unreachable!("a model file is read before it is placed")
        };
        let placed = self.place_parts(&mut model_file, uses, file, path, material, transform);
        self.model_files.insert(path.to_path_buf(), model_file);
        placed
    }

    /// Places each part of `model_file`: as copies moved into the world when the scene places
    /// the part once, or as instances of one model when more often.
    fn place_parts(
        &mut self,
        model_file: &mut ModelFile,
        uses: usize,
        file: &Spanned<String>,
        path: &Path,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<(), SceneError> {
        let fail = file_error(self.source, file, path, model_file.what);
        let spans = MeshSpans::all(file.span());
        let copied = (model_file.placements.iter())
            .filter(|&&(part, _)| uses * model_file.placed(part) == 1)
            .flat_map(|&(part, _)| &model_file.parts[part]);
        let (vertices, triangles) = copied.fold((0, 0), |(v, t), mesh| {
            (v + mesh.positions.len() as u64, t + mesh.faces.len() as u64)
        });
        memory::check(
            &format!("placing its {triangles} triangles"),
            vertices * PLACED_BYTES_PER_VERTEX + triangles * PLACED_BYTES_PER_TRIANGLE,
        )
        .map_err(&fail)?;
        for k in 0..model_file.placements.len() {
            let (part, node) = model_file.placements[k];
            let placed = match (node, &transform) {
                (Some(node), Some(outer)) => Some(node.then(outer)),
                (node, outer) => node.or(*outer),
            };
            if uses * model_file.placed(part) == 1 {
                for mesh in &model_file.parts[part] {
                    let own = mesh.material;
                    self.add_mesh(mesh.clone(), material.unwrap_or(own), placed, &spans)
                        .map_err(|e| fail(e.message))?;
                }
                continue;
            }
            let model = match model_file.models[part] {
                Some(model) => model,
                None => {
                    let model = self
                        .add_model(model_file.parts[part].clone(), &spans)
                        .map_err(|e| fail(e.message))?;
                    model_file.models[part] = Some(model);
                    model
                }
            };
            self.add_instance(model, material, placed, file.span())?;
        }
        Ok(())
    }

    /// Reads an OBJ file, each part of it a mesh: in its MTL materials, added to the scene's with
    /// the images their `map_Kd` lines name, when `with_materials` asks for them (else the
    /// default).
    fn read_obj(
        &mut self,
        file: &Spanned<String>,
        path: &Path,
        with_materials: bool,
    ) -> Result<ModelFile, SceneError> {
        let fail = file_error(self.source, file, path, "OBJ file");
        let contents = load_obj(path, self.files, with_materials).map_err(|e| match e {
            ObjError::At(error) => error,
            ObjError::Whole(message) => fail(message),
        })?;
        self.warnings.extend(contents.warnings);
        let first_mtl = self.materials.len();
        let mut mtl_count = 0;
        if with_materials && contents.parts.iter().any(|p| p.mtl_material.is_some()) {
            let mtl = contents
                .materials
                .map_err(|e| fail(format!("its MTL materials: {e}")))?;
            mtl_count = mtl.len();
            let obj_name = file.get_ref();
            self.names
                .extend((0..mtl_count).map(|i| format!("{obj_name} MTL #{i}")));
            let first_texture = self.textures.len() as u32;
            self.materials.extend(mtl.into_iter().map(|m| Material {
                texture: m.texture.map(|t| first_texture + t),
                ..m
            }));
            self.textures.extend(contents.textures);
        }
        let meshes = contents.parts.into_iter().map(|part| Mesh {
            material: match part.mtl_material {
                Some(i) if i < mtl_count => (first_mtl + i) as u32,
                _ => DEFAULT_MATERIAL,
            },
            ..part.mesh
        });
        Ok(ModelFile::one_part(meshes.collect(), "OBJ file"))
    }

    /// Reads the mesh of a PLY file, in the default material.
    fn read_ply(&mut self, file: &Spanned<String>, path: &Path) -> Result<ModelFile, SceneError> {
        let fail = file_error(self.source, file, path, "PLY file");
        let bytes = self.files.read(path).map_err(&fail)?;
        if let Some(what) = known_format(&bytes).filter(|what| !what.contains("PLY")) {
            return Err(fail(not_the_format(path, what, "PLY")));
        }
        let mesh = parse_ply(&bytes).map_err(|e| e.in_file(path, &bytes))?;
        let mesh = Mesh {
            material: DEFAULT_MATERIAL,
            ..mesh
        };
        Ok(ModelFile::one_part(vec![mesh], "PLY file"))
    }

    /// Reads a glTF file: its meshes, and where its default scene's nodes place them; in the
    /// file's own materials, added to the scene's (named `FILE › NAME`) with their textures,
    /// when `with_materials` asks for them (else the default).
    fn read_gltf(
        &mut self,
        file: &Spanned<String>,
        path: &Path,
        with_materials: bool,
    ) -> Result<(ModelFile, GltfModel), SceneError> {
        let fail = file_error(self.source, file, path, "glTF file");
        let bytes = self.files.read(path).map_err(&fail)?;
        if let Some(what) = known_format(&bytes).filter(|what| !what.contains("glTF")) {
            return Err(fail(not_the_format(path, what, "glTF")));
        }
        let model = read_gltf(path, &bytes, self.files)?;
        let first = self.materials.len() as u32;
        if with_materials {
            let name = file.get_ref();
            self.names
                .extend(model.material_names.iter().map(|n| format!("{name} › {n}")));
            let first_texture = self.textures.len() as u32;
            self.materials
                .extend(model.materials.iter().map(|m| Material {
                    texture: m.texture.map(|t| first_texture + t),
                    emission_texture: m.emission_texture.map(|t| first_texture + t),
                    ..m.clone()
                }));
            self.textures.extend(model.textures.iter().cloned());
        }
        let mut placements = Vec::with_capacity(model.placements.meshes.len());
        for &(mesh, world) in &model.placements.meshes {
            let node = Transform::from_matrix(world).ok_or_else(|| {
                fail(format!(
                    "a node placing mesh {mesh} has a matrix that squashes it flat"
                ))
            })?;
            placements.push((mesh, Some(node)));
        }
        let parts = (model.meshes.iter())
            .map(|primitives| {
                let in_material = |primitive: &Mesh| Mesh {
                    material: match primitive.material {
                        index if with_materials && index != NO_MATERIAL => first + index,
                        _ => DEFAULT_MATERIAL,
                    },
                    ..primitive.clone()
                };
                primitives.iter().map(in_material).collect()
            })
            .collect();
        let note = format!("{}: {}", path.display(), model.report);
        self.notes.push(note);
        let model_file = ModelFile {
            parts,
            placements,
            models: vec![None; model.meshes.len()],
            what: "glTF file",
        };
        Ok((model_file, model))
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
