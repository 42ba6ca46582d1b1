//! PLY (the Stanford polygon format) read into a [`Mesh`]: ASCII, binary little endian and
//! binary big endian. The `vertex` element gives positions (`x y z`), and when present normals
//! (`nx ny nz`), texture coordinates (`u v`, `s t` or `texture_u texture_v`) and colours
//! (`red green blue`, sRGB as 8-bit, 16-bit or float values, read into linear RGB); the `face` element's `vertex_indices` (or `vertex_index`)
//! lists, of any length, are cut into triangles as fans. Other elements and properties are
//! skipped. Every count is checked against the bytes left before anything is allocated for it,
//! and an error says where: `line:column` in ASCII, the byte offset and the element in binary.

use std::path::Path;

use super::error::SceneError;
use crate::color::{Color, srgb_to_linear};
use crate::mesh::Mesh;

/// Where in the file an error is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PlyPlace {
    /// 1-based line and column of the header or of an ASCII body.
    Text { line: usize, column: usize },
    /// The byte offset in a binary body, and the element (and its number) being read.
    Binary {
        offset: usize,
        element: String,
        index: usize,
    },
}

/// What is wrong with a PLY file, and where.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PlyError {
    pub place: PlyPlace,
    pub message: String,
}

impl std::fmt::Display for PlyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.place {
            PlyPlace::Text { line, column } => write!(f, "{line}:{column}: {}", self.message),
            PlyPlace::Binary {
                offset,
                element,
                index,
            } => write!(f, "byte {offset} ({element} {index}): {}", self.message),
        }
    }
}

impl PlyError {
    /// The error as a [`SceneError`] of the PLY file at `path`, whose bytes are `bytes`: at its
    /// line and column, with the line shown, or at its byte offset in a binary body.
    pub fn in_file(self, path: &Path, bytes: &[u8]) -> SceneError {
        match self.place {
            PlyPlace::Text { line, column } => {
                SceneError::at_line(path, bytes, line, column, self.message)
            }
            PlyPlace::Binary {
                offset,
                element,
                index,
            } => SceneError::at_byte(path, offset, format!("{element} {index}: {}", self.message)),
        }
    }
}

/// The most bytes a header may take.
const MAX_HEADER: usize = 1 << 16;

