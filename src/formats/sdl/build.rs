//! The state the book's parser keeps while it reads, and the scene it builds: the current
//! material (which `push`/`pop` do not save), the stack of current transforms, the pixmaps,
//! and the objects, each placed by the transform on top of the stack and given the current
//! material (and its texture) when it is made.

use std::collections::HashMap;
use std::f32::consts::{PI, TAU};
use std::sync::Arc;

use glam::{Affine3A, Vec2};

use crate::camera::{Camera, CameraSpec};
use crate::color::Color;
use crate::limits;
use crate::material::Material;
use crate::memory;
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::settings::RenderSettings;
use crate::shapes::{Csg, CsgOperation, Operand, Shape};
use crate::srgb_image::SrgbImage;
use crate::texture::{Texture, WOOD_COLORS, Wrap};
use crate::transform::{Transform, TransformStep};

/// How many pixmaps `makePixmap` can fill (numbers 0 to 15), as in the book's ray tracer.
pub const PIXMAPS: usize = 16;

/// The book's checkerboard: cubes of side ½, the diffuse colour at 20% and 80%.
const CHECKER_SIZE: f32 = 0.5;
const CHECKER_SHADES: (f32, f32) = (0.2, 0.8);

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
    pub emissive: Color,
    pub ambient: Color,
    pub diffuse: Color,
    pub specular: Color,
    pub specular_exponent: f32,
    pub reflectivity: f32,
    pub transparency: f32,
    /// The speed of light in the material, relative to its speed outside.
    pub speed_of_light: f32,
    /// `texture`: 0 none, −1 checkerboard, −2 wood, −3 marble, n > 0 pixmap n.
    pub texture: i32,
    /// `parameters`: for a pixmap on a square or a tapered cylinder, the ranges of the shape
    /// that the image spans.
    pub parameters: Vec<f32>,
}

impl Default for SdlMaterial {
    fn default() -> Self {
        SdlMaterial {
            emissive: Color::ZERO,
            ambient: Color::splat(0.1),
            diffuse: Color::splat(0.8),
            specular: Color::ZERO,
            specular_exponent: 1.0,
            reflectivity: 0.0,
            transparency: 0.0,
            speed_of_light: 1.0,
            texture: 0,
            parameters: Vec::new(),
        }
    }
}

impl SdlMaterial {
    /// raylab's nearest material. raylab's surface has one colour that its ambient and diffuse
    /// coefficients scale: the diffuse colour, with `ka` the ambient colour's mean over the
    /// diffuse colour's mean. The specular colour becomes the highlight's colour, its largest
    /// component `ks`; the index of refraction is the inverse of the speed of light.
    fn to_material(&self) -> Material {
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
            alpha_cutoff: None,
            emission: self.emissive,
            emission_texture: None,
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
            reflection_color: Color::ONE,
            transparency: self.transparency,
            ior: 1.0 / self.speed_of_light,
            fresnel: false,
            medium: None,
        }
    }
}

/// The scene being built, and the reader's state.
#[derive(Debug)]
pub(crate) struct Builder {
    pub scene: Scene,
    pub material: SdlMaterial,
    /// The images `makePixmap` read, by number.
    pub pixmaps: [Option<Arc<SrgbImage>>; PIXMAPS],
    /// The last material given to the scene, the mapping of its texture, and its index, shared
    /// by the shapes that follow while the material and the mapping stay the same.
    added: Option<(SdlMaterial, Mapping, u32)>,
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
            pixmaps: Default::default(),
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

    /// The index in the scene of the current material, its texture laid on as `mapping` says.
    fn material_index(&mut self, mapping: Mapping) -> Result<u32, String> {
        if let Some((material, m, index)) = &self.added
            && *material == self.material
            && *m == mapping
        {
            return Ok(*index);
        }
        let mut material = self.material.to_material();
        if let Some(texture) = self.texture(mapping)? {
            material.texture = Some(self.scene.textures.len() as u32);
            self.scene.textures.push(texture);
        }
        let index = self.scene.add_material(material);
        self.added = Some((self.material.clone(), mapping, index));
        Ok(index)
    }

    /// Whether the current material names a pixmap that `makePixmap` has not filled.
    pub fn pixmap_missing(&self) -> bool {
        let n = self.material.texture;
        n > 0 && self.pixmaps.get(n as usize).is_none_or(Option::is_none)
    }

    /// The current material's texture, as the book's ray tracer shades it: the checkerboard
    /// and the marble shade the diffuse colour, the wood replaces it, a pixmap lies on the
    /// shape as `mapping` says. Unknown numbers and empty pixmaps give none.
    fn texture(&self, mapping: Mapping) -> Result<Option<Texture>, String> {
        let diffuse = self.material.diffuse;
        Ok(match self.material.texture {
            -1 => Some(Texture::Checker3d {
                a: diffuse * CHECKER_SHADES.0,
                b: diffuse * CHECKER_SHADES.1,
                size: CHECKER_SIZE,
            }),
            -2 => Some(Texture::Wood {
                a: WOOD_COLORS.0,
                b: WOOD_COLORS.1,
            }),
            -3 => Some(Texture::Marble { color: diffuse }),
            n if n > 0 => match self.pixmaps.get(n as usize).and_then(Option::as_ref) {
                Some(image) => {
                    let (scale, offset) = pixmap_mapping(mapping, &self.material.parameters)?;
                    Some(Texture::Image {
                        image: image.clone(),
                        wrap: [Wrap::Repeat; 2],
                        scale,
                        offset,
                    })
                }
                None => None,
            },
            _ => None,
        })
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
        let material = self.material_index(Mapping::of(&shape))?;
        self.scene.add_object(shape, Some(transform), material);
        Ok(())
    }

