//! A file's format told from its first bytes, so that a file given as one format and holding
//! another is named for what it is (`bunny.ply is a PLY file, not OBJ`) instead of being read
//! as text it is not.

use std::path::Path;

/// The formats raylab tells apart by their first bytes, and what each is called in messages.
const SIGNATURES: [(&[u8], &str); 8] = [
    (b"ply\n", "a PLY file"),
    (b"ply\r\n", "a PLY file"),
    (b"glTF", "a binary glTF file"),
    (b"\x89PNG\r\n\x1a\n", "a PNG image"),
    (b"\xff\xd8\xff", "a JPEG image"),
    (b"\x76\x2f\x31\x01", "an OpenEXR image"),
    (b"PK\x03\x04", "a ZIP archive"),
    (b"\x1f\x8b", "a gzip archive"),
];

/// What `bytes` are, if they begin as one of the formats raylab knows and does not read as a
/// scene: PLY, glTF (binary, or JSON with an `"asset"` key), images and archives.
pub fn known_format(bytes: &[u8]) -> Option<&'static str> {
    if let Some((_, name)) = SIGNATURES
        .iter()
        .find(|(magic, _)| bytes.starts_with(magic))
    {
        return Some(name);
    }
    let start = bytes.iter().position(|b| !b.is_ascii_whitespace())?;
    let head = &bytes[start..bytes.len().min(start + 4096)];
    (head.starts_with(b"{") && head.windows(7).any(|w| w == b"\"asset\"")).then_some("a glTF file")
}

/// The message for a file at `path` that holds `what` (from [`known_format`]) where `expected`
/// was wanted: `bunny.ply is a PLY file, not OBJ`.
pub fn not_the_format(path: &Path, what: &str, expected: &str) -> String {
    let name = path
        .file_name()
        .unwrap_or(path.as_os_str())
        .to_string_lossy();
    format!("{name} is {what}, not {expected}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn models_images_and_archives_are_told_by_their_first_bytes() {
        assert_eq!(
            known_format(b"ply\nformat binary_little_endian 1.0\n"),
            Some("a PLY file")
        );
        assert_eq!(
            known_format(b"ply\r\nformat ascii 1.0\r\n"),
            Some("a PLY file")
        );
        assert_eq!(known_format(b"glTF\x02\0\0\0"), Some("a binary glTF file"));
        let gltf = b"  {\n  \"asset\": {\"version\": \"2.0\"}, \"scenes\": []}";
        assert_eq!(known_format(gltf), Some("a glTF file"));
        assert_eq!(known_format(b"\x89PNG\r\n\x1a\n...."), Some("a PNG image"));
        // Text formats raylab reads are none of these.
        for text in [
            &b"v 0 0 0\nf 1 2 3\n"[..],
            b"[camera]\neye = [0, 0, 5]\n",
            b"{ }",
            b"",
        ] {
            assert_eq!(
                known_format(text),
                None,
                "{}",
                String::from_utf8_lossy(text)
            );
        }
    }

    #[test]
    fn the_message_names_the_file_and_both_formats() {
        let message = not_the_format(Path::new("models/x.ply"), "a PLY file", "OBJ");
        assert_eq!(message, "x.ply is a PLY file, not OBJ");
    }
}
