//! Wavefront OBJ files (and the MTL materials they name, with their `map_Kd` images), read with
//! tobj into raylab meshes in the OBJ's own coordinates. A first look at the lines finds what
//! tobj would reject without saying where (a face index that is not a number) and what it would
//! drop or guess silently (a face of one or two vertices, an MTL file it cannot read, a material
//! no MTL file defines), so that these become errors and warnings at their line.

use std::cell::RefCell;
use std::collections::{BTreeSet, HashMap};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::error::{SceneError, Source};
use super::files::{SceneFiles, ascii_text};
use super::sniff::{known_format, not_the_format};
use crate::color::Color;
use crate::material::Material;
use crate::mesh::Mesh;
use crate::srgb_image::SrgbImage;
use crate::texture::{Texture, Wrap};

/// What an OBJ file holds.
#[derive(Debug)]
pub struct ObjContents {
    /// One part per OBJ object or group.
    pub parts: Vec<ObjPart>,
    /// The MTL materials, or why they could not be loaded; a material's `texture` is an index
    /// into `textures`.
    pub materials: Result<Vec<Material>, String>,
    /// The images the MTL materials' `map_Kd` name, each once.
    pub textures: Vec<Texture>,
    /// What was accepted but is worth hearing about, as `file:line: message`, in line order.
    pub warnings: Vec<String>,
}

/// One object or group of an OBJ file: a mesh (its `material` field not yet set) and the MTL
/// material it uses, if any.
#[derive(Debug)]
pub struct ObjPart {
    pub mesh: Mesh,
    /// Index into [`ObjContents::materials`].
    pub mtl_material: Option<usize>,
}

/// Why an OBJ file cannot be loaded.
#[derive(Debug)]
pub enum ObjError {
    /// A mistake at a line and column of the OBJ file.
    At(SceneError),
    /// The file as a whole: it cannot be read, or tobj rejects it.
    Whole(String),
}

