//! Building a [`Scene`] from an [`NffDocument`] the way NFF means it: the `v` block becomes the
//! camera and the image size, `f` becomes a material whose `Ks` weighs both the Phong highlight
//! and the reflected ray and whose `T` weighs the refracted ray, `s`, `c` and `p` become
//! spheres, open cones and polygons, and the `pp` patches of each material one smooth-shaded
//! mesh. The ray tree is SPD's: depth 5, the eye ray counting as 1, no adaptive cut-off.

use std::collections::BTreeMap;

use glam::{DVec3, Vec3};

use super::document::{Fill, Item, NffDocument, PatchVertex, View};
use super::lighting::NffLighting;
use super::povray;
use crate::camera::{Camera, CameraSpec};
use crate::color::Color;
use crate::light::Light;
use crate::limits;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::settings::RenderSettings;
use crate::shapes::{Polygon, Shape, Sphere, TaperedCylinder};

/// SPD's deepest ray tree: the eye ray and four generations of reflected and refracted rays.
pub const SPD_MAX_DEPTH: u32 = 5;

/// Why a document cannot be built into a scene, and which part is at fault.
#[derive(Clone, Debug, PartialEq)]
pub struct BuildError {
    pub part: Part,
    pub message: String,
}

/// A part of an [`NffDocument`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The document as a whole.
    Document,
    View,
    /// The light at this index of [`NffDocument::lights`].
    Light(usize),
    /// The item at this index of [`NffDocument::items`].
    Item(usize),
}

impl std::fmt::Display for BuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.part {
            Part::Document => write!(f, "{}", self.message),
            Part::View => write!(f, "the view: {}", self.message),
            Part::Light(i) => write!(f, "light {i}: {}", self.message),
            Part::Item(i) => write!(f, "item {i}: {}", self.message),
        }
    }
}

impl std::error::Error for BuildError {}

impl NffDocument {
    /// The scene the document describes, its lights as bright as `lighting` says.
    pub fn to_scene(&self, lighting: NffLighting) -> Result<Scene, BuildError> {
        let view = self.view.as_ref().ok_or_else(|| BuildError {
            part: Part::Document,
            message: "the file has no view (`v`), so there is no camera".into(),
        })?;
        let view_error = |message| BuildError {
            part: Part::View,
            message,
        };
        let settings = RenderSettings {
            width: view.resolution[0],
            height: view.resolution[1],
            max_depth: SPD_MAX_DEPTH,
            min_weight: 0.0,
            background: self.background.map_or(Color::ZERO, DVec3::as_vec3),
            ambient: Color::splat(lighting.ambient(self.lights.len()) as f32),
            ..RenderSettings::default()
        };
        settings.validate().map_err(view_error)?;
        let spec = camera_spec(view).map_err(view_error)?;
        let camera = Camera::new(spec).map_err(|e| view_error(e.to_string()))?;
        let mut scene = Scene::new(settings, camera);

        let intensity = DVec3::splat(lighting.light_intensity(self.lights.len()));
        for (i, light) in self.lights.iter().enumerate() {
            let position =
                single(light.position, "light position").map_err(|message| BuildError {
                    part: Part::Light(i),
                    message,
                })?;
            scene.lights.push(Light::Point {
                position,
                color: light.color.unwrap_or(intensity).as_vec3(),
            });
        }

        let nff_name = |index: usize| format!("nff #{index}");
        let material_of = |fill: &Fill| match lighting {
            NffLighting::Readme => material(fill),
            NffLighting::Povray => povray::material(fill),
        };
        let mut material = scene.add_named_material(nff_name(0), material_of(&Fill::DEFAULT));
        let mut patches: BTreeMap<u32, Mesh> = BTreeMap::new();
        for (i, item) in self.items.iter().enumerate() {
            let at = |message| BuildError {
                part: Part::Item(i),
                message,
            };
            let shape = match item {
                Item::Fill(fill) => {
                    let name = nff_name(scene.materials.len());
                    material = scene.add_named_material(name, material_of(fill));
                    continue;
                }
                Item::Patch(vertices) => {
                    add_patch(patches.entry(material).or_default(), vertices).map_err(at)?;
                    continue;
                }
                Item::Sphere { center, radius } => sphere(*center, *radius),
                Item::Cone {
                    base,
                    base_radius,
                    apex,
                    apex_radius,
                } => cone(*base, *base_radius, *apex, *apex_radius),
                Item::Polygon(vertices) => polygon(vertices),
            };
            let shape = shape.map_err(at)?;
            if let Some(bounds) = shape.bounds() {
                limits::check_bounds(&format!("the {}", shape.name()), &bounds).map_err(at)?;
            }
            scene.add_object(shape, None, material);
        }
        for (material, mut mesh) in patches {
            mesh.material = material;
            scene.geometry.add_mesh(mesh);
        }
        Ok(scene)
    }
}

