//! Turning the schema into a [`Scene`]: defaults filled in, names resolved to indices, the
//! checks that need more than one value, and textures and OBJ files loaded from disk. Every
//! error points at the value it is about.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::Vec2;
use toml::Spanned;

use super::file::{
    AtmosphereFile, CameraFile, LightFile, MaterialFile, MediumFile, RenderFile, SceneFile,
    TextureFile, WrapFile,
};
use super::object_file::{CsgOperationFile, ObjectFile, ShapeFile, TransformStepFile};
use super::placing::{ModelFile, ModelFormat, Placed, Target};
use super::values::{ColorValue, Direction, Exact, NonNegative, TexCoord, Vector};
use crate::camera::{Camera, CameraError, CameraSpec};
use crate::color::Color;
use crate::formats::SceneFiles;
use crate::formats::{SceneError, Source};
use crate::light::{Light, Spot};
use crate::limits;
use crate::material::Material;
use crate::medium::{Atmosphere, Medium};
use crate::mesh::{Mesh, MeshError};
use crate::primitive::{Geometry, Object};
use crate::scene::Scene;
use crate::settings::RenderSettings;
use crate::shapes::{Csg, CsgOperation, Operand, Shape, Triangle};
use crate::srgb_image::SrgbImage;
use crate::texture::{Texture, WOOD_COLORS, Wrap};
use crate::transform::{Transform, TransformStep};
use crate::views::Views;

/// Index of the material of objects that name none: `Material::default()`. The named materials
/// follow it in name order.
pub const DEFAULT_MATERIAL: u32 = 0;

/// Default colours and sizes of checkerboards.
const CHECKER_A: Color = Color::splat(0.9);
const CHECKER_B: Color = Color::splat(0.1);
const CHECKER_SIZE: f32 = 1.0;
const CHECKER_UV_COUNT: f32 = 8.0;
/// The default colour of marble's stone, darkened in its veins.
const MARBLE_COLOR: Color = Color::new(0.9, 0.88, 0.85);

/// Builds the scene. File names are looked up in `files`.
pub(crate) fn build_scene(
    file: SceneFile,
    source: Source,
    files: SceneFiles,
) -> Result<Scene, SceneError> {
    let background_image = match &file.render.background_image {
        Some(name) => Some(load_image(name, "background image", source, files)?),
        None => None,
    };
    let settings = build_settings(file.render, source)?;
    let has_camera = file.camera.is_some();
    let camera = build_camera(file.camera, CameraSpec::default(), source)?;
    let lights = file
        .lights
        .into_iter()
        .map(|light| build_light(light, source))
        .collect::<Result<_, _>>()?;
    let atmosphere = file
        .atmosphere
        .map_or(Atmosphere::default(), build_atmosphere);

    let texture_names = Names::new("texture", file.textures.keys(), 0);
    let material_names = Names::new("material", file.materials.keys(), DEFAULT_MATERIAL + 1);
    let mut names = vec!["default".to_string()];
    names.extend(file.materials.keys().cloned());
    let mut warnings = Vec::new();
    let mut materials = vec![Material::default()];
    for (name, material) in file.materials {
        let material = build_material(material, &texture_names, source)?;
        if material.medium.is_some() && material.transparency == 0.0 {
            warnings.push(format!(
                "{}: material `{name}` has a medium but is opaque (transparency 0): no light \
                 passes into it, so the medium shows nowhere",
                source.origin.display()
            ));
        }
        materials.push(material);
    }

    // Only the textures a material uses are loaded (an image can be large), renumbered in
    // name order.
    let used: BTreeSet<u32> = (materials.iter())
        .flat_map(|m| [m.texture, m.emission_texture])
        .flatten()
        .collect();
    for material in &mut materials {
        for t in [&mut material.texture, &mut material.emission_texture]
            .into_iter()
            .flatten()
        {
            *t = used.range(..*t).count() as u32;
        }
    }
    let mut textures = Vec::new();
    for (index, (name, texture)) in file.textures.into_iter().enumerate() {
        if used.contains(&(index as u32)) {
            textures.push(build_texture(texture, source, files)?);
        } else {
            warnings.push(format!(
                "{}: texture `{name}` is not used by any material, so it is not loaded",
                source.origin.display()
            ));
        }
    }

    let mut builder = GeometryBuilder::new(
        source,
        files,
        material_names,
        (materials, names),
        textures,
        warnings,
    );
    builder.count_placements(&file.objects)?;
    for object in file.objects {
        builder.add_object(object)?;
    }
    let mut scene = Scene {
        settings,
        camera,
        lights,
        atmosphere,
        materials: builder.materials,
        material_names: builder.names,
        textures: builder.textures,
        background_image,
        geometry: builder.geometry,
        warnings: builder.warnings,
        notes: builder.notes,
        views: Views::default(),
    };
    // A file without a camera is seen as the viewer's F frames it.
    if !has_camera {
        scene.camera = scene.framing_camera();
    }
    Ok(scene)
}

