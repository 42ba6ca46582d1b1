//! The objects on the GPU: one record per object (its shape's kind, where its shape's numbers
//! start in the shape words, its transform, its material) and the shape words themselves, four
//! floats each, which hold every shape's numbers and every transform. The WGSL that reads them
//! is `shaders/shapes/`: one file per shape, each the twin of its Rust module in `src/shapes`,
//! and `shape.wgsl`, which picks the shape by its kind and places it by its transform.

use bytemuck::{Pod, Zeroable};

use crate::primitive::Object;
use crate::shapes::{Shape, Sphere, Torus};
use crate::transform::Transform;

/// The shapes' WGSL: the dispatch by kind and each shape's intersection and surface.
pub const SHAPES_WGSL: &str = concat!(
    include_str!("../../shaders/shapes/shape.wgsl"),
    include_str!("../../shaders/shapes/sphere.wgsl"),
    include_str!("../../shaders/shapes/torus.wgsl"),
);

/// WGSL's `Object`: an analytic shape placed in the world.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GpuObject {
    /// Which shape ([`ShapeKind`]).
    pub kind: u32,
    /// Where its numbers start in the shape words.
    pub first: u32,
    /// Where its transform starts in the shape words ([`NO_TRANSFORM`]: none).
    pub transform: u32,
    pub material: u32,
}

/// [`GpuObject::transform`] of an object given in world coordinates.
pub const NO_TRANSFORM: u32 = u32::MAX;

/// The shape kinds, numbered as the `SHAPE_*` constants of `shaders/shapes/shape.wgsl`. The
/// numbers only need to be distinct; they are not counts or indices.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShapeKind {
    Sphere = 0,
    Torus = 100,
}

/// Four floats of the shape words.
pub type Word = [f32; 4];

/// The objects of a scene as the GPU reads them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjectTable {
    pub objects: Vec<GpuObject>,
    pub words: Vec<Word>,
}

impl ObjectTable {
    /// The records and words of `objects`, in their order; the error names an object whose
    /// shape the GPU does not trace.
    pub fn new(objects: &[Object]) -> Result<ObjectTable, String> {
        let mut table = ObjectTable::default();
        for (index, object) in objects.iter().enumerate() {
            let transform = match &object.transform {
                Some(t) => push_transform(t, &mut table.words),
                None => NO_TRANSFORM,
            };
            let first = table.words.len() as u32;
            let kind = push_shape(&object.shape, &mut table.words)
                .map_err(|e| format!("object #{index}: {e}"))?;
            table.objects.push(GpuObject {
                kind: kind as u32,
                first,
                transform,
                material: object.material,
            });
        }
        Ok(table)
    }
}

/// Appends the numbers of `shape` to `words`, in the order its WGSL `load_*` reads them.
fn push_shape(shape: &Shape, words: &mut Vec<Word>) -> Result<ShapeKind, String> {
    match shape {
        Shape::Sphere(s) => {
            push_sphere(s, words);
            Ok(ShapeKind::Sphere)
        }
        Shape::Torus(t) => {
            push_torus(t, words);
            Ok(ShapeKind::Torus)
        }
        other => Err(format!(
            "the GPU tracer has no {} yet (render it with --device cpu)",
            other.name()
        )),
    }
}

/// `load_sphere`: the centre and the radius.
fn push_sphere(s: &Sphere, words: &mut Vec<Word>) {
    words.push([s.center.x, s.center.y, s.center.z, s.radius]);
}

/// `load_torus`: the centre and the major radius, then the minor radius.
fn push_torus(t: &Torus, words: &mut Vec<Word>) {
    words.push([t.center.x, t.center.y, t.center.z, t.major_radius]);
    words.push([t.minor_radius, 0.0, 0.0, 0.0]);
}

/// Appends a transform as `load_transform` reads it: the columns of `object_from_world` (three
/// axes, then the translation), then those of `normal_to_world`. Returns where it starts.
fn push_transform(t: &Transform, words: &mut Vec<Word>) -> u32 {
    let first = words.len() as u32;
    let m = t.object_from_world;
    for column in [
        m.matrix3.x_axis,
        m.matrix3.y_axis,
        m.matrix3.z_axis,
        m.translation,
    ] {
        words.push(column.extend(0.0).to_array());
    }
    let n = t.normal_to_world;
    for column in [n.x_axis, n.y_axis, n.z_axis] {
        words.push(column.extend(0.0).to_array());
    }
    first
}