/// Reads an OBJ file, triangulated, with one index per vertex for position, normal and texture
/// coordinates. MTL files are looked up next to the OBJ file. OBJ is ASCII: a comment may hold
/// any byte, and a byte-order mark or a DOS end-of-file mark (^Z) is skipped. The warnings are
/// about faces left out, and if `uses_mtl` (the object takes its materials from the MTL files)
/// about MTL files that cannot be read and materials that no MTL file defines.
pub fn load_obj(path: &Path, files: SceneFiles, uses_mtl: bool) -> Result<ObjContents, ObjError> {
    let bytes = files.read(path).map_err(ObjError::Whole)?;
    if let Some(what) = known_format(&bytes) {
        return Err(ObjError::Whole(not_the_format(path, what, "OBJ")));
    }
    let text = ascii_text(&bytes);
    let lines = read_lines(Source {
        origin: path,
        text: &text,
    })
    .map_err(ObjError::At)?;
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    // What became of each `mtllib`, in file order: the names of its materials, or why not.
    let libraries: RefCell<Vec<Result<Vec<String>, String>>> = RefCell::default();
    // The MTL file each material was read from, by name: its texture names are relative to it.
    let mtl_files: RefCell<HashMap<String, PathBuf>> = RefCell::default();
    let (models, materials) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |mtl| {
        let path = folder.join(mtl);
        let loaded = files
            .read(&path)
            .and_then(|bytes| {
                let text = ascii_text(&bytes);
                check_mtl(&text)?;
                tobj::load_mtl_buf(&mut text.as_bytes()).map_err(|e| e.to_string())
            })
            .map_err(|e| format!("cannot read the MTL file `{}`: {e}", path.display()));
        libraries.borrow_mut().push(match &loaded {
            Ok((materials, _)) => Ok(materials.iter().map(|m| m.name.clone()).collect()),
            Err(message) => Err(message.clone()),
        });
        if let Ok((materials, _)) = &loaded {
            let mut mtl_files = mtl_files.borrow_mut();
            for material in materials {
                mtl_files
                    .entry(material.name.clone())
                    .or_insert(path.clone());
            }
        }
        loaded.map_err(|_| tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| ObjError::Whole(e.to_string()))?;
    let mut warnings = if uses_mtl {
        lines.material_warnings(libraries.into_inner())
    } else {
        Vec::new()
    };
    warnings.extend(lines.warnings);
    warnings.sort_by_key(|&(line, _)| line);
    if models.iter().all(|model| model.mesh.indices.is_empty()) {
        let vertices = text
            .split('\n')
            .filter(|line| line.split_whitespace().next() == Some("v"))
            .count();
        return Err(ObjError::Whole(format!(
            "it has no faces: {vertices} vertices (`v` lines) and no `f` line of three or more \
             vertices, so there is nothing to draw"
        )));
    }
    let parts = models
        .into_iter()
        .map(|model| {
            let m = model.mesh;
            ObjPart {
                mesh: Mesh {
                    positions: m.positions.chunks_exact(3).map(Vec3::from_slice).collect(),
                    normals: m.normals.chunks_exact(3).map(Vec3::from_slice).collect(),
                    uvs: m.texcoords.chunks_exact(2).map(Vec2::from_slice).collect(),
                    colors: Vec::new(),
                    faces: m
                        .indices
                        .chunks_exact(3)
                        .map(|f| [f[0], f[1], f[2]])
                        .collect(),
                    material: 0,
                },
                mtl_material: m.material_id,
            }
        })
        .collect();
    let origin = path.display();
    let mut warnings: Vec<String> = warnings
        .into_iter()
        .map(|(line, message)| format!("{origin}:{line}: {message}"))
        .collect();
    let mut textures = DiffuseTextures::default();
    let materials = match materials {
        Ok(materials) if uses_mtl => Ok(materials
            .iter()
            .map(|mtl| {
                let mtl_file = mtl_files.borrow().get(&mtl.name).cloned();
                let mtl_file = mtl_file.unwrap_or_else(|| path.to_path_buf());
                let texture = mtl.diffuse_texture.as_deref().and_then(|map| {
                    let found = textures.index(&mtl_file, map, files);
                    found
                        .map_err(|e| {
                            warnings.push(format!(
                                "{}: material `{}`: `map_Kd {map}`: {e}; the material keeps its \
                                 `Kd` colour",
                                mtl_file.display(),
                                mtl.name
                            ))
                        })
                        .ok()
                });
                // The image is the colour, as `Kd` would be: at full strength.
                let material = mtl_material(mtl);
                match texture {
                    Some(_) => Material {
                        texture,
                        diffuse: 1.0,
                        ..material
                    },
                    None => material,
                }
            })
            .collect()),
        Ok(materials) => Ok(materials.iter().map(mtl_material).collect()),
        Err(e) => Err(e.to_string()),
    };
    Ok(ObjContents {
        parts,
        materials,
        textures: textures.textures,
        warnings,
    })
}

/// The images the MTL materials' `map_Kd` lines name, each read once.
#[derive(Default)]
struct DiffuseTextures {
    textures: Vec<Texture>,
    /// The index of each image read, by its path.
    read: HashMap<PathBuf, u32>,
}

impl DiffuseTextures {
    /// The index of the texture `map` (a `map_Kd` line's value: options, then the file name,
    /// relative to the MTL file `mtl_file`) names, read now if it is new; or why it cannot be.
    fn index(&mut self, mtl_file: &Path, map: &str, files: SceneFiles) -> Result<u32, String> {
        let name = texture_file_name(map).ok_or("it names no file")?;
        let path = mtl_file.parent().unwrap_or(Path::new("")).join(name);
        if let Some(&index) = self.read.get(&path) {
            return Ok(index);
        }
        let bytes = files.read(&path)?;
        let image = SrgbImage::decode(&bytes)?;
        self.textures.push(Texture::Image {
            image: Arc::new(image),
            wrap: [Wrap::Repeat; 2],
            scale: Vec2::ONE,
            offset: Vec2::ZERO,
        });
        let index = self.textures.len() as u32 - 1;
        self.read.insert(path, index);
        Ok(index)
    }
}

/// The file name of a texture map line's value (`map_Kd -s 2 2 1 -clamp on wood.png`): past the
/// options, each a `-` word and the numbers or words after it, with Windows' `\` read as `/`.
fn texture_file_name(map: &str) -> Option<String> {
    let mut words = map.split_whitespace().peekable();
    while words.next_if(|w| w.starts_with('-')).is_some() {
        // An option's arguments: numbers, `on` or `off`, or a channel letter (`-imfchan r`).
        while words
            .next_if(|w| {
                w.parse::<f32>().is_ok() || ["on", "off", "r", "g", "b", "m", "l", "z"].contains(w)
            })
            .is_some()
        {}
    }
    let name: Vec<&str> = words.collect();
    (!name.is_empty()).then(|| name.join(" ").replace('\\', "/"))
}

/// Refuses, naming the line, what tobj would panic on in an MTL file's text: a colour (`Ka`,
/// `Kd`, `Ks`, `Ke`) of fewer than three numbers.
fn check_mtl(text: &str) -> Result<(), String> {
    for (index, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        if let Some(key @ ("Ka" | "Kd" | "Ks" | "Ke")) = words.next()
            && words.count() < 3
        {
            return Err(format!("line {}: `{key}` needs three numbers", index + 1));
        }
    }
    Ok(())
}

/// What the first look at an OBJ file's lines found.
#[derive(Debug, Default)]
struct ObjLines<'a> {
    /// Faces tobj leaves out or reads oddly: the line and what to say.
    warnings: Vec<(usize, String)>,
    /// The `mtllib` and `usemtl` lines, in file order.
    material_lines: Vec<MaterialLine<'a>>,
}

