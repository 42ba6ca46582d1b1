//! The objects of a scene file (`[[objects]]`): each one's placement, and its shape by its
//! `type`, with how the keys of an analytic shape become a [`Shape`]. Adding a shape to the
//! format is a variant of [`ShapeFile`] and its arm in [`ShapeFile::analytic`].

use std::ops::Range;

use glam::Vec3;
use serde::Deserialize;
use toml::Spanned;

use super::values::{Direction, Exact, Finite, ScaleFactors, TexCoord, Vector};
use crate::shapes::{
    Cuboid, Ellipsoid, Paraboloid, Plane, Polygon, Shape, Sphere, TaperedCylinder, Torus,
};

/// `[[objects]]`: a shape with a material and a placement.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectFile {
    /// The object's own name, for instances to place it again (`of = "NAME"`).
    pub name: Option<Spanned<String>>,
    /// A name from `[materials]`; the default material when absent.
    pub material: Option<Spanned<String>>,
    /// Steps applied in file order.
    pub transform: Option<Spanned<Vec<TransformStepFile>>>,
    /// Every other key of the object's table, tagged with its `type` (see [`super::retag`]).
    pub shape: Spanned<ShapeFile>,
}

/// The keys of [`ObjectFile`] that the file writes next to the shape's own keys.
pub const OBJECT_KEYS: [&str; 3] = ["name", "material", "transform"];

/// One step of `transform = [ … ]`.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TransformStepFile {
    Translate(Vector),
    Rotate { axis: Direction, degrees: Finite },
    Scale(ScaleFactors),
}

/// The shape of an object, by its `type`.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeFile {
    Sphere {
        center: Option<Vector>,
        radius: Option<Spanned<f32>>,
    },
    Plane {
        point: Option<Vector>,
        /// Towards the plane's front.
        normal: Option<Direction>,
    },
    Triangle {
        vertices: Spanned<Exact<Vector, 3>>,
        normals: Option<Exact<Direction, 3>>,
        uvs: Option<Exact<TexCoord, 3>>,
    },
    /// A mesh written out in the file.
    Mesh {
        positions: Vec<Vector>,
        /// Vertex indices, counted from 0.
        faces: Spanned<Vec<Exact<u32, 3>>>,
        normals: Option<Spanned<Vec<Direction>>>,
        uvs: Option<Spanned<Vec<TexCoord>>>,
    },
    /// A Wavefront OBJ file, relative to the scene file's folder.
    Obj { file: Spanned<String> },
    /// A PLY file (the Stanford format), relative to the scene file's folder.
    Ply { file: Spanned<String> },
    /// A glTF 2.0 model (`.gltf` or `.glb`), relative to the scene file's folder: its default
    /// scene's meshes where its nodes place them, in its own materials unless the object names
    /// one.
    Gltf { file: Spanned<String> },
    /// The object named `of` (above this one) placed again, by this object's own transform
    /// instead of that one's, in this object's material if it names one: a model file or a
    /// mesh placed again shares its triangles with the first.
    Instance { of: Spanned<String> },
    /// A planar polygon, convex or concave, counter-clockwise seen from its front.
    Polygon { vertices: Vec<Vector> },
    /// An axis-aligned box (turn it with a transform).
    Box { min: Vector, max: Vector },
    /// A cylinder from `base` to `top`.
    Cylinder {
        base: Option<Vector>,
        top: Option<Vector>,
        radius: Option<f32>,
        capped: Option<bool>,
    },
    /// A cone, or a truncated cone when both radii are positive.
    Cone {
        base: Option<Vector>,
        top: Option<Vector>,
        base_radius: Option<f32>,
        top_radius: Option<f32>,
        capped: Option<bool>,
    },
    Ellipsoid {
        center: Option<Vector>,
        radii: Vector,
    },
    /// A paraboloid opening towards +y from `vertex`, `radius` wide at `height`.
    Paraboloid {
        vertex: Option<Vector>,
        radius: Option<f32>,
        height: Option<f32>,
        capped: Option<bool>,
    },
    /// A torus around the y axis through `center`: a tube of radius `minor_radius` swept
    /// around a ring of radius `major_radius`.
    Torus {
        center: Option<Vector>,
        major_radius: f32,
        minor_radius: f32,
    },
    /// A boolean object: closed solids and other csg objects combined by `operation`. Children
    /// without a `material` take the node's.
    Csg {
        operation: CsgOperationFile,
        children: Vec<Spanned<ObjectFile>>,
    },
}

