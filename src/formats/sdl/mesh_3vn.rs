//! The book's `.3vn` mesh files (`Mesh::readMesh`): free-format numbers, `numVerts numNorms
//! numFaces`, the vertices, the normals, then per face its corner count `n`, `n` vertex indices
//! and `n` normal indices (0-based). Faces of any size are cut into fans of triangles; each
//! corner keeps its own normal, so flat and smooth meshes both come out as drawn.

use glam::Vec3;

use crate::mesh::Mesh;

/// The numbers of a `.3vn` file, read one at a time.
struct Numbers<'a> {
    words: std::iter::Enumerate<std::str::SplitAsciiWhitespace<'a>>,
    /// How many numbers the file holds, to tell a count that cannot be true.
    total: usize,
}

impl Numbers<'_> {
    fn next(&mut self, what: &str) -> Result<f32, String> {
        match self.words.next() {
            Some((i, word)) => word
                .parse::<f32>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("number {}: expected {what}, found `{word}`", i + 1)),
            None => Err(format!("the file ends where {what} was expected")),
        }
    }

    /// A count of items that take at least `per_item` numbers each.
    fn count(&mut self, what: &str, per_item: usize) -> Result<usize, String> {
        let n = self.next(what)?;
        if n < 0.0 || n.fract() != 0.0 || n * per_item as f32 > self.total as f32 {
            return Err(format!("{what} {n} is not a count this file can hold"));
        }
        Ok(n as usize)
    }

    /// An index below `limit`.
    fn index(&mut self, what: &str, limit: usize, face: usize) -> Result<usize, String> {
        let i = self.next(what)?;
        if i < 0.0 || i.fract() != 0.0 || i >= limit as f32 {
            return Err(format!("face {face}: {what} {i} does not exist"));
        }
        Ok(i as usize)
    }

    fn vector(&mut self, what: &str) -> Result<Vec3, String> {
        Ok(Vec3::new(
            self.next(what)?,
            self.next(what)?,
            self.next(what)?,
        ))
    }
}

/// Reads a `.3vn` file's text into a mesh in object space. The message says what is wrong and
/// which number of the file it is at.
pub(crate) fn parse_3vn(text: &str) -> Result<Mesh, String> {
    let mut numbers = Numbers {
        words: text.split_ascii_whitespace().enumerate(),
        total: text.split_ascii_whitespace().count(),
    };
    let vertex_count = numbers.count("the number of vertices", 3)?;
    let normal_count = numbers.count("the number of normals", 3)?;
    let face_count = numbers.count("the number of faces", 7)?;
    let vertices = (0..vertex_count)
        .map(|_| numbers.vector("a vertex coordinate"))
        .collect::<Result<Vec<_>, _>>()?;
    let normals = (0..normal_count)
        .map(|_| numbers.vector("a normal coordinate"))
        .collect::<Result<Vec<_>, _>>()?;
    let mut mesh = Mesh::default();
    for face in 0..face_count {
        let corners = numbers.count("a face's number of corners", 2)?;
        if corners < 3 {
            return Err(format!(
                "face {face} has {corners} corners (at least 3 needed)"
            ));
        }
        let points = (0..corners)
            .map(|_| numbers.index("vertex", vertex_count, face))
            .collect::<Result<Vec<_>, _>>()?;
        let turns = (0..corners)
            .map(|_| numbers.index("normal", normal_count, face))
            .collect::<Result<Vec<_>, _>>()?;
        let [a, b, c] = [0, 1, 2].map(|k| vertices[points[k]]);
        let flat = (b - a).cross(c - a).try_normalize().unwrap_or(Vec3::Z);
        let first = mesh.positions.len() as u32;
        for (&p, &n) in points.iter().zip(&turns) {
            mesh.positions.push(vertices[p]);
            mesh.normals
                .push(normals[n].try_normalize().unwrap_or(flat));
        }
        let corners = corners as u32;
        mesh.faces
            .extend((1..corners - 1).map(|k| [first, first + k, first + k + 1]));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: &str = "4 1 1\n0 0 0  1 0 0  1 1 0  0 1 0\n0 0 1\n4\n0 1 2 3\n0 0 0 0\n";

    #[test]
    fn faces_become_fans_with_their_corners_normals() {
        let mesh = parse_3vn(SQUARE).unwrap();
        assert_eq!(mesh.faces, [[0, 1, 2], [0, 2, 3]]);
        assert_eq!(mesh.normals, [Vec3::Z; 4]);
        assert!(mesh.validate().is_ok());
    }

    #[test]
    fn bad_files_say_what_is_wrong() {
        let error = parse_3vn("4 1 1\n0 0 0 1 0 0 1 1 0 0 1 0\n0 0 1\n3 0 1 7 0 0 0").unwrap_err();
        assert!(error.contains("vertex 7 does not exist"), "{error}");
        let error = parse_3vn("1000000000 0 0").unwrap_err();
        assert!(error.contains("not a count"), "{error}");
        let error = parse_3vn("1 0 0 0 x 0").unwrap_err();
        assert!(
            error.contains("number 5: expected a vertex coordinate, found `x`"),
            "{error}"
        );
        let error =
            parse_3vn("4 1 1\n0 0 0 1 0 0 1 1 0 0 1 0\n0 0 1\n4\n0 1 2 3\n0 0 0").unwrap_err();
        assert!(error.contains("the file ends"), "{error}");
    }
}
