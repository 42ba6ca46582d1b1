//! glTF 2.0 models, `.gltf` (JSON with its buffers in files beside it or in `data:` URIs) and
//! `.glb` (binary): read with the `gltf` crate's schema and validation, every accessor read by
//! `buffers` after its ranges are checked. [`read_gltf`] gives the triangles of each mesh, the
//! default scene's placements of meshes, cameras and lights ([`geometry`]), the materials by
//! the rule in [`materials`], and the one-line report of what became what. Lights and camera
//! views are made from the placements by [`lights`] once the caller knows the model's centre.
//!
//! A required extension raylab cannot honour is refused by name; animations, skins and morph
//! targets are ignored (the rest pose is drawn) and the report says so.

mod buffers;
pub mod geometry;
pub mod lights;
pub mod materials;
pub mod textures;

use std::path::Path;

use crate::formats::{SceneError, SceneFiles};
use crate::material::Material;
use crate::mesh::Mesh;
use crate::texture::Texture;
use geometry::{Placements, placements, primitive_mesh};
use materials::{BLEND_CUTOFF, PbrValues, materials_report, whitted_material};

pub use geometry::NO_MATERIAL;

/// The extensions raylab reads; a file may require these and no others.
pub const HONOURED: [&str; 5] = [
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_transmission",
    "KHR_texture_transform",
];

/// The GLB header's magic, and its chunk types (little-endian `JSON` and `BIN\0`).
const GLB_MAGIC: &[u8; 4] = b"glTF";
const GLB_JSON: u32 = 0x4E4F_534A;
const GLB_BIN: u32 = 0x004E_4942;
/// The bytes of a GLB header, and of a chunk's length and type.
const GLB_HEADER: usize = 12;
const GLB_CHUNK_HEADER: usize = 8;

/// A glTF model as read: the geometry in model space and where the default scene places it.
pub struct GltfModel {
    pub document: gltf::Document,
    /// The triangle primitives of each glTF mesh the scene places (empty for one it does not),
    /// each's `material` the index into [`Self::materials`] or [`NO_MATERIAL`].
    pub meshes: Vec<Vec<Mesh>>,
    pub placements: Placements,
    /// The file's materials by the rule, with their glTF values and names; a material's
    /// `texture` and `emission_texture` are indices into [`Self::textures`].
    pub materials: Vec<Material>,
    pub pbr_values: Vec<PbrValues>,
    pub material_names: Vec<String>,
    /// The materials' base colour and emissive textures.
    pub textures: Vec<Texture>,
    /// What became what: `glTF: 3 materials → 1 mirror, 2 Phong; not used: KHR_materials_sheen (1)`.
    pub report: String,
}

/// Reads the glTF or GLB file at `path`, whose bytes are `bytes`; its buffers and images are
/// read through `files`, beside it. Errors are at `file:line:column` in the JSON (a GLB's JSON chunk too), at the
/// byte in a GLB's framing, or name the accessor, mesh or node they are about.
pub fn read_gltf(path: &Path, bytes: &[u8], files: SceneFiles) -> Result<GltfModel, SceneError> {
    let whole = |message: String| SceneError::whole_file(path, message);
    let (json, blob) = if bytes.starts_with(GLB_MAGIC) {
        glb_chunks(bytes).map_err(|(at, e)| SceneError::at_byte(path, at, e))?
    } else {
        (bytes, None)
    };
    let root: gltf::json::Root = gltf::json::deserialize::from_slice(json).map_err(|e| {
        let message = format!("not valid glTF JSON: {e}");
        let message = message.split(" at line ").next().unwrap_or_default();
        if blob.is_none() && !bytes.starts_with(GLB_MAGIC) {
            SceneError::at_line(path, json, e.line(), e.column(), message)
        } else {
            // A GLB's JSON chunk starts after the header and the chunk's own header.
            let line_start: usize = json
                .split(|&b| b == b'\n')
                .take(e.line().saturating_sub(1))
                .map(|l| l.len() + 1)
                .sum();
            let at = GLB_HEADER + GLB_CHUNK_HEADER + line_start + e.column().saturating_sub(1);
            SceneError::at_byte(path, at, format!("in the JSON chunk: {message}"))
        }
    })?;
    if let Some(refused) = root
        .extensions_required
        .iter()
        .find(|e| !HONOURED.contains(&e.as_str()))
    {
        return Err(whole(format!(
            "the file requires the extension {refused}, which raylab cannot honour (it reads {})",
            HONOURED.join(", ")
        )));
    }
    check_positions_indices(&root).map_err(whole)?;
    let document = gltf::Document::from_json(root).map_err(|e| whole(validation_message(e)))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let buffers = buffers::load_buffers(&document, blob, folder, files).map_err(whole)?;
    let placements = placements(&document).map_err(whole)?;
    let textured =
        textures::material_textures(&document, &buffers, folder, files).map_err(whole)?;
    let map_of = |primitive: &gltf::Primitive| {
        let material = primitive.material().index()?;
        textured.maps.get(material)?.as_ref()
    };

    let mut placed = vec![false; document.meshes().len()];
    for &(mesh, _) in &placements.meshes {
        placed[mesh] = true;
    }
    let mut meshes: Vec<Vec<Mesh>> = vec![Vec::new(); document.meshes().len()];
    for mesh in document.meshes() {
        if placed[mesh.index()] {
            meshes[mesh.index()] = mesh
                .primitives()
                .map(|p| primitive_mesh(&mesh, &p, &buffers, map_of(&p)))
                .collect::<Result<_, _>>()
                .map_err(whole)?;
        }
    }
    let pbr_values: Vec<PbrValues> = document.materials().map(|m| PbrValues::of(&m)).collect();
    let mut materials: Vec<Material> = pbr_values.iter().map(whitted_material).collect();
    for (k, material) in materials.iter_mut().enumerate() {
        material.texture = textured.base[k];
        material.emission_texture = textured.emissive[k];
    }
    let material_names = document
        .materials()
        .map(|m| match m.name() {
            Some(name) => name.to_string(),
            None => format!("#{}", m.index().unwrap_or_default()),
        })
        .collect();
    let report = report(&document, &materials);
    Ok(GltfModel {
        document,
        meshes,
        placements,
        materials,
        pbr_values,
        material_names,
        textures: textured.textures,
        report,
    })
}

