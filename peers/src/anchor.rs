//! Reading what `embree_anchor.py --dump DIR` writes: per mesh, its vertices and triangles and
//! its ray sets (origins, unit directions, `tfar` for shadow rays) with Embree's answer for each
//! ray (the closest triangle, −1 for a miss, or 1/0 for occluded/not). Raw little-endian files
//! listed in `manifest.json`.

use std::path::{Path, PathBuf};

use serde_json::Value;

/// A triangle mesh as Embree saw it.
pub struct AnchorMesh {
    pub name: String,
    pub positions: Vec<[f32; 3]>,
    pub faces: Vec<[u32; 3]>,
    pub ray_sets: Vec<RaySet>,
}

/// What a ray set asks for: the closest hit, or only whether anything is hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Query {
    Closest,
    Occluded,
}

/// One ray of a set: `origin + t·dir` for `t` in `(0, tfar)`.
#[derive(Clone, Copy, Debug)]
pub struct AnchorRay {
    pub origin: [f32; 3],
    pub dir: [f32; 3],
    pub tfar: f32,
}

/// Rays of one kind with Embree's answers: the triangle hit (−1 for none) or 1/0 for occluded.
pub struct RaySet {
    pub name: String,
    pub query: Query,
    pub rays: Vec<AnchorRay>,
    pub embree: Vec<i32>,
    /// The rays come in 8 × 8 tiles of neighbouring pixels, 64 at a time, for packet tracers.
    pub in_tiles: bool,
}

/// Suffix of the name of a camera ray set reordered into tiles.
pub const TILES: &str = "_tiles";

impl RaySet {
    /// The same set in 8 × 8 tiles (tile after tile, each in row order), when it is the camera
    /// rays of a square image in row order (a set named `primaryN` with N × N rays, N a
    /// multiple of 8).
    pub fn in_tiles(&self) -> Option<RaySet> {
        let size: usize = self.name.strip_prefix("primary")?.parse().ok()?;
        if size * size != self.rays.len() || !size.is_multiple_of(8) {
            return None;
        }
        let order: Vec<usize> = (0..size / 8)
            .flat_map(|tile_y| (0..size / 8).map(move |tile_x| (tile_y, tile_x)))
            .flat_map(|(tile_y, tile_x)| {
                (0..64).map(move |k| (tile_y * 8 + k / 8) * size + tile_x * 8 + k % 8)
            })
            .collect();
        Some(RaySet {
            name: format!("{}{TILES}", self.name),
            query: self.query,
            rays: order.iter().map(|&i| self.rays[i]).collect(),
            embree: order.iter().map(|&i| self.embree[i]).collect(),
            in_tiles: true,
        })
    }
}

/// The meshes named in `only` (all when empty) from the dump in `dir`.
pub fn load(dir: &Path, only: &[String]) -> Result<Vec<AnchorMesh>, String> {
    let manifest_path = dir.join("manifest.json");
    let text = std::fs::read_to_string(&manifest_path).map_err(|e| {
        format!(
            "cannot read {}: {e} (write it with embree_anchor.py --dump {})",
            manifest_path.display(),
            dir.display()
        )
    })?;
    let manifest: Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", manifest_path.display()))?;
    let meshes = manifest["meshes"]
        .as_object()
        .ok_or_else(|| format!("{}: no \"meshes\" table", manifest_path.display()))?;
    meshes
        .iter()
        .filter(|(name, _)| only.is_empty() || only.contains(name))
        .map(|(name, entry)| load_mesh(dir, name, entry))
        .collect()
}

fn load_mesh(dir: &Path, name: &str, entry: &Value) -> Result<AnchorMesh, String> {
    let file = |key: &str| -> Result<PathBuf, String> {
        entry[key]
            .as_str()
            .map(|f| dir.join(f))
            .ok_or_else(|| format!("mesh {name}: no \"{key}\""))
    };
    let positions = triples(&read_f32(&file("vertices_file")?)?)?;
    let faces = triples(&read_u32(&file("indices_file")?)?)?;
    let sets = entry["rays"]
        .as_object()
        .ok_or_else(|| format!("mesh {name}: no \"rays\""))?;
    let mut ray_sets: Vec<RaySet> = sets
        .iter()
        .map(|(set, e)| load_ray_set(dir, set, e).map_err(|err| format!("{name}/{set}: {err}")))
        .collect::<Result<_, _>>()?;
    let tiled: Vec<RaySet> = ray_sets.iter().filter_map(RaySet::in_tiles).collect();
    ray_sets.extend(tiled);
    Ok(AnchorMesh {
        name: name.to_string(),
        positions,
        faces,
        ray_sets,
    })
}

fn load_ray_set(dir: &Path, name: &str, entry: &Value) -> Result<RaySet, String> {
    let path = |key: &str| entry[key].as_str().map(|f| dir.join(f));
    let need = |key: &str| path(key).ok_or_else(|| format!("no \"{key}\""));
    let query = match entry["query"].as_str() {
        Some("INTERSECT") => Query::Closest,
        Some("OCCLUDED") => Query::Occluded,
        other => return Err(format!("unknown query {other:?}")),
    };
    let origins = triples(&read_f32(&need("org")?)?)?;
    let dirs = triples(&read_f32(&need("dir")?)?)?;
    let embree: Vec<i32> = read_u32(&need("embree_result")?)?
        .into_iter()
        .map(|v| v as i32)
        .collect();
    let tfar = match path("tfar") {
        Some(p) => read_f32(&p)?,
        None => vec![f32::INFINITY; origins.len()],
    };
    if dirs.len() != origins.len() || tfar.len() != origins.len() || embree.len() != origins.len() {
        return Err("files of different lengths".into());
    }
    let rays = (0..origins.len())
        .map(|i| AnchorRay {
            origin: origins[i],
            dir: dirs[i],
            tfar: tfar[i],
        })
        .collect();
    Ok(RaySet {
        name: name.to_string(),
        query,
        rays,
        embree,
        in_tiles: false,
    })
}

fn read_bytes(path: &Path) -> Result<Vec<[u8; 4]>, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if !bytes.len().is_multiple_of(4) {
        return Err(format!(
            "{}: not a whole number of 4-byte values",
            path.display()
        ));
    }
    Ok(bytes
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect())
}

fn read_f32(path: &Path) -> Result<Vec<f32>, String> {
    Ok(read_bytes(path)?
        .into_iter()
        .map(f32::from_le_bytes)
        .collect())
}

fn read_u32(path: &Path) -> Result<Vec<u32>, String> {
    Ok(read_bytes(path)?
        .into_iter()
        .map(u32::from_le_bytes)
        .collect())
}

/// Consecutive values grouped by three.
fn triples<T: Copy>(values: &[T]) -> Result<Vec<[T; 3]>, String> {
    if !values.len().is_multiple_of(3) {
        return Err(format!("{} values do not make whole triples", values.len()));
    }
    Ok(values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
}