/// How an error about the file at `path`, which the scene names at `file`, is reported: at that
/// value, `cannot load WHAT `PATH`: message`.
pub(super) fn file_error<'s>(
    source: Source<'s>,
    file: &Spanned<String>,
    path: &Path,
    what: &str,
) -> impl Fn(String) -> SceneError + use<'s> {
    let (span, path, what) = (file.span(), path.display().to_string(), what.to_string());
    move |message| {
        source.error(
            span.clone(),
            format!("cannot load {what} `{path}`: {message}"),
        )
    }
}

/// The names a file gives textures or materials, and the indices they stand for.
pub(super) struct Names {
    /// What is named, for messages.
    what: &'static str,
    indices: BTreeMap<String, u32>,
}

impl Names {
    /// Numbers `names` in order from `first`.
    pub(super) fn new<'a>(
        what: &'static str,
        names: impl Iterator<Item = &'a String>,
        first: u32,
    ) -> Self {
        let indices = names.cloned().zip(first..).collect();
        Names { what, indices }
    }

    fn resolve(&self, name: &Spanned<String>, source: Source) -> Result<u32, SceneError> {
        self.indices.get(name.get_ref()).copied().ok_or_else(|| {
            let expected = if self.indices.is_empty() {
                format!("the scene defines no {}s", self.what)
            } else {
                let known: Vec<String> = self.indices.keys().map(|n| format!("`{n}`")).collect();
                format!("expected one of {}", known.join(", "))
            };
            source.error(
                name.span(),
                format!("unknown {} `{}`; {expected}", self.what, name.get_ref()),
            )
        })
    }
}

/// Applies the `[render]` keys one at a time, checking the settings after each, so that an
/// out-of-range value is reported at its own key.
fn build_settings(render: RenderFile, source: Source) -> Result<RenderSettings, SceneError> {
    fn apply<T>(
        settings: &mut RenderSettings,
        value: Option<Spanned<T>>,
        set: fn(&mut RenderSettings, T),
        source: Source,
    ) -> Result<(), SceneError> {
        if let Some(value) = value {
            let span = value.span();
            set(settings, value.into_inner());
            settings
                .validate()
                .map_err(|message| source.error(span, message))?;
        }
        Ok(())
    }
    let mut settings = RenderSettings::default();
    let s = &mut settings;
    apply(s, render.width, |s, v| s.width = v, source)?;
    apply(s, render.height, |s, v| s.height = v, source)?;
    apply(s, render.max_depth, |s, v| s.max_depth = v, source)?;
    apply(s, render.min_weight, |s, v| s.min_weight = v, source)?;
    apply(s, render.block_size, |s, v| s.block_size = v, source)?;
    apply(s, render.samples, |s, v| s.samples = v, source)?;
    apply(s, render.aa_threshold, |s, v| s.aa_threshold = v, source)?;
    apply(s, render.background, |s, v| s.background = v.0, source)?;
    apply(s, render.ambient, |s, v| s.ambient = v.0, source)?;
    apply(s, render.shadows, |s, v| s.shadows = v, source)?;
    apply(s, render.reflections, |s, v| s.reflections = v, source)?;
    apply(s, render.transmission, |s, v| s.transmission = v, source)?;
    apply(s, render.textures, |s, v| s.textures = v, source)?;
    apply(s, render.fog_steps, |s, v| s.fog_steps = v, source)?;
    apply(
        s,
        render.caustic_photons,
        |s, v| s.caustic_photons = v,
        source,
    )?;
    apply(
        s,
        render.caustic_gather,
        |s, v| s.caustic_gather = v,
        source,
    )?;
    Ok(settings)
}