/// raylab's camera for a view. NFF's angle spans the image's width from edge to edge;
/// raylab's spans its height, so the two differ for images that are not square.
fn camera_spec(view: &View) -> Result<CameraSpec, String> {
    let [width, height] = view.resolution.map(f64::from);
    let half_width = (view.angle.to_radians() / 2.0).tan();
    let vertical = 2.0 * (half_width * height / width).atan();
    Ok(CameraSpec {
        eye: single(view.from, "eye position")?,
        look_at: single(view.at, "look-at point")?,
        up: single(view.up, "up vector")?,
        view_angle: vertical.to_degrees() as f32,
        near: near(view) as f32,
    })
}

/// The fraction of the way from the eye to the look-at point where the image plane goes for
/// `hither 0`: close enough to the eye to clip nothing a scene shows.
const NO_CLIPPING_NEAR: f64 = 1e-3;

/// raylab's near distance, where its eye rays start: `hither`, or for `hither 0` (no clipping)
/// close to the eye, as raylab's near distance must be positive. Since hither only clips, it is
/// moved into [`limits::NEAR_RANGE`] rather than refused (an eye at the look-at point is for the
/// camera to report).
fn near(view: &View) -> f64 {
    let near = if view.hither > 0.0 {
        view.hither
    } else {
        NO_CLIPPING_NEAR * view.from.distance(view.at)
    };
    near.clamp(
        f64::from(*limits::NEAR_RANGE.start()),
        f64::from(*limits::NEAR_RANGE.end()),
    )
}

/// The material of an `f`: `Ks` weighs the highlight and the reflected ray, `T` the refracted
/// ray, and the ambient light is reflected like diffuse light (`ka = Kd`).
fn material(fill: &Fill) -> Material {
    let transmits = fill.transmittance > 0.0;
    Material {
        color: fill.color.as_vec3(),
        texture: None,
        alpha_cutoff: None,
        emission: Color::ZERO,
        emission_texture: None,
        ambient: fill.kd as f32,
        diffuse: fill.kd as f32,
        specular: fill.ks as f32,
        specular_color: Color::ONE,
        shininess: fill.shine as f32,
        reflectivity: fill.ks as f32,
        reflection_color: Color::ONE,
        transparency: fill.transmittance as f32,
        // Opaque materials carry 0 or 1 here; only transmitters use it.
        ior: if transmits { fill.ior as f32 } else { 1.0 },
        fresnel: false,
        medium: None,
    }
}

/// A sphere. A negative radius asks for the inside only; raylab shows both sides.
fn sphere(center: DVec3, radius: f64) -> Result<Shape, String> {
    Sphere::new(single(center, "centre")?, radius.abs() as f32).map(Shape::Sphere)
}

/// A polygon, one-sided in NFF, seen from both sides in raylab.
fn polygon(vertices: &[DVec3]) -> Result<Shape, String> {
    let vertices = vertices
        .iter()
        .map(|&v| single(v, "vertex"))
        .collect::<Result<Vec<_>, _>>()?;
    Polygon::new(vertices).map(Shape::Polygon)
}

/// An open cone. The radii may come in either order; both negative means "inside only", which
/// raylab shows from both sides like every surface.
fn cone(base: DVec3, base_radius: f64, apex: DVec3, apex_radius: f64) -> Result<Shape, String> {
    let (base_radius, apex_radius) = if base_radius <= 0.0 && apex_radius <= 0.0 {
        (-base_radius, -apex_radius)
    } else if base_radius < 0.0 || apex_radius < 0.0 {
        return Err(format!(
            "cone radii must have the same sign, got {base_radius} and {apex_radius}"
        ));
    } else {
        (base_radius, apex_radius)
    };
    TaperedCylinder::new(
        single(base, "base")?,
        single(apex, "apex")?,
        base_radius as f32,
        apex_radius as f32,
        false,
    )
    .map(Shape::TaperedCylinder)
}

/// Adds a patch to its material's mesh, as a fan of triangles around its first vertex.
fn add_patch(mesh: &mut Mesh, vertices: &[PatchVertex]) -> Result<(), String> {
    if vertices.len() < 3 {
        return Err(format!(
            "a patch needs at least 3 vertices, got {}",
            vertices.len()
        ));
    }
    let too_many = || "too many patch vertices for one mesh".to_string();
    let first = u32::try_from(mesh.positions.len()).map_err(|_| too_many())?;
    let count = u32::try_from(vertices.len())
        .ok()
        .filter(|&count| first.checked_add(count).is_some())
        .ok_or_else(too_many)?;
    for v in vertices {
        mesh.positions.push(single(v.position, "vertex")?);
        mesh.normals.push(single(v.normal, "vertex normal")?);
    }
    mesh.faces
        .extend((1..count - 1).map(|k| [first, first + k, first + k + 1]));
    Ok(())
}

/// `v` in single precision, which raylab renders in, within ±[`limits::MAX_COORDINATE`];
/// `what` names it in the error.
fn single(v: DVec3, what: &str) -> Result<Vec3, String> {
    let single = v.as_vec3();
    if limits::within_range(single) {
        Ok(single)
    } else {
        Err(limits::out_of_range_message(&format!("the {what}"), single))
    }
}
