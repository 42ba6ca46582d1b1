//! The WGSL prelude: every number the GPU's Rust and its WGSL share, written once, in Rust.
//! Each shader module starts with [`prelude`], which writes them as WGSL `const`s:
//!
//! - the kinds of shapes, lights, textures, wraps, views, CSG operations and tone curves, and the bindings of
//!   every bind group, from their Rust enums: one constant a variant, numbered in order, so that
//!   a new variant reaches the WGSL with no edit here;
//! - the flags, limits and tunings, from the Rust constants that define them;
//! - the numbers that have no other home: the workgroup size, the bindings of the work and
//!   of the film, and the limits only the WGSL's loops have (its stacks).
//!
//! No file in `shaders/` types a number of its own; the test below checks it.

use std::fmt::{Debug, Write};

use strum::IntoEnumIterator;

use super::bvh::{
    INSTANCE_ENTRY, INSTANCE_LEAF, INSTANCE_WORDS, NO_INSTANCE, NO_MATERIAL, TRIANGLE_LEAF,
    WALK_STACK,
};
use super::caustics::MAX_PHOTON_TREE_DEPTH;
use super::frame::{
    BALL_BACKDROP, CAUSTICS, CUT_OUTS, OPAQUE, REFLECTIONS, SHADOWS, TEXTURES, TRANSMISSION,
    ViewKind,
};
use super::materials::{HAS_COLORS, HAS_NORMALS, HAS_UVS, MATERIAL_BITS};
use super::scene::SceneBinding;
use super::shapes::{CSG_COMBINE, CSG_COMPLEMENTED, GPU_MAX_CSG_OPERANDS, NO_TRANSFORM};
use super::texture::{NO_TEXTURE, WRAP_V_SHIFT};
use super::wgsl_names::snake_case;
use crate::bvh::WideNode;
use crate::color::BUCKET_SHIFT;
use crate::item_buffer::FAR_MARGIN;
use crate::light::LightKind;
use crate::medium::ISOTROPIC_PHASE;
use crate::photon_map::LEAF_SIZE;
use crate::primitive::PrimId;
use crate::settings::MAX_CAUSTIC_GATHER;
use crate::shapes::{
    CSG_PART_BITS, CsgOperation, MAX_CSG_DEPTH, Paraboloid, ShapeKind, TaperedCylinder,
};
use crate::texture::{MARBLE_TURBULENCE, TextureKind, WOOD_RING_WIDTH, WOOD_WOBBLE, Wrap};
use crate::tone::{CURVE_INPUT_MAX, ToneCurve};
use crate::whitted::{EYE_RAY_T_MIN, MAX_CUT_OUTS, RAY_BUDGET};

/// Invocations per workgroup of every compute entry point (`@workgroup_size(WORKGROUP)`).
pub const WORKGROUP: u32 = 64;

/// The bindings of bind group 1, the work of a dispatch or a draw: the list a dispatch reads
/// and the list it writes, and the item buffer's proxies and film size.
#[derive(Clone, Copy, Debug, PartialEq, Eq, strum::EnumIter)]
pub enum WorkBinding {
    Input,
    Output,
    Proxies,
    RasterFilm,
}

/// The kinds of the item buffer's proxies (`GpuProxy::kind` in `item_raster.rs`): an object's
/// box.
pub const PROXY_BOX: u32 = 0;
/// A proxy of the whole film, for an object without finite bounds.
pub const PROXY_FULL_FILM: u32 = 1;
/// An instance's box, whose fragments walk into the instance.
pub const PROXY_INSTANCE: u32 = 2;

/// The bindings of the film's module (`shaders/film.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, strum::EnumIter)]
pub enum FilmBinding {
    Samples,
    Colors,
    Pixels,
    Tally,
    Cut,
    FilmPass,
    Texels,
    SrgbTable,
    Show,
}

/// The most crossings of one object a shadow ray follows: a CSG node's solids, each crossed at
/// most four times (a torus).
pub const MAX_CROSSINGS: u32 = 4 * GPU_MAX_CSG_OPERANDS as u32;

/// Entries of the ray tree's explicit stack: the rays waiting to be traced.
pub const TREE_STACK: u32 = 64;

/// The item buffer's near clipping plane, as a share of the image plane's distance: a little
/// nearer than every eye ray's first point (`t` = [`EYE_RAY_T_MIN`]), so that no surface an eye
/// ray sees is clipped.
pub const NEAR_SHARE: f32 = 0.999;

/// `Within` in the WGSL's media: the fog between objects, or clear material inside an object
/// without a medium (else the index of the material whose medium fills the object).
pub const WITHIN_FOG: u32 = u32::MAX;
pub const WITHIN_CLEAR: u32 = u32::MAX - 1;

/// The searches of the BVH's walk: the closest hit, or whether anything blocks a shadow ray.
#[derive(Clone, Copy, Debug, strum::EnumIter)]
pub enum Find {
    Closest,
    Shadow,
}

