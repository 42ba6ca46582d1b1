//! [`SceneError`]: what is wrong with a scene file and where, printed the way a compiler prints
//! its messages (`file:line:column: message`, then the offending line with a caret under it).
//! What it prints is text a terminal shows as it is: a control character from a binary file
//! is printed escaped (`\u{1b}`), never as itself.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::shapes::MAX_CSG_DEPTH;

/// An error in a scene file, located at the offending value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file, or the name a built-in scene goes by.
    pub file: PathBuf,
    /// 1-based line of the offending value (1 when the file could not be read at all).
    pub line: usize,
    /// 1-based column of the offending value, counted in characters.
    pub column: usize,
    /// What is wrong, and what was expected instead.
    pub message: String,
    /// The offending line, shown under the message; `None` when there is no text to show.
    pub source_line: Option<String>,
    /// How many characters from `column` on the caret underlines (at least 1).
    pub underline: usize,
    /// The offset of an error in a binary file, which has no lines: then the message is
    /// printed `file: byte N: message`.
    pub byte: Option<usize>,
}

impl SceneError {
    /// An error about the file as a whole (it cannot be read), placed at its start.
    pub fn whole_file(file: &Path, message: impl Into<String>) -> SceneError {
        SceneError {
            file: file.to_path_buf(),
            line: 1,
            column: 1,
            message: message.into(),
            source_line: None,
            underline: 1,
            byte: None,
        }
    }

    /// An error at byte `offset` of a binary file.
    pub fn at_byte(file: &Path, offset: usize, message: impl Into<String>) -> SceneError {
        SceneError {
            byte: Some(offset),
            ..SceneError::whole_file(file, message)
        }
    }