/// A scalar type of a property.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn named(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// The value that stands for 1 in a colour of this type: 255 for `uchar`, 1 for floats.
    fn full_scale(self) -> f32 {
        match self {
            Scalar::I8 => i8::MAX as f32,
            Scalar::U8 => u8::MAX as f32,
            Scalar::I16 => i16::MAX as f32,
            Scalar::U16 => u16::MAX as f32,
            Scalar::I32 => i32::MAX as f32,
            Scalar::U32 => u32::MAX as f32,
            Scalar::F32 | Scalar::F64 => 1.0,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

/// A property of an element: one value, or a list of them after its length.
#[derive(Clone, Debug, PartialEq)]
struct Property {
    name: String,
    kind: Scalar,
    /// The type of the list's length, for a list.
    list: Option<Scalar>,
}

#[derive(Clone, Debug, PartialEq)]
struct Element {
    name: String,
    count: usize,
    properties: Vec<Property>,
}

impl Element {
    /// The fewest bytes one of these elements takes in the body.
    fn min_bytes(&self, binary: bool) -> usize {
        let each = |p: &Property| match (binary, p.list) {
            (true, Some(length)) => length.size(),
            (true, None) => p.kind.size(),
            // A value and the space after it.
            (false, _) => 2,
        };
        self.properties.iter().map(each).sum::<usize>().max(1)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

/// Reads a PLY file's bytes.
pub fn parse_ply(bytes: &[u8]) -> Result<Mesh, PlyError> {
    let (encoding, elements, body) = header(bytes)?;
    let mut body = Body::new(bytes, body, encoding);
    let mut mesh = Mesh::default();
    for element in &elements {
        let needed = element
            .count
            .checked_mul(element.min_bytes(encoding != Encoding::Ascii));
        // The last ASCII value of the file may end it without a space or a newline after it.
        let slack = usize::from(encoding == Encoding::Ascii);
        if needed.is_none_or(|n| n > body.left() + slack) {
            return Err(body.error(
                &element.name,
                0,
                format!(
                    "the header promises {} {} elements, more than the {} bytes left can hold",
                    element.count,
                    element.name,
                    body.left()
                ),
            ));
        }
        match element.name.as_str() {
            "vertex" => vertices(&mut body, element, &mut mesh)?,
            "face" => faces(&mut body, element, &mut mesh)?,
            _ => skip(&mut body, element)?,
        }
    }
    if mesh.positions.is_empty() && !mesh.faces.is_empty() {
        return Err(body.error("face", 0, "faces but no vertices".into()));
    }
    Ok(mesh)
}

/// The header: the encoding, the elements and the byte where the body starts.
fn header(bytes: &[u8]) -> Result<(Encoding, Vec<Element>, usize), PlyError> {
    let at = |line: usize, column: usize, message: String| PlyError {
        place: PlyPlace::Text { line, column },
        message,
    };
    let end = find(bytes, b"end_header")
        .filter(|&e| e < MAX_HEADER)
        .ok_or_else(|| {
            at(
                1,
                1,
                format!("no `end_header` line in the first {MAX_HEADER} bytes"),
            )
        })?;
    let after = bytes[end..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |p| end + p + 1);
    let text = std::str::from_utf8(&bytes[..end]).map_err(|e| {
        let line = 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        at(line, 1, "the header is not text".into())
    })?;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        let words: Vec<&str> = line.split_whitespace().collect();
        let column = |k: usize| line.find(words[k]).map_or(1, |c| c + 1);
        match words.as_slice() {
            ["ply"] if n == 1 => {}
            _ if n == 1 => {
                return Err(at(
                    1,
                    1,
                    "not a PLY file: the first line must be `ply`".into(),
                ));
            }
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", ..] if encoding.is_some() => {
                return Err(at(n, 1, "a second `format` line".into()));
            }
            ["format", kind, _version] => {
                encoding = Some(match *kind {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::Little,
                    "binary_big_endian" => Encoding::Big,
                    _ => {
                        return Err(at(
                            n,
                            column(1),
                            format!(
                                "unknown format `{kind}` (expected ascii, binary_little_endian or binary_big_endian)"
                            ),
                        ));
                    }
                })
            }
            ["element", name, _] if elements.iter().any(|e| e.name == *name) => {
                return Err(at(n, column(1), format!("a second `{name}` element")));
            }
            ["element", name, count] => {
                let count = count.parse::<usize>().map_err(|_| {
                    at(
                        n,
                        column(2),
                        format!("`{count}` is not a count of elements"),
                    )
                })?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                });
            }
            ["property", rest @ ..] => {
                let Some(element) = elements.last_mut() else {
                    return Err(at(n, 1, "a property before any element".into()));
                };
                let scalar = |k: usize| {
                    Scalar::named(words[k]).ok_or_else(|| {
                        at(n, column(k), format!("unknown type `{}` (expected char, uchar, short, ushort, int, uint, float or double, or their int8…float64 names)", words[k]))
                    })
                };
                let property =
                    match rest {
                        ["list", _, _, name] => Property {
                            name: name.to_string(),
                            list: Some(scalar(2)?),
                            kind: scalar(3)?,
                        },
                        [_, name] => Property {
                            name: name.to_string(),
                            list: None,
                            kind: scalar(1)?,
                        },
                        _ => return Err(at(
                            n,
                            1,
                            "expected `property TYPE NAME` or `property list COUNT_TYPE TYPE NAME`"
                                .into(),
                        )),
                    };
                if property.list.is_some_and(|l| !l.is_integer()) {
                    return Err(at(
                        n,
                        column(2),
                        "a list's length must be of an integer type".into(),
                    ));
                }
                element.properties.push(property);
            }
            _ => {
                return Err(at(
                    n,
                    1,
                    format!("unexpected header line `{}`", line.trim()),
                ));
            }
        }
    }
    let encoding = encoding.ok_or_else(|| at(2, 1, "no `format` line in the header".into()))?;
    Ok((encoding, elements, after))
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

/// The body, read value by value.
struct Body<'a> {
    bytes: &'a [u8],
    at: usize,
    /// Where the last ASCII value read starts: where an error about it points.
    token: usize,
    encoding: Encoding,
}