/// The camera: each key the table leaves out is `default`'s. An error points at the key it is
/// about, or at `[camera]` when that key was left to its default.
pub(super) fn build_camera(
    camera: Option<Spanned<CameraFile>>,
    default: CameraSpec,
    source: Source,
) -> Result<Camera, SceneError> {
    let (table_span, file) = match camera {
        Some(camera) => (camera.span(), camera.into_inner()),
        None => (0..0, CameraFile::default()),
    };
    let vector =
        |v: &Option<Spanned<Vector>>, default| v.as_ref().map_or(default, |v| v.get_ref().0);
    let number = |x: &Option<Spanned<f32>>, default| x.as_ref().map_or(default, |x| *x.get_ref());
    let spec = CameraSpec {
        eye: vector(&file.eye, default.eye),
        look_at: vector(&file.look_at, default.look_at),
        up: vector(&file.up, default.up),
        view_angle: number(&file.view_angle, default.view_angle),
        near: number(&file.near, default.near),
    };
    Camera::new(spec).map_err(|error| {
        let key_span = match error {
            CameraError::EyeAtLookAt => file.look_at.or(file.eye).map(|k| k.span()),
            CameraError::Eye(_) => file.eye.map(|k| k.span()),
            CameraError::LookAt(_) => file.look_at.map(|k| k.span()),
            CameraError::UpParallelToView => file.up.map(|k| k.span()),
            CameraError::ViewAngle(_) => file.view_angle.map(|k| k.span()),
            CameraError::Near(_) => file.near.map(|k| k.span()),
        };
        source.error(key_span.unwrap_or(table_span), error.to_string())
    })
}

/// Largest half-angle of a spot light's cone, in degrees: a cone wider than a half-space
/// would no longer be a spot.
const MAX_SPOT_ANGLE: f32 = 90.0;

fn build_light(light: LightFile, source: Source) -> Result<Light, SceneError> {
    let color = |color: Option<ColorValue>, intensity: Option<NonNegative>| {
        color.map_or(Color::ONE, |c| c.0) * intensity.map_or(1.0, |i| i.0)
    };
    Ok(match light {
        LightFile::Point {
            position,
            color: c,
            intensity,
        } => Light::Point {
            position: position.0,
            color: color(c, intensity),
        },
        LightFile::Directional {
            direction,
            color: c,
            intensity,
        } => Light::Directional {
            direction: direction.0,
            color: color(c, intensity),
        },
        LightFile::Spot {
            position,
            direction,
            angle,
            falloff,
            color: c,
            intensity,
        } => {
            let angle_degrees = *angle.get_ref();
            if !(angle_degrees > 0.0 && angle_degrees <= MAX_SPOT_ANGLE) {
                return Err(source.error(
                    angle.span(),
                    format!(
                        "a spot light's angle (the half-angle of its cone, in degrees) must be \
                         more than 0 and at most {MAX_SPOT_ANGLE}, got {angle_degrees}"
                    ),
                ));
            }
            let falloff_degrees = falloff.as_ref().map_or(0.0, |f| *f.get_ref());
            if let Some(falloff) = falloff
                && !(0.0..=angle_degrees).contains(&falloff_degrees)
            {
                return Err(source.error(
                    falloff.span(),
                    format!(
                        "a spot light's falloff (the degrees of soft edge inside its angle) must \
                         be from 0 to the angle, {angle_degrees}, got {falloff_degrees}"
                    ),
                ));
            }
            Light::Spot(Spot::new(
                position.0,
                direction.0,
                angle_degrees,
                falloff_degrees,
                color(c, intensity),
            ))
        }
    })
}

fn build_atmosphere(atmosphere: AtmosphereFile) -> Atmosphere {
    let medium = MediumFile {
        density: atmosphere.density,
        albedo: atmosphere.albedo,
        color: atmosphere.color,
    };
    Atmosphere {
        medium: build_medium(medium),
        background_distance: atmosphere.background_distance.map(|d| d.0),
    }
}

fn build_medium(medium: MediumFile) -> Medium {
    let clear = Medium::default();
    Medium {
        density: medium.density.0,
        albedo: medium.albedo.map_or(clear.albedo, |a| a.0),
        color: medium.color.map_or(clear.color, |c| c.0),
    }
}