    /// An error at `line` and `column` (1-based; 0, as serde_json gives at a line's start, is
    /// taken for 1) of a text file whose bytes are `bytes`, the line shown under the message
    /// (each byte that is not UTF-8 as U+FFFD).
    pub fn at_line(
        file: &Path,
        bytes: &[u8],
        line: usize,
        column: usize,
        message: impl Into<String>,
    ) -> SceneError {
        let text = bytes
            .split(|&b| b == b'\n')
            .nth(line.saturating_sub(1))
            .unwrap_or_default();
        let text = String::from_utf8_lossy(text)
            .trim_end_matches('\r')
            .to_string();
        SceneError {
            line: line.max(1),
            column: column.max(1),
            source_line: Some(text),
            ..SceneError::whole_file(file, message)
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let message: String = self
            .message
            .split('\n')
            .map(printable)
            .collect::<Vec<_>>()
            .join("\n");
        let file = printable(&self.file.display().to_string());
        if let Some(byte) = self.byte {
            return write!(f, "{file}: byte {byte}: {message}");
        }
        write!(f, "{file}:{}:{}: {message}", self.line, self.column,)?;
        if let Some(source_line) = &self.source_line {
            let number = self.line.to_string();
            let gutter = " ".repeat(number.len());
            let (source_line, column) = shown_part(source_line, self.column);
            let source_line = source_line.as_str();
            let before: String = source_line.chars().take(column - 1).collect();
            let marked: String = source_line
                .chars()
                .skip(column - 1)
                .take(self.underline.min(SHOWN_LINE / 2))
                .collect();
            // Tabs stay tabs under the line so that the caret lines up in any terminal.
            let indent: String = printable(&before)
                .chars()
                .map(|c| if c == '\t' { '\t' } else { ' ' })
                .collect();
            let underline = printable(&marked).chars().count().max(1);
            write!(
                f,
                "\n{gutter} |\n{number} | {}\n{gutter} | {indent}{}",
                printable(source_line),
                "^".repeat(underline)
            )?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneError {}

/// How deeply the `toml` crate lets tables and arrays nest in a file it reads.
pub const TOML_NESTING_LIMIT: u32 = 80;

/// The most characters of the offending line shown under a message: a longer line is shown
/// around the column, cut short at either end with `…`.
const SHOWN_LINE: usize = 100;

/// The characters `line` shows under a message at 1-based `column`: the whole line, or
/// [`SHOWN_LINE`] of them around the column; and the column within what is shown.
fn shown_part(line: &str, column: usize) -> (String, usize) {
    let count = line.chars().count();
    if count <= SHOWN_LINE {
        return (line.to_string(), column);
    }
    let start = column
        .saturating_sub(SHOWN_LINE / 2)
        .min(count - SHOWN_LINE);
    let part: String = line.chars().skip(start).take(SHOWN_LINE).collect();
    let before = if start > 0 { "…" } else { "" };
    let after = if start + SHOWN_LINE < count {
        "…"
    } else {
        ""
    };
    let shown_column = column - start + before.chars().count();
    (format!("{before}{part}{after}"), shown_column)
}

/// `text` with each control character but the tab escaped as Rust writes it (`\u{0}`, `\r`),
/// so that bytes read from a binary file cannot move a terminal's cursor or change its colours.
pub fn printable(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() && c != '\t' {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// A scene file's text and the name it goes by: what byte spans are turned into lines and
/// columns against.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Source<'a> {
    pub origin: &'a Path,
    pub text: &'a str,
}

impl Source<'_> {
    /// An error at the byte span `span` of the text.
    pub fn error(&self, span: Range<usize>, message: impl Into<String>) -> SceneError {
        let text = self.text;
        let start = text.floor_char_boundary(span.start.min(text.len()));
        let end = text.floor_char_boundary(span.end.clamp(start, text.len()));
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        let source_line = text[line_start..line_end].trim_end_matches('\r');
        let column = text[line_start..start].chars().count() + 1;
        let underline = text[start..end.min(line_end)]
            .trim_end_matches('\r')
            .chars()
            .count()
            .max(1);
        SceneError {
            file: self.origin.to_path_buf(),
            line: text[..start].matches('\n').count() + 1,
            column,
            message: message.into(),
            source_line: Some(source_line.to_string()),
            underline,
            byte: None,
        }
    }

    /// A TOML syntax error, or an error serde raised while reading the schema.
    pub fn toml_error(&self, error: &toml::de::Error) -> SceneError {
        let message = error.message().trim();
        let message = if message.contains("max recursion depth") {
            format!(
                "tables and arrays are nested more than {TOML_NESTING_LIMIT} deep, the TOML \
                 reader's limit (csg objects nest at most {MAX_CSG_DEPTH} deep)"
            )
        } else {
            message.to_string()
        };
        self.error(error.span().unwrap_or(0..0), message)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn source(text: &str) -> Source<'_> {
        Source {
            origin: Path::new("demo.toml"),
            text,
        }
    }

    #[test]
    fn spans_become_one_based_lines_and_columns() {
        let text = "a = 1\nradius = -1\n";
        let error = source(text).error(15..17, "radius must be positive");
        assert_eq!((error.line, error.column, error.underline), (2, 10, 2));
        assert_eq!(error.source_line.as_deref(), Some("radius = -1"));
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        let text = "name = \"é\" x";
        let error = source(text).error(12..13, "stray");
        assert_eq!(error.column, 12);
    }

    #[test]
    fn display_shows_the_line_and_a_caret() {
        let error = source("a = 1\nradius = -1\n").error(15..17, "radius must be positive");
        assert_eq!(
            error.to_string(),
            "demo.toml:2:10: radius must be positive\n  |\n2 | radius = -1\n  |          ^^"
        );
    }

    #[test]
    fn spans_past_the_end_or_inside_a_character_are_clamped() {
        let text = "é";
        let error = source(text).error(1..99, "odd span");
        assert_eq!((error.line, error.column), (1, 1));
        let error = source(text).error(50..60, "past the end");
        assert_eq!((error.line, error.column), (1, 2));
    }

    #[test]
    fn control_characters_are_printed_escaped_and_the_caret_still_lines_up() {
        let error = source("a = \u{1b}[31m\u{0}x\n").error(9..10, "stray");
        let printed = error.to_string();
        assert!(
            !printed.contains('\u{1b}') && !printed.contains('\u{0}'),
            "{printed}"
        );
        let lines: Vec<&str> = printed.lines().collect();
        assert_eq!(lines[2], "1 | a = \\u{1b}[31m\\u{0}x");
        let caret = lines[3].find('^').unwrap();
        assert_eq!(caret, lines[2].find("\\u{0}").unwrap(), "{printed}");
        assert_eq!(lines[3][caret..].trim_end(), "^^^^^");
    }

    #[test]
    fn a_long_line_is_shown_around_the_column() {
        let text = format!("a = [{}]\n", "1, ".repeat(500));
        let error = source(&text).error(1000..1001, "here");
        let printed = error.to_string();
        let lines: Vec<&str> = printed.lines().collect();
        assert!(lines[2].chars().count() < 120, "{printed}");
        assert!(
            lines[2].starts_with("1 | …") && lines[2].ends_with('…'),
            "{printed}"
        );
        let caret = lines[3].chars().position(|c| c == '^').unwrap();
        let at: String = lines[2].chars().skip(caret).take(3).collect();
        assert_eq!(
            at,
            text.chars().skip(1000).take(3).collect::<String>(),
            "{printed}"
        );
    }

    #[test]
    fn whole_file_errors_have_no_source_line() {
        let error = SceneError::whole_file(Path::new("gone.toml"), "cannot read it");
        assert_eq!(error.to_string(), "gone.toml:1:1: cannot read it");
    }
}