/// An `mtllib` or `usemtl` line, by its 1-based number.
#[derive(Debug)]
enum MaterialLine<'a> {
    Library { line: usize },
    Use { line: usize, name: &'a str },
}

/// The three kinds of vertex data a face indexes, in the order of `v/vt/vn`: their keyword and
/// what they are.
const VERTEX_DATA: [(&str, &str); 3] = [
    ("v", "position"),
    ("vt", "texture coordinate"),
    ("vn", "normal"),
];

/// Which of [`VERTEX_DATA`] a line's keyword brings, if any.
fn vertex_data(keyword: &str) -> Option<usize> {
    VERTEX_DATA.iter().position(|(k, _)| *k == keyword)
}

/// Reads the lines of an OBJ file the way tobj splits them (at `\n`, then at whitespace) and
/// checks the ones tobj would reject without a line number: `v`, `vt` and `vn` must start with
/// numbers, faces (`f`, and `l`, which tobj reads alike) must have whole-number indices of data
/// that is there, and `usemtl` must name a material.
fn read_lines(source: Source<'_>) -> Result<ObjLines<'_>, SceneError> {
    let text = source.text;
    let keyword = |line: &str| line.split_whitespace().next().and_then(vertex_data);
    // Positive indices may point past their line (tobj resolves them at the end); negative ones
    // count back from it.
    let mut totals = [0usize; 3];
    for kind in text.split('\n').filter_map(keyword) {
        totals[kind] += 1;
    }
    let mut so_far = [0usize; 3];
    let mut lines = ObjLines::default();
    // The first face of 1 or 2 vertices (line and vertex count) and how many there are.
    let mut short_faces: Option<(usize, usize, usize)> = None;
    // The first `l` of 3 or more vertices, which tobj reads as a face.
    let mut filled_polyline: Option<(usize, usize)> = None;
    let mut start = 0;
    for (number, line) in (1..).zip(text.split('\n')) {
        let mut words = words(line, start);
        start += line.len() + 1;
        let Some((keyword, keyword_span)) = words.next() else {
            continue;
        };
        if let Some(kind) = vertex_data(keyword) {
            let count = if keyword == "vt" { 2 } else { 3 };
            for _ in 0..count {
                match words.next() {
                    Some((word, _)) if word.parse::<f32>().is_ok() => {}
                    Some((word, span)) => {
                        let message = format!("expected a number for `{keyword}`, found `{word}`");
                        return Err(source.error(span, message));
                    }
                    None => {
                        let message = format!("`{keyword}` needs {count} numbers");
                        return Err(source.error(keyword_span, message));
                    }
                }
            }
            so_far[kind] += 1;
            continue;
        }
        match keyword {
            "f" | "l" => {
                let vertices: Vec<_> = words.collect();
                if vertices.is_empty() {
                    let message = format!("`{keyword}` has no vertices");
                    return Err(source.error(keyword_span, message));
                }
                // tobj leaves out faces of 1 or 2 vertices and lines of 1 or 2 (raylab draws no
                // lines), and does not look at their indices.
                let used = vertices.len() >= 3;
                for (word, span) in vertices.iter().cloned() {
                    check_vertex(word, used.then_some((&totals, &so_far)))
                        .map_err(|message| source.error(span, message))?;
                }
                if keyword == "f" && !used {
                    short_faces.get_or_insert((number, vertices.len(), 0)).2 += 1;
                } else if keyword == "l" && used {
                    filled_polyline.get_or_insert((number, vertices.len()));
                }
            }
            "mtllib" => lines
                .material_lines
                .push(MaterialLine::Library { line: number }),
            "usemtl" => {
                // The name as tobj takes it: everything after the first space.
                let name = line.split_once(' ').unwrap_or_default().1.trim();
                if name.is_empty() {
                    return Err(source.error(keyword_span, "`usemtl` names no material"));
                }
                lines
                    .material_lines
                    .push(MaterialLine::Use { line: number, name });
            }
            _ => {}
        }
    }
    if let Some((line, vertices, count)) = short_faces {
        let more = match count - 1 {
            0 => String::new(),
            1 => " (and 1 more such face)".to_string(),
            n => format!(" (and {n} more such faces)"),
        };
        lines.warnings.push((
            line,
            format!("a face of {vertices} vertices has no area, so it is left out{more}"),
        ));
    }
    if let Some((line, vertices)) = filled_polyline {
        lines.warnings.push((
            line,
            format!("a line (`l`) of {vertices} vertices is filled in as a polygon"),
        ));
    }
    Ok(lines)
}

/// The words of a line, each with its byte range in the text; the line starts at `start`.
fn words(line: &str, start: usize) -> impl Iterator<Item = (&str, Range<usize>)> {
    line.split_whitespace().map(move |word| {
        // The word is a slice of the line: their addresses differ by its offset in the line.
        let at = start + (word.as_ptr() as usize - line.as_ptr() as usize);
        (word, at..at + word.len())
    })
}

/// Checks one vertex of a face, `v`, `v/vt`, `v//vn` or `v/vt/vn`: whole-number indices, from
/// 1 or counting back from -1. With `counts` (how many of each kind of data the file has in
/// all, and before this line), checks that the data they index is there, as tobj does: texture
/// coordinates and normals only if the file has any.
fn check_vertex(word: &str, counts: Option<(&[usize; 3], &[usize; 3])>) -> Result<(), String> {
    let malformed = || {
        format!(
            "expected a face vertex `v`, `v/vt`, `v//vn` or `v/vt/vn` (whole numbers), found \
             `{word}`"
        )
    };
    let mut indices = [None; 3];
    let mut parts = word.split('/');
    for (index, part) in indices.iter_mut().zip(parts.by_ref()) {
        if !part.is_empty() {
            *index = Some(part.parse::<isize>().map_err(|_| malformed())?);
        }
    }
    if parts.next().is_some() || indices[0].is_none() {
        return Err(malformed());
    }
    let Some((totals, so_far)) = counts else {
        return Ok(());
    };
    for (kind, index) in indices.into_iter().enumerate() {
        let Some(index) = index else { continue };
        let (keyword, what) = VERTEX_DATA[kind];
        let (count, place) = match index {
            0 => {
                return Err(format!(
                    "{what} index 0: OBJ counts from 1 (or back from -1)"
                ));
            }
            _ if kind > 0 && totals[kind] == 0 => continue,
            1.. => (totals[kind], "in the file"),
            _ => (so_far[kind], "before this line"),
        };
        if index.unsigned_abs() > count {
            return Err(format!(
                "{what} index {index} is out of range: there are {count} `{keyword}` lines {place}"
            ));
        }
    }
    Ok(())
}

impl ObjLines<'_> {
    /// The line and a message for each `mtllib` whose file could not be read (`libraries`: what
    /// became of each, in order) and for the first `usemtl` of each material that no MTL file
    /// read before it defines (tobj then uses no material).
    fn material_warnings(
        &self,
        libraries: Vec<Result<Vec<String>, String>>,
    ) -> Vec<(usize, String)> {
        let mut libraries = libraries.into_iter();
        let mut defined = BTreeSet::new();
        let mut warned = BTreeSet::new();
        let mut warnings = Vec::new();
        for material_line in &self.material_lines {
            match *material_line {
                MaterialLine::Library { line } => match libraries.next() {
                    Some(Ok(names)) => defined.extend(names),
                    Some(Err(message)) => {
                        warnings.push((line, format!("{message}; its materials are left out")))
                    }
                    None => {}
                },
                MaterialLine::Use { line, name } => {
                    if !defined.contains(name) && warned.insert(name) {
                        let message = format!(
                            "no MTL file defines the material `{name}`; its faces get the \
                             default material"
                        );
                        warnings.push((line, message));
                    }
                }
            }
        }
        warnings
    }
}