/// The image the file names at `file` (relative to the scene file's folder), the `what` of
/// the error if it cannot be read or decoded.
fn load_image(
    file: &Spanned<String>,
    what: &str,
    source: Source,
    files: SceneFiles,
) -> Result<Arc<SrgbImage>, SceneError> {
    let path = files.path(file.get_ref());
    let fail = file_error(source, file, &path, what);
    let bytes = files.read(&path).map_err(&fail)?;
    Ok(Arc::new(SrgbImage::decode(&bytes).map_err(fail)?))
}

fn build_texture(
    texture: TextureFile,
    source: Source,
    files: SceneFiles,
) -> Result<Texture, SceneError> {
    let color = |c: Option<ColorValue>, default| c.map_or(default, |c| c.0);
    Ok(match texture {
        TextureFile::Checker3d { a, b, size } => Texture::Checker3d {
            a: color(a, CHECKER_A),
            b: color(b, CHECKER_B),
            size: size.map_or(CHECKER_SIZE, |s| s.0),
        },
        TextureFile::CheckerUv {
            a,
            b,
            u_count,
            v_count,
        } => Texture::CheckerUv {
            a: color(a, CHECKER_A),
            b: color(b, CHECKER_B),
            u_count: u_count.map_or(CHECKER_UV_COUNT, |n| n.0),
            v_count: v_count.map_or(CHECKER_UV_COUNT, |n| n.0),
        },
        TextureFile::Wood { a, b } => Texture::Wood {
            a: color(a, WOOD_COLORS.0),
            b: color(b, WOOD_COLORS.1),
        },
        TextureFile::Marble { color: stone } => Texture::Marble {
            color: color(stone, MARBLE_COLOR),
        },
        TextureFile::Image { file, wrap, scale } => {
            let image = load_image(&file, "texture image", source, files)?;
            Texture::Image {
                image,
                wrap: [match wrap {
                    None | Some(WrapFile::Repeat) => Wrap::Repeat,
                    Some(WrapFile::Clamp) => Wrap::Clamp,
                    Some(WrapFile::Mirror) => Wrap::Mirror,
                }; 2],
                scale: scale.map_or(Vec2::ONE, |Exact([u, v])| Vec2::new(u.0, v.0)),
                offset: Vec2::ZERO,
            }
        }
    })
}

fn build_material(
    material: MaterialFile,
    textures: &Names,
    source: Source,
) -> Result<Material, SceneError> {
    let default = Material::default();
    Ok(Material {
        color: material.color.map_or(default.color, |c| c.0),
        texture: material
            .texture
            .map(|name| textures.resolve(&name, source))
            .transpose()?,
        alpha_cutoff: material.alpha_cutoff.map(|x| x.0),
        emission: material.emission.map_or(default.emission, |c| c.0),
        emission_texture: material
            .emission_texture
            .map(|name| textures.resolve(&name, source))
            .transpose()?,
        ambient: material.ambient.map_or(default.ambient, |x| x.0),
        diffuse: material.diffuse.map_or(default.diffuse, |x| x.0),
        specular: material.specular.map_or(default.specular, |x| x.0),
        specular_color: material
            .specular_color
            .map_or(default.specular_color, |c| c.0),
        shininess: material.shininess.map_or(default.shininess, |x| x.0),
        reflectivity: material.reflectivity.map_or(default.reflectivity, |x| x.0),
        reflection_color: material
            .reflection_color
            .map_or(default.reflection_color, |c| c.0),
        transparency: material.transparency.map_or(default.transparency, |x| x.0),
        ior: material.ior.map_or(default.ior, |x| x.0),
        fresnel: material.fresnel.unwrap_or(default.fresnel),
        medium: material.medium.map(build_medium),
    })
}