/// `operation = "union" | "intersection" | "difference"` (the first child minus the others).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CsgOperationFile {
    Union,
    Intersection,
    Difference,
}

impl ShapeFile {
    /// The analytic shape the keys describe (the result of its constructor) and the position
    /// to blame for what is wrong with it (`span`, the table's, or a key's); `None` for what
    /// the builder makes: csg nodes, triangles, meshes and model files.
    pub fn analytic(&self, span: Range<usize>) -> Option<(Result<Shape, String>, Range<usize>)> {
        Some(match self {
            ShapeFile::Sphere { center, radius } => {
                let radius_span = radius.as_ref().map_or(span.clone(), |r| r.span());
                let center = center.map_or(Vec3::ZERO, |c| c.0);
                let radius = radius.as_ref().map_or(1.0, |r| *r.get_ref());
                let shape = Sphere::new(center, radius).map(Shape::Sphere);
                (shape, radius_span)
            }
            ShapeFile::Plane { point, normal } => {
                let plane = Plane {
                    point: point.map_or(Vec3::ZERO, |p| p.0),
                    normal: normal.map_or(Vec3::Y, |n| n.0),
                };
                (Ok(Shape::Plane(plane)), span)
            }
            ShapeFile::Polygon { vertices } => {
                let vertices = vertices.iter().map(|v| v.0).collect();
                let shape = Polygon::new(vertices).map(Shape::Polygon);
                (shape, span)
            }
            ShapeFile::Box { min, max } => {
                let shape = Cuboid::new(min.0, max.0).map(Shape::Cuboid);
                (shape, span)
            }
            ShapeFile::Cylinder {
                base,
                top,
                radius,
                capped,
            } => {
                let radius = radius.unwrap_or(1.0);
                let shape = TaperedCylinder::new(
                    base.map_or(Vec3::ZERO, |v| v.0),
                    top.map_or(Vec3::Y, |v| v.0),
                    radius,
                    radius,
                    capped.unwrap_or(true),
                );
                (shape.map(Shape::TaperedCylinder), span)
            }
            ShapeFile::Cone {
                base,
                top,
                base_radius,
                top_radius,
                capped,
            } => {
                let shape = TaperedCylinder::new(
                    base.map_or(Vec3::ZERO, |v| v.0),
                    top.map_or(Vec3::Y, |v| v.0),
                    base_radius.unwrap_or(1.0),
                    top_radius.unwrap_or(0.0),
                    capped.unwrap_or(true),
                );
                (shape.map(Shape::TaperedCylinder), span)
            }
            ShapeFile::Ellipsoid { center, radii } => {
                let shape = Ellipsoid::new(center.map_or(Vec3::ZERO, |v| v.0), radii.0);
                (shape.map(Shape::Ellipsoid), span)
            }
            ShapeFile::Paraboloid {
                vertex,
                radius,
                height,
                capped,
            } => {
                let shape = Paraboloid::new(
                    vertex.map_or(Vec3::ZERO, |v| v.0),
                    radius.unwrap_or(1.0),
                    height.unwrap_or(1.0),
                    capped.unwrap_or(false),
                );
                (shape.map(Shape::Paraboloid), span)
            }
            ShapeFile::Torus {
                center,
                major_radius,
                minor_radius,
            } => {
                let center = center.map_or(Vec3::ZERO, |c| c.0);
                let shape = Torus::new(center, *major_radius, *minor_radius);
                (shape.map(Shape::Torus), span)
            }
            ShapeFile::Csg { .. }
            | ShapeFile::Triangle { .. }
            | ShapeFile::Mesh { .. }
            | ShapeFile::Obj { .. }
            | ShapeFile::Ply { .. }
            | ShapeFile::Gltf { .. }
            | ShapeFile::Instance { .. } => return None,
        })
    }
}
