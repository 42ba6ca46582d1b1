//! The objects on the GPU: one record per object (its shape's kind, where its shape's numbers
//! start in the shape words, its transform, its material) and the shape words themselves, four
//! floats each, which hold every shape's numbers and every transform. The WGSL that reads them
//! is `shaders/shapes/`: one file per shape, each the twin of its Rust module in `src/shapes`,
//! and `shape.wgsl`, which places a shape by its transform; the dispatch by kind is written
//! here, from [`ShapeKind`] ([`shapes_wgsl`]).

use super::record::gpu_record;
use strum::IntoEnumIterator;

use crate::primitive::Object;
use crate::shapes::{
    Csg, CsgStep, Cuboid, Ellipsoid, Paraboloid, Plane, Polygon, Shape, ShapeKind, Sphere,
    TaperedCylinder, Torus,
};
use crate::transform::Transform;

use super::wgsl_names::snake_case;

/// The WGSL of the objects and of each shape: one file per shape, `shapes/NAME.wgsl` with
/// `load_NAME`, `intersect_NAME` and `NAME_surface` (NAME the kind's snake-case name), and
/// CSG's.
const SHAPE_FILES: &str = concat!(
    include_str!("../../shaders/shapes/shape.wgsl"),
    include_str!("../../shaders/shapes/quadratic.wgsl"),
    include_str!("../../shaders/shapes/sphere.wgsl"),
    include_str!("../../shaders/shapes/plane.wgsl"),
    include_str!("../../shaders/shapes/polygon.wgsl"),
    include_str!("../../shaders/shapes/cuboid.wgsl"),
    include_str!("../../shaders/shapes/tapered_cylinder.wgsl"),
    include_str!("../../shaders/shapes/ellipsoid.wgsl"),
    include_str!("../../shaders/shapes/paraboloid.wgsl"),
    include_str!("../../shaders/shapes/torus.wgsl"),
    include_str!("../../shaders/shapes/csg.wgsl"),
);

/// How the WGSL finds where a line crosses a CSG operand of a kind, as [`Shape::crossings`]
/// does on the CPU.
enum OperandCrossings {
    /// By the shape's own `NAME_crossings`.
    Own,
    /// As a convex solid: two hits on the whole line ([`Shape::is_convex`]).
    Convex,
    /// Never an operand: `Csg::new` takes neither polygons nor nodes.
    None,
}

/// [`OperandCrossings`] of `kind`.
fn operand_crossings(kind: ShapeKind) -> OperandCrossings {
    match kind {
        ShapeKind::Plane | ShapeKind::Torus => OperandCrossings::Own,
        ShapeKind::Sphere
        | ShapeKind::Cuboid
        | ShapeKind::Ellipsoid
        | ShapeKind::TaperedCylinder
        | ShapeKind::Paraboloid => OperandCrossings::Convex,
        ShapeKind::Polygon | ShapeKind::Csg => OperandCrossings::None,
    }
}

/// The shapes' WGSL: each shape's file and the dispatch by kind, a case for every
/// [`ShapeKind`] but CSG (which `intersect_shape` traces, its operands through this). A kind
/// the WGSL does not trace sets `cut_short`, so that its sample is traced again on the CPU.
pub fn shapes_wgsl() -> String {
    let mut intersect = String::new();
    let mut surface = String::new();
    let (mut convex, mut own) = (Vec::new(), String::new());
    for kind in ShapeKind::iter().filter(|&kind| kind != ShapeKind::Csg) {
        let (name, constant) = (
            snake_case(&kind),
            format!("SHAPE_{}", snake_case(&kind).to_uppercase()),
        );
        let load = format!("load_{name}(first)");
        intersect += &format!(
            "        case {constant}: {{ return intersect_{name}({load}, origin, dir, t_min, t_max); }}\n"
        );
        surface +=
            &format!("        case {constant}: {{ return {name}_surface({load}, p, part); }}\n");
        match operand_crossings(kind) {
            OperandCrossings::Own => {
                own += &format!(
                    "        case {constant}: {{ return {name}_crossings({load}, origin, dir); }}\n"
                );
            }
            OperandCrossings::Convex => convex.push(constant),
            OperandCrossings::None => {}
        }
    }
    format!(
        "{SHAPE_FILES}
// `intersect_shape` for every shape but CSG, which traces its operands by this (WGSL has no
// recursion). Written by src/gpu/shapes.rs, a case for each `ShapeKind`.
fn intersect_plain_shape(kind: u32, first: u32, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {{
    switch kind {{
{intersect}        default: {{ cut_short = true; return no_hit(); }}
    }}
}}

// `shape_surface` for every shape but CSG.
fn plain_shape_surface(kind: u32, first: u32, p: vec3<f32>, part: u32) -> LocalSurface {{
    switch kind {{
{surface}        default: {{ cut_short = true; return LocalSurface(vec3<f32>(0.0, 0.0, 1.0), vec2<f32>(0.0)); }}
    }}
}}

// `Shape::crossings`, for a shape that is an operand of a CSG node.
fn shape_crossings(kind: u32, first: u32, origin: vec3<f32>, dir: vec3<f32>) -> Crossings {{
    switch kind {{
{own}        case {convex}: {{ return convex_crossings(kind, first, origin, dir); }}
        default: {{ cut_short = true; return Crossings(vec4<f32>(0.0), vec4<u32>(0u), 0u); }}
    }}
}}
",
        convex = convex.join(", ")
    )
}

gpu_record! {
    /// WGSL's `Object`: an analytic shape placed in the world.
    pub struct GpuObject {
        /// Which shape ([`ShapeKind`]).
        pub kind: u32,
        /// Where its numbers start in the shape words.
        pub first: u32,
        /// Where its transform starts in the shape words ([`NO_TRANSFORM`]: none).
        pub transform: u32,
        pub material: u32,
    }
}

/// [`GpuObject::transform`] of an object given in world coordinates.
pub const NO_TRANSFORM: u32 = u32::MAX;

/// The most solids one CSG object may combine on the GPU: fewer than the CPU's
/// [`crate::shapes::MAX_CSG_OPERANDS`], since every ray keeps two stacks of two spans per solid
/// (16 bytes each) in private memory: 2 KiB with this limit, 4 KiB with the CPU's. The WGSL's
/// `CSG_MAX_OPERANDS` is the same number.
pub const GPU_MAX_CSG_OPERANDS: usize = 32;

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
        Shape::Sphere(s) => push_sphere(s, words),
        Shape::Plane(p) => push_plane(p, words),
        Shape::Polygon(p) => push_polygon(p, words),
        Shape::Cuboid(c) => push_cuboid(c, words),
        Shape::TaperedCylinder(c) => push_tapered_cylinder(c, words),
        Shape::Ellipsoid(e) => push_ellipsoid(e, words),
        Shape::Paraboloid(p) => push_paraboloid(p, words),
        Shape::Torus(t) => push_torus(t, words),
        Shape::Csg(c) => push_csg(c, words)?,
    }
    Ok(ShapeKind::from(shape))
}