impl<'a> Body<'a> {
    fn new(bytes: &'a [u8], at: usize, encoding: Encoding) -> Body<'a> {
        Body {
            bytes,
            at,
            token: at,
            encoding,
        }
    }

    fn left(&self) -> usize {
        self.bytes.len() - self.at
    }

    /// An error at the current place, in element `name` number `index`.
    fn error(&self, name: &str, index: usize, message: String) -> PlyError {
        let place = match self.encoding {
            Encoding::Ascii => {
                let before = &self.bytes[..self.token];
                let line = 1 + before.iter().filter(|&&b| b == b'\n').count();
                let start = before
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |p| p + 1);
                PlyPlace::Text {
                    line,
                    column: 1 + self.token - start,
                }
            }
            _ => PlyPlace::Binary {
                offset: self.at,
                element: name.to_string(),
                index,
            },
        };
        PlyError { place, message }
    }

    /// The next value, of type `kind`.
    fn value(&mut self, kind: Scalar) -> Result<f64, String> {
        match self.encoding {
            Encoding::Ascii => self.word(kind),
            Encoding::Little | Encoding::Big => self.binary(kind),
        }
    }

    fn word(&mut self, kind: Scalar) -> Result<f64, String> {
        while self.bytes.get(self.at).is_some_and(u8::is_ascii_whitespace) {
            self.at += 1;
        }
        self.token = self.at;
        while self
            .bytes
            .get(self.at)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.at += 1;
        }
        if self.token == self.at {
            return Err("the file ends before its last element".into());
        }
        let text = String::from_utf8_lossy(&self.bytes[self.token..self.at]);
        let value = text.parse::<f64>().ok().filter(|v| v.is_finite());
        let value = value.filter(|v| !kind.is_integer() || v.fract() == 0.0);
        let expected = if kind.is_integer() {
            "an integer"
        } else {
            "a finite number"
        };
        value.ok_or_else(|| format!("`{text}` is not {expected}"))
    }

    fn binary(&mut self, kind: Scalar) -> Result<f64, String> {
        let size = kind.size();
        let Some(raw) = self.bytes.get(self.at..self.at + size) else {
            return Err("the file ends before its last element".into());
        };
        let mut b = [0u8; 8];
        b[..size].copy_from_slice(raw);
        if self.encoding == Encoding::Big {
            b[..size].reverse();
        }
        self.at += size;
        Ok(match kind {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            Scalar::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }

    /// A list's length, checked against the bytes left.
    fn length(&mut self, length: Scalar, item: Scalar) -> Result<usize, String> {
        let n = self.value(length)?;
        let per_item = if self.encoding == Encoding::Ascii {
            2
        } else {
            item.size()
        };
        if n < 0.0 || n as usize > self.left() / per_item {
            return Err(format!(
                "a list of {n} values, more than the bytes left can hold"
            ));
        }
        Ok(n as usize)
    }
}

/// Which vertex attribute a property fills, and where in it.
#[derive(Clone, Copy, PartialEq)]
enum Slot {
    Position(usize),
    Normal(usize),
    Uv(usize),
    Color(usize),
    Other,
}

fn slot(name: &str) -> Slot {
    match name {
        "x" => Slot::Position(0),
        "y" => Slot::Position(1),
        "z" => Slot::Position(2),
        "nx" => Slot::Normal(0),
        "ny" => Slot::Normal(1),
        "nz" => Slot::Normal(2),
        "u" | "s" | "texture_u" => Slot::Uv(0),
        "v" | "t" | "texture_v" => Slot::Uv(1),
        "red" | "r" => Slot::Color(0),
        "green" | "g" => Slot::Color(1),
        "blue" | "b" => Slot::Color(2),
        _ => Slot::Other,
    }
}

fn vertices(body: &mut Body, element: &Element, mesh: &mut Mesh) -> Result<(), PlyError> {
    let slots: Vec<Slot> = element.properties.iter().map(|p| slot(&p.name)).collect();
    // An attribute is read when each of its parts is a property once.
    let has = |part: fn(usize) -> Slot, parts: usize| {
        (0..parts).all(|k| slots.iter().filter(|&&s| s == part(k)).count() == 1)
    };
    if !has(Slot::Position, 3) {
        return Err(body.error(
            "vertex",
            0,
            "the vertex element needs x, y and z, once each".into(),
        ));
    }
    let (normals, uvs, colors) = (has(Slot::Normal, 3), has(Slot::Uv, 2), has(Slot::Color, 3));
    let n = element.count;
    mesh.positions.reserve_exact(n);
    mesh.normals.reserve_exact(if normals { n } else { 0 });
    mesh.uvs.reserve_exact(if uvs { n } else { 0 });
    mesh.colors.reserve_exact(if colors { n } else { 0 });
    for index in 0..n {
        let (mut p, mut nrm, mut uv, mut c) = ([0.0f32; 3], [0.0f32; 3], [0.0f32; 2], [0.0f32; 3]);
        for (property, &slot) in element.properties.iter().zip(&slots) {
            let fail = |body: &Body, e: String| body.error("vertex", index, e);
            if let Some(length) = property.list {
                let count = body
                    .length(length, property.kind)
                    .map_err(|e| fail(body, e))?;
                for _ in 0..count {
                    body.value(property.kind).map_err(|e| fail(body, e))?;
                }
                continue;
            }
            let v = body.value(property.kind).map_err(|e| fail(body, e))?;
            match slot {
                Slot::Position(k) => p[k] = v as f32,
                Slot::Normal(k) => nrm[k] = v as f32,
                Slot::Uv(k) => uv[k] = v as f32,
                Slot::Color(k) => c[k] = srgb_to_linear(v as f32 / property.kind.full_scale()),
                Slot::Other => {}
            }
        }
        mesh.positions.push(p.into());
        if normals {
            mesh.normals.push(nrm.into());
        }
        if uvs {
            mesh.uvs.push(uv.into());
        }
        if colors {
            mesh.colors.push(Color::from(c));
        }
    }
    Ok(())
}

fn faces(body: &mut Body, element: &Element, mesh: &mut Mesh) -> Result<(), PlyError> {
    let is_indices = |p: &Property| {
        p.list.is_some() && matches!(p.name.as_str(), "vertex_indices" | "vertex_index")
    };
    if !element.properties.iter().any(is_indices) {
        return Err(body.error(
            "face",
            0,
            "the face element needs a `vertex_indices` list".into(),
        ));
    }
    let vertex_count = mesh.positions.len();
    // One triangle a face, as most files have; polygons of more corners grow it.
    mesh.faces.reserve_exact(element.count);
    let mut polygon: Vec<u32> = Vec::new();
    for index in 0..element.count {
        for property in &element.properties {
            let fail = |body: &Body, e: String| body.error("face", index, e);
            let Some(length) = property.list else {
                body.value(property.kind).map_err(|e| fail(body, e))?;
                continue;
            };
            let count = body
                .length(length, property.kind)
                .map_err(|e| fail(body, e))?;
            polygon.clear();
            for _ in 0..count {
                let v = body.value(property.kind).map_err(|e| fail(body, e))?;
                if is_indices(property) && !(v >= 0.0 && (v as usize) < vertex_count) {
                    return Err(fail(
                        body,
                        format!("vertex {v} does not exist (the file has {vertex_count} vertices)"),
                    ));
                }
                polygon.push(v as u32);
            }
            if is_indices(property) {
                for k in 1..polygon.len().saturating_sub(1) {
                    mesh.faces.push([polygon[0], polygon[k], polygon[k + 1]]);
                }
            }
        }
    }
    Ok(())
}

/// Reads past an element raylab does not use.
fn skip(body: &mut Body, element: &Element) -> Result<(), PlyError> {
    for index in 0..element.count {
        for property in &element.properties {
            let fail = |body: &Body, e: String| body.error(&element.name, index, e);
            let count = match property.list {
                Some(length) => body
                    .length(length, property.kind)
                    .map_err(|e| fail(body, e))?,
                None => 1,
            };
            for _ in 0..count {
                body.value(property.kind).map_err(|e| fail(body, e))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Vec2, Vec3};

    const HEADER: &str = "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
        property uchar red\nproperty uchar green\nproperty uchar blue\n\
        element face 2\nproperty list uchar int vertex_indices\nend_header\n";

    /// A unit square (a quad) and a triangle beside it, with colours, in ASCII.
    fn ascii() -> Vec<u8> {
        let body = "0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 255 255\n2 0 0 0 0 0\n\
            4 0 1 2 3\n3 1 4 2\n";
        format!("ply\nformat ascii 1.0\ncomment made by hand\n{HEADER}{body}").into_bytes()
    }

    /// The same mesh in binary, `big` endian or little.
    fn binary(big: bool) -> Vec<u8> {
        let kind = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let mut bytes = format!("ply\nformat {kind} 1.0\n{HEADER}").into_bytes();
        let f = |v: f32| {
            if big {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            }
        };
        let i = |v: i32| {
            if big {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            }
        };
        let vertices = [
            ([0.0, 0.0, 0.0], [255, 0, 0]),
            ([1.0, 0.0, 0.0], [0, 255, 0]),
            ([1.0, 1.0, 0.0], [0, 0, 255]),
            ([0.0, 1.0, 0.0], [255, 255, 255]),
            ([2.0, 0.0, 0.0], [0, 0, 0]),
        ];
        for (p, c) in vertices {
            p.iter().for_each(|&v| bytes.extend(f(v)));
            bytes.extend(c);
        }
        for face in [&[0, 1, 2, 3][..], &[1, 4, 2]] {
            bytes.push(face.len() as u8);
            face.iter().for_each(|&v| bytes.extend(i(v)));
        }
        bytes
    }

    #[test]
    fn ascii_and_both_binaries_give_the_same_mesh_with_quads_cut_into_fans() {
        let mesh = parse_ply(&ascii()).unwrap();
        assert_eq!(mesh.positions.len(), 5);
        assert_eq!(mesh.faces, vec![[0, 1, 2], [0, 2, 3], [1, 4, 2]]);
        assert_eq!(mesh.colors[0], Color::new(1.0, 0.0, 0.0));
        assert_eq!(mesh.colors[4], Color::ZERO);
        assert!(mesh.normals.is_empty() && mesh.uvs.is_empty());
        assert_eq!(parse_ply(&binary(false)).unwrap(), mesh);
        assert_eq!(parse_ply(&binary(true)).unwrap(), mesh);
    }

    #[test]
    fn errors_say_where() {
        let bad_index = String::from_utf8(ascii())
            .unwrap()
            .replace("3 1 4 2", "3 1 9 2");
        let e = parse_ply(bad_index.as_bytes()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "20:5: vertex 9 does not exist (the file has 5 vertices)"
        );
        let e = parse_ply(
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n0\n1\n2\n",
        )
        .unwrap_err();
        assert!(
            e.to_string()
                .contains("the vertex element needs x, y and z"),
            "{e}"
        );
        let mut truncated = binary(false);
        truncated.truncate(truncated.len() - 3);
        let e = parse_ply(&truncated).unwrap_err();
        assert!(
            matches!(e.place, PlyPlace::Binary { ref element, index: 1, .. } if element == "face"),
            "{e}"
        );
        let e = parse_ply(
            b"ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\nend_header\n1",
        )
        .unwrap_err();
        assert!(
            e.message.contains("more than the 1 bytes left can hold"),
            "{e}"
        );
        let e = parse_ply(b"ply\nformat ascii 1.0\nproperty float x\nend_header\n").unwrap_err();
        assert_eq!(e.to_string(), "3:1: a property before any element");
        let e = parse_ply(b"ply\nformat zip 1.0\nend_header\n").unwrap_err();
        assert!(
            e.to_string().starts_with("2:8: unknown format `zip`"),
            "{e}"
        );
        assert!(
            parse_ply(b"solid cube\n")
                .unwrap_err()
                .message
                .contains("end_header")
        );
    }

    #[test]
    fn other_elements_and_properties_are_skipped_and_float_colours_read_as_srgb() {
        let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
            property double z\nproperty float nx\nproperty float ny\nproperty float nz\n\
            property float s\nproperty float t\nproperty float red\nproperty float green\n\
            property float blue\nproperty float confidence\nelement face 1\n\
            property uchar flags\nproperty list uchar uint vertex_index\nelement edge 1\n\
            property int vertex1\nproperty int vertex2\nend_header\n\
            0 0 0 0 0 1 0 0 0.5 0.5 0.5 9\n1 0 0 0 0 1 1 0 0.5 0.5 0.5 9\n\
            0 1 0 0 0 1 0 1 0.5 0.5 0.5 9\n7 3 0 1 2\n0 1\n";
        let mesh = parse_ply(text.as_bytes()).unwrap();
        assert_eq!(mesh.faces, vec![[0, 1, 2]]);
        assert_eq!(mesh.normals, vec![Vec3::Z; 3]);
        assert_eq!(mesh.uvs[2], Vec2::new(0.0, 1.0));
        assert_eq!(mesh.colors[1], Color::splat(srgb_to_linear(0.5)));
        // The file may end right after its last value.
        let mesh = parse_ply(text.trim_end().as_bytes()).unwrap();
        assert_eq!(mesh.faces, vec![[0, 1, 2]]);
    }
}
