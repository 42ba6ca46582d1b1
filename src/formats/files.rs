//! Where a scene's texture and OBJ files come from: a folder on disk (relative to the scene
//! file), or files held in memory (those built into the binary for the built-in scenes); and
//! how the bytes of a text file (a scene, NFF, OBJ or MTL file) become text.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use super::error::{SceneError, Source};

/// The source of the files a scene names.
#[derive(Clone, Copy, Debug)]
pub enum SceneFiles<'a> {
    /// Files on disk; names are relative to this folder.
    Folder(&'a Path),
    /// Files held in memory (compiled into the binary for the built-in scenes), by the name
    /// the scene uses.
    Builtin(&'a [(&'a str, &'a [u8])]),
}

impl<'a> SceneFiles<'a> {
    /// The path that `name` stands for, for messages and for finding files next to it.
    pub fn path(&self, name: &str) -> PathBuf {
        match self {
            SceneFiles::Folder(folder) => folder.join(name),
            SceneFiles::Builtin(_) => PathBuf::from(name),
        }
    }

    /// The bytes of the file at `path` (as returned by [`Self::path`] or a path beside it).
    pub fn read(&self, path: &Path) -> Result<Cow<'a, [u8]>, String> {
        match self {
            SceneFiles::Folder(_) => crate::memory::read_file(path).map(Cow::Owned),
            SceneFiles::Builtin(files) => files
                .iter()
                .find(|(name, _)| Path::new(name) == path)
                .map(|(_, bytes)| Cow::Borrowed(*bytes))
                .ok_or_else(|| "no such built-in file".to_string()),
        }
    }
}

/// The UTF-8 byte-order mark that some editors put at the start of a text file.
const BYTE_ORDER_MARK: &[u8] = "\u{feff}".as_bytes();

/// ^Z, which DOS programs wrote at the end of a text file.
const DOS_END_OF_FILE: u8 = 0x1a;

/// A text file's bytes without a byte-order mark at the start and ^Z marks at the end.
fn without_marks(bytes: &[u8]) -> &[u8] {
    let bytes = bytes.strip_prefix(BYTE_ORDER_MARK).unwrap_or(bytes);
    let end = bytes
        .iter()
        .rposition(|&b| b != DOS_END_OF_FILE)
        .map_or(0, |i| i + 1);
    &bytes[..end]
}

/// The text of a file in an ASCII format (NFF, OBJ, MTL), which any byte may appear in: a
/// byte-order mark at the start and ^Z marks at the end are dropped, and each byte that is not
/// UTF-8 (a Latin-1 `é` in a comment) becomes one U+FFFD, so that it is one character in its
/// column and a reader that meets it outside a comment reports it there.
pub fn ascii_text(bytes: &[u8]) -> Cow<'_, str> {
    let bytes = without_marks(bytes);
    // Checking that it is all UTF-8 first is several times faster than the lossy conversion.
    match std::str::from_utf8(bytes) {
        Ok(text) => Cow::Borrowed(text),
        Err(_) => String::from_utf8_lossy(bytes),
    }
}

/// The text of a TOML file, which must be UTF-8: a byte-order mark at the start and ^Z marks at
/// the end are dropped; a byte that is not UTF-8 is an error at its line and column.
pub fn utf8_text<'a>(bytes: &'a [u8], origin: &Path) -> Result<&'a str, SceneError> {
    let bytes = without_marks(bytes);
    std::str::from_utf8(bytes).map_err(|e| {
        let text = String::from_utf8_lossy(bytes);
        let at = e.valid_up_to();
        Source {
            origin,
            text: &text,
        }
        .error(
            at..at + 1,
            "this byte is not UTF-8 text; a scene file must be saved as UTF-8",
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn marks_at_the_ends_are_dropped() {
        assert_eq!(ascii_text(b"\xef\xbb\xbfs 0 0 0 1\n\x1a"), "s 0 0 0 1\n");
        assert_eq!(ascii_text(b"s 1\x1a\x1a"), "s 1");
        assert_eq!(ascii_text(b"\x1a"), "");
        // Only at the ends: a mark inside stays for the reader to report.
        assert_eq!(ascii_text(b"a\x1ab"), "a\x1ab");
    }

    #[test]
    fn each_byte_that_is_not_utf8_becomes_one_character() {
        let text = ascii_text(b"# caf\xe9\ns 0\xe9 0");
        assert_eq!(text, "# caf\u{fffd}\ns 0\u{fffd} 0");
    }

    #[test]
    fn toml_text_must_be_utf8_and_is_told_where_it_is_not() {
        let origin = Path::new("scene.toml");
        assert_eq!(
            utf8_text(b"\xef\xbb\xbfa = 1\n", origin).unwrap(),
            "a = 1\n"
        );
        let error = utf8_text(b"a = 1\n# caf\xe9 au lait\n", origin).unwrap_err();
        assert_eq!((error.line, error.column), (2, 6), "{error}");
        assert!(error.message.contains("not UTF-8"), "{error}");
    }
}