/// `load_sphere`: the centre and the radius.
fn push_sphere(s: &Sphere, words: &mut Vec<Word>) {
    words.push([s.center.x, s.center.y, s.center.z, s.radius]);
}

/// A flag of the shape words: 1 for true, 0 for false.
fn flag(b: bool) -> f32 {
    if b { 1.0 } else { 0.0 }
}

/// A whole number stored in a float of the shape words bit for bit, as WGSL's `bitcast<u32>`
/// reads it back.
fn bits(n: usize) -> f32 {
    f32::from_bits(n as u32)
}

/// `load_plane`: the point, then the normal.
fn push_plane(p: &Plane, words: &mut Vec<Word>) {
    words.push(p.point.extend(0.0).to_array());
    words.push(p.normal.extend(0.0).to_array());
}

/// `load_polygon`: a header of five words (the normal and the plane's offset; the projected
/// bounds; each texture axis with its end of `texture_min`; `texture_inv_extent` and the two
/// kept axes), then the edge bands: a word with `min_y`, `bands_per_y` and the numbers of bands
/// and of listed edges, the `starts` of the bands four to a word, and the listed edges one to a
/// word (`start`, `end_y`, `dx_dy`). Whole numbers are stored by [`bits`].
fn push_polygon(p: &Polygon, words: &mut Vec<Word>) {
    let (s, t) = p.texture_axes;
    words.push(p.normal.extend(p.plane_offset).to_array());
    words.push([
        p.projected_min.x,
        p.projected_min.y,
        p.projected_max.x,
        p.projected_max.y,
    ]);
    words.push(s.extend(p.texture_min.x).to_array());
    words.push(t.extend(p.texture_min.y).to_array());
    words.push([
        p.texture_inv_extent.x,
        p.texture_inv_extent.y,
        bits(p.kept_axes[0]),
        bits(p.kept_axes[1]),
    ]);
    let bands = &p.edges;
    words.push([
        bands.min_y,
        bands.bands_per_y,
        bits(bands.starts.len() - 1),
        bits(bands.edges.len()),
    ]);
    for chunk in bands.starts.chunks(4) {
        let mut word = [0.0; 4];
        for (w, &start) in word.iter_mut().zip(chunk) {
            *w = bits(start as usize);
        }
        words.push(word);
    }
    for edge in &bands.edges {
        words.push([edge.start.x, edge.start.y, edge.end_y, edge.dx_dy]);
    }
}

/// `load_cuboid`: the corners `min` and `max`.
fn push_cuboid(c: &Cuboid, words: &mut Vec<Word>) {
    let b = c.bounds();
    words.push(b.min.extend(0.0).to_array());
    words.push(b.max.extend(0.0).to_array());
}

/// `load_tapered_cylinder`: the base and the height, the frame's `x` and the base radius, its
/// `y` and the top radius, the axis and the slope, then whether it is capped.
fn push_tapered_cylinder(c: &TaperedCylinder, words: &mut Vec<Word>) {
    words.push(c.base.extend(c.height).to_array());
    words.push(c.frame_x.extend(c.base_radius).to_array());
    words.push(c.frame_y.extend(c.top_radius).to_array());
    words.push(c.axis.extend(c.slope).to_array());
    words.push([flag(c.is_capped()), 0.0, 0.0, 0.0]);
}