/// The transform of `transform = [ … ]`; `None` for an empty list.
fn build_transform(
    steps: Spanned<Vec<TransformStepFile>>,
    source: Source,
) -> Result<Option<Transform>, SceneError> {
    let span = steps.span();
    let steps: Vec<TransformStep> = steps
        .into_inner()
        .into_iter()
        .map(|step| match step {
            TransformStepFile::Translate(t) => TransformStep::Translate(t.0),
            TransformStepFile::Rotate { axis, degrees } => TransformStep::Rotate {
                axis: axis.0,
                degrees: degrees.0,
            },
            TransformStepFile::Scale(s) => TransformStep::Scale(s.0),
        })
        .collect();
    if steps.is_empty() {
        return Ok(None);
    }
    let transform =
        Transform::from_steps(&steps).map_err(|e| source.error(span.clone(), e.to_string()))?;
    // Steps that are each fine can still multiply out past what single precision holds, or to
    // something too small to invert.
    if !transform.world_from_object.is_finite() {
        return Err(source.error(
            span,
            "the transform's steps multiply out past the largest single-precision number",
        ));
    }
    if !transform.object_from_world.is_finite() {
        return Err(source.error(span, "the transform squashes the object too flat to invert"));
    }
    Ok(Some(transform))
}

/// A mesh of one triangle.
fn triangle_mesh(
    vertices: [Vector; 3],
    normals: Option<Exact<Direction, 3>>,
    uvs: Option<Exact<TexCoord, 3>>,
) -> Result<Mesh, String> {
    let positions = vertices.map(|v| v.0);
    if Triangle::new(positions, 0).double_area() <= 0.0 {
        return Err("the triangle's vertices lie on one line, so it has no area".into());
    }
    Ok(Mesh {
        positions: positions.to_vec(),
        normals: normals.map_or(Vec::new(), |n| n.0.map(|n| n.0).to_vec()),
        uvs: uvs.map_or(Vec::new(), |uv| uv.0.map(|uv| uv.0).to_vec()),
        colors: Vec::new(),
        faces: vec![[0, 1, 2]],
        material: DEFAULT_MATERIAL,
    })
}

/// Where the parts of a mesh are in the file, to point a [`MeshError`] at.
pub(super) struct MeshSpans {
    pub(super) whole: Range<usize>,
    faces: Range<usize>,
    normals: Range<usize>,
    uvs: Range<usize>,
}

impl MeshSpans {
    pub(super) fn all(span: Range<usize>) -> Self {
        MeshSpans {
            whole: span.clone(),
            faces: span.clone(),
            normals: span.clone(),
            uvs: span,
        }
    }

    pub(super) fn of(&self, error: &MeshError) -> Range<usize> {
        match error {
            MeshError::IndexOutOfRange { .. } => self.faces.clone(),
            MeshError::NormalCount { .. } => self.normals.clone(),
            MeshError::UvCount { .. } => self.uvs.clone(),
            MeshError::ColorCount { .. } | MeshError::NotFinite | MeshError::OutOfRange(_) => {
                self.whole.clone()
            }
        }
    }
}

/// Collects the objects' geometry, and the materials model files bring along.
pub(super) struct GeometryBuilder<'a> {
    pub(super) source: Source<'a>,
    pub(super) files: SceneFiles<'a>,
    pub(super) material_names: Names,
    pub(super) materials: Vec<Material>,
    /// The materials' names, index for index.
    pub(super) names: Vec<String>,
    pub(super) geometry: Geometry,
    /// What the model files hold that is worth a warning (`file:line: message`).
    pub(super) warnings: Vec<String>,
    /// What the model files became (`file: glTF: 3 materials → …`).
    pub(super) notes: Vec<String>,
    /// The scene's textures, and those model files bring along.
    pub(super) textures: Vec<Texture>,
    /// The model files read so far, by path.
    pub(super) model_files: HashMap<PathBuf, ModelFile>,
    /// How often the scene places each thing (one when not counted).
    pub(super) uses: HashMap<Target, usize>,
    /// What each object of the scene placed so far became, for instances of it, with its name.
    pub(super) placed: Vec<(Option<String>, Placed)>,
}

impl<'a> GeometryBuilder<'a> {
    /// A builder of no geometry yet, with the scene's materials (and their names), textures
    /// and warnings so far.
    pub(super) fn new(
        source: Source<'a>,
        files: SceneFiles<'a>,
        material_names: Names,
        (materials, names): (Vec<Material>, Vec<String>),
        textures: Vec<Texture>,
        warnings: Vec<String>,
    ) -> Self {
        GeometryBuilder {
            source,
            files,
            material_names,
            materials,
            names,
            geometry: Geometry::default(),
            warnings,
            notes: Vec::new(),
            textures,
            model_files: HashMap::new(),
            uses: HashMap::new(),
            placed: Vec::new(),
        }
    }
}