/// A value as a WGSL constant holds it: its type and its expression.
pub trait WgslValue {
    fn wgsl(&self) -> (&'static str, String);
}

impl WgslValue for u32 {
    fn wgsl(&self) -> (&'static str, String) {
        ("u32", format!("{self}u"))
    }
}

impl WgslValue for usize {
    fn wgsl(&self) -> (&'static str, String) {
        u32::try_from(*self).expect("a count WGSL holds").wgsl()
    }
}

impl WgslValue for u64 {
    fn wgsl(&self) -> (&'static str, String) {
        u32::try_from(*self).expect("a count WGSL holds").wgsl()
    }
}

impl WgslValue for f32 {
    /// Rust's shortest text that reads back as the same `f32`, which WGSL reads alike.
    fn wgsl(&self) -> (&'static str, String) {
        assert!(self.is_finite(), "WGSL has no infinities");
        ("f32", format!("{self:?}"))
    }
}

impl WgslValue for (f32, f32) {
    fn wgsl(&self) -> (&'static str, String) {
        (
            "vec2<f32>",
            format!("vec2<f32>({:?}, {:?})", self.0, self.1),
        )
    }
}

impl WgslValue for (f32, f32, f32) {
    fn wgsl(&self) -> (&'static str, String) {
        let (x, y, z) = self;
        ("vec3<f32>", format!("vec3<f32>({x:?}, {y:?}, {z:?})"))
    }
}

/// Writes `const NAME: TYPE = VALUE;`.
fn constant(out: &mut String, name: &str, value: impl WgslValue) {
    let (ty, value) = value.wgsl();
    writeln!(out, "const {name}: {ty} = {value};").unwrap();
}

/// Writes a constant for each `NAME = value` (a bare `NAME` for a Rust constant of that name).
macro_rules! constants {
    ($out:expr; $($name:ident $(= $value:expr)?),+ $(,)?) => {
        $( constant($out, stringify!($name), constants!(@value $name $(, $value)?)); )+
    };
    (@value $name:ident) => { $name };
    (@value $name:ident, $value:expr) => { $value };
}

/// Writes `const PREFIX_VARIANT: u32 = n;` for each variant of `K`, numbered from 0 in order
/// (the number `variant as u32` gives a fieldless enum without explicit discriminants), the
/// variant's name in capitals: `ShapeKind::TaperedCylinder` is `SHAPE_TAPERED_CYLINDER`.
pub fn numbered<K: IntoEnumIterator + Debug>(out: &mut String, prefix: &str) {
    for (number, kind) in K::iter().enumerate() {
        let name = snake_case(&kind).to_uppercase();
        writeln!(out, "const {prefix}{name}: u32 = {number}u;").unwrap();
    }
}

/// The WGSL every shader module of the GPU tracer and its film starts with.
pub fn prelude() -> String {
    let mut out = String::from("// The numbers Rust and WGSL share: src/gpu/prelude.rs.\n");
    let o = &mut out;
    numbered::<ShapeKind>(o, "SHAPE_");
    numbered::<LightKind>(o, "LIGHT_");
    numbered::<TextureKind>(o, "TEXTURE_");
    numbered::<Wrap>(o, "WRAP_");
    numbered::<ViewKind>(o, "VIEW_");
    numbered::<CsgOperation>(o, "CSG_");
    numbered::<ToneCurve>(o, "CURVE_");
    numbered::<Find>(o, "FIND_");
    numbered::<SceneBinding>(o, "SCENE_");
    numbered::<WorkBinding>(o, "WORK_");
    numbered::<FilmBinding>(o, "FILM_");
    constants! { o;
        WORKGROUP,
        PI = std::f32::consts::PI,
        TAU = std::f32::consts::TAU,
        FLOAT_MAX = f32::MAX,
        F32_EPSILON = f32::EPSILON,
        PIXEL_CENTRE = crate::camera::PIXEL_CENTRE,
        // The scene's records.
        SHADOWS, REFLECTIONS, TRANSMISSION, OPAQUE, TEXTURES, BALL_BACKDROP, CAUSTICS, CUT_OUTS,
        NO_TRANSFORM, NO_TEXTURE, WRAP_V_SHIFT, HAS_COLORS, HAS_NORMALS, HAS_UVS, MATERIAL_BITS,
        // The shapes' parts and the CSG programs.
        TAPERED_SIDE = TaperedCylinder::SIDE,
        TAPERED_BASE_CAP = TaperedCylinder::BASE_CAP,
        TAPERED_TOP_CAP = TaperedCylinder::TOP_CAP,
        PARABOLOID_BOWL = Paraboloid::BOWL,
        PARABOLOID_CAP = Paraboloid::CAP,
        CSG_PART_BITS, CSG_COMPLEMENTED, CSG_COMBINE,
        CSG_MAX_OPERANDS = GPU_MAX_CSG_OPERANDS,
        CSG_MAX_SPANS = 2 * GPU_MAX_CSG_OPERANDS,
        CSG_MAX_LISTS = MAX_CSG_DEPTH + 2,
        // The BVH's walk.
        INTERIOR = WideNode::INTERIOR,
        TRIANGLE_LEAF, INSTANCE_LEAF, INSTANCE_WORDS, INSTANCE_ENTRY, NO_INSTANCE, NO_MATERIAL,
        OBJECT_BIT = PrimId::OBJECT_BIT,
        WALK_STACK, MAX_CROSSINGS,
        T_FAR = f32::MAX,
        // Textures, media and caustics.
        WOOD_RING_WIDTH, WOOD_WOBBLE, MARBLE_TURBULENCE,
        ISOTROPIC_PHASE, WITHIN_FOG, WITHIN_CLEAR,
        PHOTON_LEAF_SIZE = LEAF_SIZE,
        MAX_GATHER = MAX_CAUSTIC_GATHER,
        PHOTON_STACK = MAX_PHOTON_TREE_DEPTH,
        // The ray tree, the item buffer and the film.
        EYE_RAY_T_MIN, RAY_BUDGET, MAX_CUT_OUTS, TREE_STACK, FAR_MARGIN, NEAR_SHARE,
        PROXY_BOX, PROXY_FULL_FILM, PROXY_INSTANCE,
        SRGB_BUCKET_SHIFT = BUCKET_SHIFT,
        CURVE_INPUT_MAX,
    }
    out
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    /// `(file, line number, line)` of every line of the WGSL in `shaders/`.
    fn wgsl_lines() -> Vec<(String, usize, String)> {
        let mut lines = Vec::new();
        let mut folders = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders")];
        while let Some(folder) = folders.pop() {
            for entry in std::fs::read_dir(&folder).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    folders.push(path);
                } else if path.extension().is_some_and(|e| e == "wgsl") {
                    let text = std::fs::read_to_string(&path).unwrap();
                    let name = path.display().to_string();
                    for (i, line) in text.lines().enumerate() {
                        lines.push((name.clone(), i + 1, line.to_string()));
                    }
                }
            }
        }
        assert!(lines.len() > 1000, "{} lines of WGSL", lines.len());
        lines
    }

    /// Whether `text` holds a number written out (a digit not inside a name).
    fn has_number(text: &str) -> bool {
        let mut after_name = false;
        for ch in text.chars() {
            if ch.is_ascii_digit() && !after_name {
                return true;
            }
            after_name = ch.is_alphanumeric() || ch == '_';
        }
        false
    }

    /// The argument lists of attribute `@name(…)` in `line`.
    fn attribute_arguments<'a>(line: &'a str, name: &str) -> Vec<&'a str> {
        line.match_indices(&format!("@{name}("))
            .map(|(at, found)| {
                let rest = &line[at + found.len()..];
                &rest[..rest.find(')').unwrap_or(rest.len())]
            })
            .collect()
    }

    #[test]
    fn no_wgsl_file_types_a_number_the_prelude_holds() {
        let mut typed = Vec::new();
        for (file, number, line) in wgsl_lines() {
            let code = line.split("//").next().unwrap();
            let constant = code.trim_start().strip_prefix("const ").and_then(|rest| {
                let (_, value) = rest.split_once('=')?;
                Some(value)
            });
            // A constant table (corners of a quad or a box) is data, not a shared number.
            let hand_typed = constant.is_some_and(|v| has_number(v) && !v.contains("array"))
                || ["binding", "workgroup_size"]
                    .iter()
                    .flat_map(|name| attribute_arguments(code, name))
                    .any(has_number);
            if hand_typed {
                typed.push(format!("{file}:{number}: {}", line.trim()));
            }
        }
        assert!(
            typed.is_empty(),
            "numbers typed in the WGSL, which src/gpu/prelude.rs must hold:\n{}",
            typed.join("\n")
        );
    }

    #[test]
    fn the_check_finds_numbers_but_not_names() {
        assert!(has_number("2u * CSG_MAX_OPERANDS"));
        assert!(has_number(" 0.5;"));
        assert!(!has_number(" CSG_MAX_OPERANDS * VEC2;"));
        assert_eq!(
            attribute_arguments("@group(0) @binding(SCENE_OBJECTS) var", "binding"),
            ["SCENE_OBJECTS"]
        );
        assert_eq!(
            attribute_arguments("@workgroup_size(64)", "workgroup_size"),
            ["64"]
        );
    }

    #[test]
    fn each_kind_is_numbered_as_rust_numbers_it() {
        let prelude = prelude();
        for kind in ShapeKind::iter() {
            let name = snake_case(&kind).to_uppercase();
            let line = format!("const SHAPE_{name}: u32 = {}u;", kind as u32);
            assert!(prelude.contains(&line), "{line}");
        }
        assert!(prelude.contains("const SHAPE_TAPERED_CYLINDER: u32 = "));
        let line = format!("const TEXTURE_IMAGE: u32 = {}u;", TextureKind::Image as u32);
        assert!(prelude.contains(&line), "{line}");
        assert!(prelude.contains("const EYE_RAY_T_MIN: f32 = 1.0;"));
        assert!(prelude.contains("const FLOAT_MAX: f32 = 3.4028235e38;"));
    }
}
