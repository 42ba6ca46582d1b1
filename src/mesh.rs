//! Triangle meshes: shared vertices with optional per-vertex normals (smooth shading), texture
//! coordinates and colours, already placed in world space.

use glam::{Vec2, Vec3};

use crate::color::Color;
use crate::limits;
use crate::shapes::Triangle;
use crate::transform::Transform;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    /// Per-vertex normals, empty for flat shading.
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates, empty when the mesh has none.
    pub uvs: Vec<Vec2>,
    /// Per-vertex colours (linear RGB), empty when the mesh has none. They multiply the
    /// surface's colour (see [`crate::whitted::Tracer::base_color`]).
    pub colors: Vec<Color>,
    pub faces: Vec<[u32; 3]>,
    pub material: u32,
}

/// The colours of a surface the mesh's vertex colours multiply by where a mesh has none.
pub const NO_VERTEX_COLOR: Color = Color::ONE;

/// Why a mesh cannot be used.
#[derive(Clone, Debug, PartialEq)]
pub enum MeshError {
    IndexOutOfRange {
        face: usize,
        index: u32,
    },
    NormalCount {
        normals: usize,
        positions: usize,
    },
    UvCount {
        uvs: usize,
        positions: usize,
    },
    ColorCount {
        colors: usize,
        positions: usize,
    },
    /// A normal or colour that is not a finite number.
    NotFinite,
    /// A vertex past [`limits::MAX_COORDINATE`] (or not a number).
    OutOfRange(Vec3),
}

impl std::fmt::Display for MeshError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MeshError::IndexOutOfRange { face, index } => {
                write!(f, "face {face} uses vertex {index}, which does not exist")
            }
            MeshError::NormalCount { normals, positions } => write!(
                f,
                "{normals} normals for {positions} vertices (need one per vertex, or none)"
            ),
            MeshError::UvCount { uvs, positions } => write!(
                f,
                "{uvs} texture coordinates for {positions} vertices (need one per vertex, or none)"
            ),
            MeshError::ColorCount { colors, positions } => write!(
                f,
                "{colors} vertex colours for {positions} vertices (need one per vertex, or none)"
            ),
            MeshError::NotFinite => write!(f, "a normal or a colour is not a finite number"),
            MeshError::OutOfRange(p) => {
                write!(f, "{}", limits::out_of_range_message("a vertex", *p))
            }
        }
    }
}

impl Mesh {
    /// Checks the mesh's indices and attribute counts.
    pub fn validate(&self) -> Result<(), MeshError> {
        let n = self.positions.len();
        if !self.normals.is_empty() && self.normals.len() != n {
            return Err(MeshError::NormalCount {
                normals: self.normals.len(),
                positions: n,
            });
        }
        if !self.uvs.is_empty() && self.uvs.len() != n {
            return Err(MeshError::UvCount {
                uvs: self.uvs.len(),
                positions: n,
            });
        }
        if !self.colors.is_empty() && self.colors.len() != n {
            return Err(MeshError::ColorCount {
                colors: self.colors.len(),
                positions: n,
            });
        }
        if let Some(&p) = self.positions.iter().find(|&&p| !limits::within_range(p)) {
            return Err(MeshError::OutOfRange(p));
        }
        let finite = |v: &Vec3| v.is_finite();
        if !self.normals.iter().all(finite) || !self.colors.iter().all(finite) {
            return Err(MeshError::NotFinite);
        }
        for (face, f) in self.faces.iter().enumerate() {
            if let Some(&index) = f.iter().find(|&&i| i as usize >= n) {
                return Err(MeshError::IndexOutOfRange { face, index });
            }
        }
        Ok(())
    }

    /// Moves the mesh into world space.
    pub fn transform(&mut self, transform: &Transform) {
        for p in &mut self.positions {
            *p = transform.point_to_world(*p);
        }
        for n in &mut self.normals {
            *n = transform.normal_to_world(*n);
        }
    }

    /// The mesh's triangles, skipping degenerate ones (zero area: no ray can hit them).
    pub fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        self.faces.iter().enumerate().filter_map(move |(i, f)| {
            let tri = Triangle::new(f.map(|v| self.positions[v as usize]), i as u32);
            (tri.double_area() > 0.0).then_some(tri)
        })
    }

    /// Shading normal and texture coordinates of face `face` at barycentric `(b1, b2)`. Without
    /// vertex normals the shading normal is the geometric one. A mesh kept in its own space and
    /// placed by `placement` has its vertex normals moved into the world one by one, as
    /// [`Self::transform`] moves a copy's, so that both shade alike to the last bit.
    pub fn shading(
        &self,
        face: u32,
        bary: Vec2,
        geometric_normal: Vec3,
        placement: Option<&Transform>,
    ) -> (Vec3, Vec2) {
        let [i0, i1, i2] = self.faces[face as usize].map(|i| i as usize);
        let b0 = 1.0 - bary.x - bary.y;
        let normal = if self.normals.is_empty() {
            geometric_normal
        } else {
            let [n0, n1, n2] = [i0, i1, i2].map(|i| match placement {
                Some(transform) => transform.normal_to_world(self.normals[i]),
                None => self.normals[i],
            });
            let n = n0 * b0 + n1 * bary.x + n2 * bary.y;
            n.normalize_or(geometric_normal)
        };
        let uv = if self.uvs.is_empty() {
            bary
        } else {
            self.uvs[i0] * b0 + self.uvs[i1] * bary.x + self.uvs[i2] * bary.y
        };
        (normal, uv)
    }

    /// The vertex colour of face `face` at barycentric `(b1, b2)`; [`NO_VERTEX_COLOR`] when
    /// the mesh has none.
    pub fn color(&self, face: u32, bary: Vec2) -> Color {
        if self.colors.is_empty() {
            return NO_VERTEX_COLOR;
        }
        let [i0, i1, i2] = self.faces[face as usize].map(|i| i as usize);
        let b0 = 1.0 - bary.x - bary.y;
        self.colors[i0] * b0 + self.colors[i1] * bary.x + self.colors[i2] * bary.y
    }
}