impl GeometryBuilder<'_> {
    /// Adds one object: a mesh, a model file, an instance of an object above it, or an analytic
    /// shape (see [`Self::analytic_shape`]).
    fn add_object(&mut self, object: ObjectFile) -> Result<(), SceneError> {
        let name = object.name.as_ref().map(|name| name.get_ref().clone());
        let index = self.placed.len();
        let placed = self.add_shape_of(object, index)?;
        self.placed.push((name, placed));
        Ok(())
    }

    /// Adds the shape of object `index`, and says what it became.
    fn add_shape_of(&mut self, object: ObjectFile, index: usize) -> Result<Placed, SceneError> {
        let source = self.source;
        let (material, transform) = self.placement(object.material, object.transform, None)?;
        let span = object.shape.span();
        match object.shape.into_inner() {
            ShapeFile::Triangle {
                vertices,
                normals,
                uvs,
            } => {
                let vertices_span = vertices.span();
                let mesh = triangle_mesh(vertices.into_inner().0, normals, uvs)
                    .map_err(|message| source.error(vertices_span.clone(), message))?;
                let spans = MeshSpans::all(vertices_span);
                self.add_scene_mesh(index, mesh, material, transform, &spans)
            }
            ShapeFile::Mesh {
                positions,
                faces,
                normals,
                uvs,
            } => {
                let spans = MeshSpans {
                    whole: span.clone(),
                    faces: faces.span(),
                    normals: normals.as_ref().map_or(span.clone(), |n| n.span()),
                    uvs: uvs.as_ref().map_or(span.clone(), |uv| uv.span()),
                };
                let mesh = Mesh {
                    positions: positions.iter().map(|p| p.0).collect(),
                    normals: normals
                        .map_or(Vec::new(), |n| n.get_ref().iter().map(|n| n.0).collect()),
                    uvs: uvs.map_or(Vec::new(), |uv| {
                        uv.get_ref().iter().map(|uv| uv.0).collect()
                    }),
                    colors: Vec::new(),
                    faces: faces.into_inner().into_iter().map(|f| f.0).collect(),
                    material: DEFAULT_MATERIAL,
                };
                self.add_scene_mesh(index, mesh, material, transform, &spans)
            }
            ShapeFile::Obj { file } => self.add_file(ModelFormat::Obj, file, material, transform),
            ShapeFile::Ply { file } => self.add_file(ModelFormat::Ply, file, material, transform),
            ShapeFile::Gltf { file } => self.add_file(ModelFormat::Gltf, file, material, transform),
            ShapeFile::Instance { of } => self.add_instance_of(&of, material, transform),
            shape => {
                let (shape, blame) = self.analytic_shape(shape, span, material)?;
                self.add_shape(shape, blame, material, transform)?;
                Ok(Placed::Object(self.geometry.objects.len() - 1))
            }
        }
    }

    /// Adds a model file as an object of the scene.
    fn add_file(
        &mut self,
        format: ModelFormat,
        file: Spanned<String>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<Placed, SceneError> {
        self.add_model_file(format, &file, material, transform)?;
        let path = self.files.path(file.get_ref());
        Ok(Placed::File {
            path,
            file,
            material,
        })
    }

    /// The material (the object's own, else `inherited`) and the transform of an object.
    fn placement(
        &self,
        material: Option<Spanned<String>>,
        transform: Option<Spanned<Vec<TransformStepFile>>>,
        inherited: Option<u32>,
    ) -> Result<(Option<u32>, Option<Transform>), SceneError> {
        let material = material
            .map(|name| self.material_names.resolve(&name, self.source))
            .transpose()?
            .or(inherited);
        let transform = match transform {
            Some(steps) => build_transform(steps, self.source)?,
            None => None,
        };
        Ok((material, transform))
    }

    /// An analytic shape or a csg node, and the position to blame for what is wrong with it.
    /// `material` is what the children of a csg object take when they name none.
    fn analytic_shape(
        &mut self,
        shape: ShapeFile,
        span: Range<usize>,
        material: Option<u32>,
    ) -> Result<(Shape, Range<usize>), SceneError> {
        let source = self.source;
        let (shape, blame) = match (shape.analytic(span.clone()), shape) {
            (Some(analytic), _) => analytic,
            (
                None,
                ShapeFile::Csg {
                    operation,
                    children,
                },
            ) => (Ok(self.csg(operation, children, material, &span)?), span),
            (None, shape) => {
                let kind = match shape {
                    ShapeFile::Triangle { .. } => "triangle",
                    ShapeFile::Mesh { .. } => "mesh",
                    ShapeFile::Ply { .. } => "PLY mesh",
                    ShapeFile::Gltf { .. } => "glTF model",
                    ShapeFile::Instance { .. } => {
                        return Err(source.error(
                            span,
                            "an instance cannot be a csg operand: write the shape itself",
                        ));
                    }
                    _ => "OBJ mesh",
                };
                return Err(source.error(
                    span,
                    format!("the {kind} is an open surface; csg operands must be closed solids"),
                ));
            }
        };
        let shape = shape.map_err(|message| source.error(blame.clone(), message))?;
        Ok((shape, blame))
    }

    /// A csg object of `children`, which take `material` when they name none.
    fn csg(
        &mut self,
        operation: CsgOperationFile,
        children: Vec<Spanned<ObjectFile>>,
        material: Option<u32>,
        span: &Range<usize>,
    ) -> Result<Shape, SceneError> {
        let source = self.source;
        let mut operands = Vec::with_capacity(children.len());
        for child in children {
            let child_span = child.span();
            let child = child.into_inner();
            let (material, transform) =
                self.placement(child.material, child.transform, material)?;
            let shape_span = child.shape.span();
            let (shape, blame) =
                self.analytic_shape(child.shape.into_inner(), shape_span, material)?;
            if !shape.is_solid() {
                return Err(source.error(
                    child_span,
                    format!(
                        "the {} is an open surface; csg operands must be closed solids (a \
                         cylinder, cone or paraboloid needs `capped = true`)",
                        shape.name()
                    ),
                ));
            }
            self.check_bounds(&shape, transform, blame)?;
            operands.push(Operand {
                shape,
                transform,
                material: material.unwrap_or(DEFAULT_MATERIAL),
            });
        }
        let operation = match operation {
            CsgOperationFile::Union => CsgOperation::Union,
            CsgOperationFile::Intersection => CsgOperation::Intersection,
            CsgOperationFile::Difference => CsgOperation::Difference,
        };
        let csg =
            Csg::new(operation, operands).map_err(|message| source.error(span.clone(), message))?;
        Ok(Shape::Csg(Box::new(csg)))
    }

    /// Adds an analytic shape; the shape reaching past [`limits::MAX_COORDINATE`] is reported
    /// at `span`.
    pub(super) fn add_shape(
        &mut self,
        shape: Shape,
        span: Range<usize>,
        material: Option<u32>,
        transform: Option<Transform>,
    ) -> Result<(), SceneError> {
        self.check_bounds(&shape, transform, span)?;
        self.geometry.objects.push(Object {
            shape,
            transform: transform.map(Box::new),
            material: material.unwrap_or(DEFAULT_MATERIAL),
        });
        Ok(())
    }

    /// An error at `span` if the shape, placed by `transform`, reaches past
    /// [`limits::MAX_COORDINATE`].
    fn check_bounds(
        &self,
        shape: &Shape,
        transform: Option<Transform>,
        span: Range<usize>,
    ) -> Result<(), SceneError> {
        if let Some(bounds) = shape.bounds() {
            let bounds = transform.map_or(bounds, |t| t.bounds_to_world(&bounds));
            limits::check_bounds(&format!("the {}", shape.name()), &bounds)
                .map_err(|message| self.source.error(span, message))?;
        }
        Ok(())
    }

    /// Moves a mesh into the world, checks it and adds it.
    pub(super) fn add_mesh(
        &mut self,
        mut mesh: Mesh,
        material: u32,
        transform: Option<Transform>,
        spans: &MeshSpans,
    ) -> Result<(), SceneError> {
        mesh.material = material;
        if let Some(transform) = &transform {
            mesh.transform(transform);
        }
        mesh.validate()
            .map_err(|e| self.source.error(spans.of(&e), e.to_string()))?;
        self.geometry.add_mesh(mesh);
        Ok(())
    }
}