    /// Adds a solid with a hole taken out of it (the tapered tube), both in its object space,
    /// placed and coloured as [`Self::shape`] does.
    pub fn hollow(&mut self, solid: Shape, hole: Shape) -> Result<(), String> {
        let material = self.material_index(Mapping::Own)?;
        let operand = |shape| Operand {
            shape,
            transform: None,
            material,
        };
        let operands = vec![operand(solid), operand(hole)];
        let csg = Csg::new(CsgOperation::Difference, operands)?;
        self.shape(Shape::Csg(Box::new(csg)))
    }

    /// Adds a boolean object. As in the book, the node has no transform or material of its own:
    /// each operand keeps the ones in force when it was read.
    pub fn boolean(&mut self, csg: Csg) -> Result<(), String> {
        let shape = Shape::Csg(Box::new(csg));
        if let Some(bounds) = shape.bounds() {
            limits::check_bounds("the boolean object", &bounds)?;
        }
        let material = self.material_index(Mapping::Own)?;
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
        mesh.material = self.material_index(Mapping::Own)?;
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

/// How a pixmap lies on a shape. The book maps it by the material's `parameters` on a square
/// (the image spans x from p0 to p3 and y from p1 to p2) and on a tapered cylinder (the angle
/// around z from p0 to p1, in radians, and z from p2 to p3); other shapes use their own
/// texture coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mapping {
    Square,
    TaperedCylinder,
    Own,
}

impl Mapping {
    fn of(shape: &Shape) -> Mapping {
        match shape {
            // The only polygon SDL makes is the square.
            Shape::Polygon(_) => Mapping::Square,
            Shape::TaperedCylinder(_) => Mapping::TaperedCylinder,
            _ => Mapping::Own,
        }
    }
}

/// The `scale` and `offset` of an image texture that lays the pixmap as `mapping` and the
/// `parameters` say, from the shape's own texture coordinates: on the square, u = (x + 1)/2
/// and v = (y + 1)/2; on the cylinder's side, u = ½ + angle/2π and v = z.
fn pixmap_mapping(mapping: Mapping, parameters: &[f32]) -> Result<(Vec2, Vec2), String> {
    let &[p0, p1, p2, p3, ..] = parameters else {
        return Ok((Vec2::ONE, Vec2::ZERO));
    };
    // A coordinate `c = k·t + c0` of the shape (t its own u or v) mapped from [from, to] onto
    // [0, 1]: (c − from)/(to − from).
    let range = |k: f32, c0: f32, from: f32, to: f32| -> Result<(f32, f32), String> {
        let (scale, offset) = (k / (to - from), (c0 - from) / (to - from));
        if scale.is_finite() && offset.is_finite() {
            Ok((scale, offset))
        } else {
            Err(format!(
                "the `parameters` of this pixmap give the empty range {from} to {to}"
            ))
        }
    };
    let (u, v) = match mapping {
        Mapping::Square => (range(2.0, -1.0, p0, p3)?, range(2.0, -1.0, p1, p2)?),
        Mapping::TaperedCylinder => (range(TAU, -PI, p0, p1)?, range(1.0, 0.0, p2, p3)?),
        Mapping::Own => return Ok((Vec2::ONE, Vec2::ZERO)),
    };
    Ok((Vec2::new(u.0, v.0), Vec2::new(u.1, v.1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Where `mapping` with `parameters` takes the shape's own texture coordinates `uv`.
    fn mapped(mapping: Mapping, parameters: &[f32], uv: Vec2) -> Vec2 {
        let (scale, offset) = pixmap_mapping(mapping, parameters).unwrap();
        uv * scale + offset
    }

    #[test]
    fn on_a_square_the_image_spans_x_from_p0_to_p3_and_y_from_p1_to_p2() {
        let p = [-0.5, 0.0, 1.0, 1.5];
        // The square's point (x, y) has u = (x + 1)/2, v = (y + 1)/2.
        for (x, y) in [(-0.5, 0.0), (1.5, 1.0), (0.5, 0.25), (-1.0, -1.0)] {
            let uv = Vec2::new((x + 1.0) / 2.0, (y + 1.0) / 2.0);
            let expected = Vec2::new((x + 0.5) / 2.0, y / 1.0);
            assert!(mapped(Mapping::Square, &p, uv).abs_diff_eq(expected, 1e-6));
        }
    }

    #[test]
    fn on_a_tapered_cylinder_the_image_spans_an_angle_and_a_height() {
        let p = [0.0, PI, 0.25, 0.75];
        // The side's point at angle θ (−π to π) and height z has u = ½ + θ/2π, v = z.
        for (angle, z) in [
            (0.0f32, 0.25f32),
            (PI, 0.75),
            (PI / 2.0, 0.5),
            (-PI / 2.0, 1.0),
        ] {
            let uv = Vec2::new(0.5 + angle / TAU, z);
            let expected = Vec2::new(angle / PI, (z - 0.25) / 0.5);
            let got = mapped(Mapping::TaperedCylinder, &p, uv);
            assert!(got.abs_diff_eq(expected, 1e-6), "{got} {expected}");
        }
    }

    #[test]
    fn without_four_parameters_or_on_other_shapes_the_shapes_own_coordinates_serve() {
        let uv = Vec2::new(0.3, 0.7);
        assert_eq!(mapped(Mapping::Square, &[1.0, 2.0], uv), uv);
        assert_eq!(mapped(Mapping::Own, &[0.0, 1.0, 2.0, 3.0], uv), uv);
    }
}