/// A raylab material from an MTL one: `Kd` is the colour (reflected in full), `Ks` the
/// highlight (its brightest channel the coefficient), `Ke` the emission, `Ns` the shininess,
/// `d` the opacity and `Ni` the index of refraction. Values that are missing or out of range keep the default.
fn mtl_material(mtl: &tobj::Material) -> Material {
    let default = Material::default();
    let color_of = |c: Option<[f32; 3]>| {
        c.map(Color::from_array)
            .filter(|c| c.is_finite() && c.min_element() >= 0.0)
    };
    let diffuse = color_of(mtl.diffuse);
    let specular = color_of(mtl.specular).filter(|s| s.max_element() > 0.0);
    Material {
        color: diffuse.unwrap_or(default.color),
        diffuse: if diffuse.is_some() {
            1.0
        } else {
            default.diffuse
        },
        emission: color_of(mtl.emissive).unwrap_or(default.emission),
        specular: specular.map_or(default.specular, |s| s.max_element()),
        specular_color: specular.map_or(default.specular_color, |s| s / s.max_element()),
        shininess: mtl
            .shininess
            .filter(|s| s.is_finite() && *s >= 0.0)
            .unwrap_or(default.shininess),
        transparency: mtl
            .dissolve
            .filter(|d| (0.0..=1.0).contains(d))
            .map_or(default.transparency, |d| 1.0 - d),
        ior: mtl
            .optical_density
            .filter(|n| n.is_finite() && *n > 0.0)
            .unwrap_or(default.ior),
        ..default
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_texture_maps_file_name_is_found_past_its_options() {
        for (map, name) in [
            ("wood.png", Some("wood.png")),
            ("-s 2 2 1 -o 0.5 0.5 wood.png", Some("wood.png")),
            (
                "-clamp on -imfchan r -bm 1.5 maps\\old wood.png",
                Some("maps/old wood.png"),
            ),
            ("-blendu off", None),
            ("", None),
        ] {
            assert_eq!(texture_file_name(map).as_deref(), name, "{map:?}");
        }
    }

    #[test]
    fn mtl_colours_of_fewer_than_three_numbers_are_refused_at_their_line() {
        assert_eq!(
            check_mtl("newmtl red\nKd 1 0 0\nKs\n"),
            Err("line 3: `Ks` needs three numbers".to_string())
        );
        assert!(check_mtl("newmtl red\n  Ka 0.1 0.2\n").is_err());
        assert!(check_mtl("newmtl red\nKd 1 0 0\nKs 1 1 1 # more\nNs 10\n").is_ok());
    }

    #[test]
    fn mtl_values_map_onto_the_shading_model() {
        let mtl = tobj::Material {
            diffuse: Some([0.5, 0.25, 0.0]),
            specular: Some([0.0, 0.4, 0.2]),
            emissive: Some([0.1, 0.2, 0.3]),
            shininess: Some(64.0),
            dissolve: Some(0.25),
            optical_density: Some(1.5),
            ..Default::default()
        };
        let m = mtl_material(&mtl);
        assert_eq!(m.color, Color::new(0.5, 0.25, 0.0));
        assert_eq!(m.diffuse, 1.0);
        assert_eq!(m.specular, 0.4);
        assert_eq!(m.emission, Color::new(0.1, 0.2, 0.3));
        assert_eq!(m.specular_color, Color::new(0.0, 1.0, 0.5));
        assert_eq!(m.shininess, 64.0);
        assert_eq!(m.transparency, 0.75);
        assert_eq!(m.ior, 1.5);
    }

    #[test]
    fn missing_or_bad_mtl_values_keep_the_defaults() {
        let mtl = tobj::Material {
            diffuse: Some([f32::NAN, 0.0, 0.0]),
            dissolve: Some(2.0),
            ..Default::default()
        };
        assert_eq!(mtl_material(&mtl), Material::default());
    }
}
