//! Wavefront OBJ files (and the MTL materials they name), read with tobj into raylab meshes in
//! the OBJ's own coordinates.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::files::SceneFiles;
use crate::material::{Color, Material};
use crate::mesh::Mesh;

/// What an OBJ file holds.
#[derive(Debug)]
pub struct ObjContents {
    /// One part per OBJ object or group.
    pub parts: Vec<ObjPart>,
    /// The MTL materials, or why they could not be loaded.
    pub materials: Result<Vec<Material>, String>,
}

/// One object or group of an OBJ file: a mesh (its `material` field not yet set) and the MTL
/// material it uses, if any.
#[derive(Debug)]
pub struct ObjPart {
    pub mesh: Mesh,
    /// Index into [`ObjContents::materials`].
    pub mtl_material: Option<usize>,
}

/// Reads an OBJ file, triangulated, with one index per vertex for position, normal and texture
/// coordinates. MTL files are looked up next to the OBJ file.
pub fn load_obj(path: &Path, files: SceneFiles) -> Result<ObjContents, String> {
    let bytes = files.read(path)?;
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let folder = path.parent().unwrap_or(Path::new(""));
    let (models, materials) = tobj::load_obj_buf(&mut &bytes[..], &options, |mtl| {
        let bytes = files
            .read(&folder.join(mtl))
            .map_err(|_| tobj::LoadError::OpenFileFailed)?;
        tobj::load_mtl_buf(&mut &bytes[..])
    })
    .map_err(|e| e.to_string())?;
    let parts = models
        .into_iter()
        .map(|model| {
            let m = model.mesh;
            ObjPart {
                mesh: Mesh {
                    positions: m.positions.chunks_exact(3).map(Vec3::from_slice).collect(),
                    normals: m.normals.chunks_exact(3).map(Vec3::from_slice).collect(),
                    uvs: m.texcoords.chunks_exact(2).map(Vec2::from_slice).collect(),
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
    Ok(ObjContents {
        parts,
        materials: materials
            .map(|materials| materials.iter().map(mtl_material).collect())
            .map_err(|e| e.to_string()),
    })
}

/// A raylab material from an MTL one: `Kd` is the colour (reflected in full), `Ks` the
/// highlight (its brightest channel the coefficient), `Ns` the shininess, `d` the opacity and
/// `Ni` the index of refraction. Values that are missing or out of range keep the default.
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
    fn mtl_values_map_onto_the_shading_model() {
        let mtl = tobj::Material {
            diffuse: Some([0.5, 0.25, 0.0]),
            specular: Some([0.0, 0.4, 0.2]),
            shininess: Some(64.0),
            dissolve: Some(0.25),
            optical_density: Some(1.5),
            ..Default::default()
        };
        let m = mtl_material(&mtl);
        assert_eq!(m.color, Color::new(0.5, 0.25, 0.0));
        assert_eq!(m.diffuse, 1.0);
        assert_eq!(m.specular, 0.4);
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