/// A GLB file's JSON chunk and its binary chunk, if it has one.
type GlbChunks<'a> = (&'a [u8], Option<&'a [u8]>);

/// The chunks of a GLB file, or the byte at which its framing is wrong and what was expected.
fn glb_chunks(bytes: &[u8]) -> Result<GlbChunks<'_>, (usize, String)> {
    let word = |at: usize| -> Result<u32, (usize, String)> {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .ok_or((
                at,
                format!("the GLB ends at byte {}, inside its header", bytes.len()),
            ))
    };
    let version = word(4)?;
    if version != 2 {
        return Err((4, format!("GLB version {version}; raylab reads version 2")));
    }
    let length = word(8)? as usize;
    if length < GLB_HEADER + GLB_CHUNK_HEADER || length > bytes.len() {
        return Err((
            8,
            format!(
                "the header gives the file's length as {length} bytes; it has {}",
                bytes.len()
            ),
        ));
    }
    let bytes = &bytes[..length];
    let chunk = |at: usize, wanted: u32, name: &str| -> Result<&[u8], (usize, String)> {
        let size = word(at)? as usize;
        let kind = word(at + 4)?;
        if kind != wanted {
            return Err((
                at + 4,
                format!("expected the {name} chunk's type {wanted:#010x}, found {kind:#010x}"),
            ));
        }
        let start = at + GLB_CHUNK_HEADER;
        bytes.get(start..start + size).ok_or((
            at,
            format!(
                "the {name} chunk of {size} bytes reaches past the file's end at byte {length}"
            ),
        ))
    };
    let json = chunk(GLB_HEADER, GLB_JSON, "JSON")?;
    let next = GLB_HEADER + GLB_CHUNK_HEADER + json.len();
    let blob = if next + GLB_CHUNK_HEADER <= length {
        Some(chunk(next, GLB_BIN, "BIN")?)
    } else {
        None
    };
    Ok((json, blob))
}

/// The one check the crate's validation needs done first: each primitive's POSITION names an
/// accessor that exists (the validation reads it unchecked).
fn check_positions_indices(root: &gltf::json::Root) -> Result<(), String> {
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for index in primitive.attributes.values() {
                if index.value() >= root.accessors.len() {
                    return Err(format!(
                        "mesh {m} primitive {p}: an attribute names accessor {}, but the file \
                         has {} accessors",
                        index.value(),
                        root.accessors.len()
                    ));
                }
            }
        }
    }
    Ok(())
}

/// The crate's validation errors as one message: the first few, with the JSON path of each.
fn validation_message(error: gltf::Error) -> String {
    match error {
        gltf::Error::Validation(errors) => {
            const SHOWN: usize = 5;
            let mut lines: Vec<String> = errors
                .iter()
                .take(SHOWN)
                .map(|(path, e)| format!("  {path}: {e}"))
                .collect();
            if errors.len() > SHOWN {
                lines.push(format!("  and {} more", errors.len() - SHOWN));
            }
            format!("not valid glTF:\n{}", lines.join("\n"))
        }
        other => format!("not valid glTF: {other}"),
    }
}

/// The report: `glTF: 14 materials → 2 mirrors, 1 glass, 11 Phong; not used:
/// KHR_materials_clearcoat (3), KHR_materials_sheen (1); alphaMode BLEND (2) drawn as MASK at
/// 0.5; 2 animations ignored`. A count after an extension or BLEND is how many materials use it.
fn report(document: &gltf::Document, materials: &[Material]) -> String {
    let mut parts = vec![format!("glTF: {}", materials_report(materials))];
    let unused: Vec<String> = document
        .extensions_used()
        .filter(|e| !HONOURED.contains(e))
        .map(|e| {
            let users = document
                .materials()
                .filter(|m| m.extensions().is_some_and(|x| x.contains_key(e)))
                .count();
            if users > 0 {
                format!("{e} ({users})")
            } else {
                e.to_string()
            }
        })
        .collect();
    if !unused.is_empty() {
        parts.push(format!("not used: {}", unused.join(", ")));
    }
    let blended = document
        .materials()
        .filter(|m| m.alpha_mode() == gltf::material::AlphaMode::Blend)
        .count();
    if blended > 0 {
        parts.push(format!(
            "alphaMode BLEND ({blended}) drawn as MASK at {BLEND_CUTOFF}"
        ));
    }
    let morphed = document
        .meshes()
        .filter(|m| m.primitives().any(|p| p.morph_targets().next().is_some()))
        .count();
    let ignored: Vec<String> = [
        (document.animations().count(), "animation"),
        (document.skins().count(), "skin"),
        (morphed, "mesh with morph targets"),
    ]
    .into_iter()
    .filter(|&(n, _)| n > 0)
    .map(|(n, what)| {
        let what = if n == 1 {
            what.to_string()
        } else if let Some(rest) = what.strip_prefix("mesh") {
            format!("meshes{rest}")
        } else {
            format!("{what}s")
        };
        format!("{n} {what}")
    })
    .collect();
    if !ignored.is_empty() {
        parts.push(format!(
            "{} ignored (the rest pose is drawn)",
            ignored.join(", ")
        ));
    }
    parts.join("; ")
}