/// `load_ellipsoid`: the centre, then the reciprocals of the radii.
fn push_ellipsoid(e: &Ellipsoid, words: &mut Vec<Word>) {
    words.push(e.center.extend(0.0).to_array());
    words.push(e.inv_radii.extend(0.0).to_array());
}

/// `load_paraboloid`: the vertex and the radius, then the height, the curvature and whether it
/// is capped.
fn push_paraboloid(p: &Paraboloid, words: &mut Vec<Word>) {
    words.push(p.vertex.extend(p.radius).to_array());
    words.push([p.height, p.curvature, flag(p.is_capped()), 0.0]);
}

/// `load_torus`: the centre and the major radius, then the minor radius.
fn push_torus(t: &Torus, words: &mut Vec<Word>) {
    words.push([t.center.x, t.center.y, t.center.z, t.major_radius]);
    words.push([t.minor_radius, 0.0, 0.0, 0.0]);
}

/// `load_csg_leaf`'s flag on the kind of a leaf that is subtracted an odd number of times.
pub const CSG_COMPLEMENTED: u32 = 1 << 31;

/// The flag of a step of a CSG program that combines the two topmost lists (or-ed with the
/// operation); a step without it pushes the spans of the leaf it names.
pub const CSG_COMBINE: u32 = 1 << 31;

/// `intersect_csg`: a header (the numbers of leaves and of steps), a record per leaf (its
/// shape's kind, or-ed with [`CSG_COMPLEMENTED`] where it is subtracted an odd number of times;
/// where its numbers start; where its transform to the node's space starts, or
/// [`NO_TRANSFORM`]; its material), the steps of the program four to a word (a leaf's index, or
/// [`CSG_COMBINE`] or-ed with the operation), then each leaf's transform and numbers. Nodes of
/// more than [`GPU_MAX_CSG_OPERANDS`] solids are refused.
fn push_csg(csg: &Csg, words: &mut Vec<Word>) -> Result<(), String> {
    let leaves = csg.leaves();
    if leaves.len() > GPU_MAX_CSG_OPERANDS {
        return Err(format!(
            "a csg object of {} solids: the GPU tracer combines at most {GPU_MAX_CSG_OPERANDS} \
             (render it with --device cpu)",
            leaves.len()
        ));
    }
    let program = csg.program();
    let first = words.len();
    words.push([bits(leaves.len()), bits(program.len()), 0.0, 0.0]);
    words.resize(first + 1 + leaves.len(), [0.0; 4]);
    for chunk in program.chunks(4) {
        let mut word = [0.0; 4];
        for (w, step) in word.iter_mut().zip(chunk) {
            *w = f32::from_bits(match *step {
                CsgStep::Leaf(i) => u32::from(i),
                CsgStep::Combine(operation) => CSG_COMBINE | operation as u32,
            });
        }
        words.push(word);
    }
    for (index, leaf) in leaves.iter().enumerate() {
        let transform = match &leaf.transform {
            Some(t) => push_transform(t, words),
            None => NO_TRANSFORM,
        };
        let shape_first = words.len();
        let kind = push_shape(&leaf.shape, words)? as u32;
        let flags = if leaf.is_complemented() {
            CSG_COMPLEMENTED
        } else {
            0
        };
        words[first + 1 + index] = [
            f32::from_bits(kind | flags),
            bits(shape_first),
            f32::from_bits(transform),
            f32::from_bits(leaf.material),
        ];
    }
    Ok(())
}

impl ObjectTable {
    /// Appends a transform to the shape words (an instance's); returns where it starts.
    pub fn push_transform(&mut self, t: &Transform) -> u32 {
        push_transform(t, &mut self.words)
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{CsgOperation, Operand};

    fn sphere_operand(x: f32) -> Operand {
        Operand {
            shape: Shape::Sphere(Sphere::new(glam::Vec3::new(x, 0.0, 0.0), 1.0).unwrap()),
            transform: None,
            material: 0,
        }
    }

    #[test]
    fn csg_objects_of_more_solids_than_the_gpu_combines_are_refused_with_the_limit() {
        let within = (0..GPU_MAX_CSG_OPERANDS).map(|k| sphere_operand(k as f32));
        let csg = Csg::new(CsgOperation::Union, within.collect()).unwrap();
        assert!(push_shape(&Shape::Csg(Box::new(csg)), &mut Vec::new()).is_ok());
        let over = (0..=GPU_MAX_CSG_OPERANDS).map(|k| sphere_operand(k as f32));
        let csg = Csg::new(CsgOperation::Union, over.collect()).unwrap();
        let error = push_shape(&Shape::Csg(Box::new(csg)), &mut Vec::new()).unwrap_err();
        assert!(
            error.contains(&GPU_MAX_CSG_OPERANDS.to_string()) && error.contains("--device cpu"),
            "{error}"
        );
    }
}
