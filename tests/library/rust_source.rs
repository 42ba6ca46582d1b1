//! Reading the crate's Rust source as the tests of its structure need it: the text with
//! comments and literals blanked, its tokens, and the tokens left once test code is taken out.

use std::fs;
use std::path::{Path, PathBuf};

/// The crate's `src/` folder.
pub fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The `.rs` files in `folder` and the folders under it, sorted (none when it does not exist).
pub fn rust_files_under(folder: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut folders = vec![folder.to_path_buf()];
    while let Some(folder) = folders.pop() {
        let Ok(entries) = fs::read_dir(&folder) else {
            continue;
        };
        for entry in entries {
            let path = entry.unwrap().path();
            if path.is_dir() {
                folders.push(path);
            } else if path.extension().is_some_and(|ext| ext == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// The text of the file at `path`.
pub fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

/// `text` with its comments, string literals and character literals blanked out (lines kept).
pub fn code_only(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |out: &mut String, from: usize, to: usize| {
        for &ch in &c[from..to.min(c.len())] {
            out.push(if ch == '\n' { '\n' } else { ' ' });
        }
    };
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let ident_char = |ch: char| ch.is_alphanumeric() || ch == '_';
    let mut i = 0;
    while i < c.len() {
        let end = if at(i) == '/' && at(i + 1) == '/' {
            (i..c.len()).find(|&j| c[j] == '\n').unwrap_or(c.len())
        } else if at(i) == '/' && at(i + 1) == '*' {
            let (mut j, mut depth) = (i + 2, 1);
            while j < c.len() && depth > 0 {
                if at(j) == '/' && at(j + 1) == '*' {
                    (depth, j) = (depth + 1, j + 2);
                } else if at(j) == '*' && at(j + 1) == '/' {
                    (depth, j) = (depth - 1, j + 2);
                } else {
                    j += 1;
                }
            }
            j
        } else if at(i) == '"' {
            let mut j = i + 1;
            while j < c.len() && c[j] != '"' {
                j += if c[j] == '\\' { 2 } else { 1 };
            }
            j + 1
        } else if (at(i) == 'r' || (at(i) == 'b' && at(i + 1) == 'r'))
            && (i == 0 || !ident_char(c[i - 1]))
            && {
                let r = if at(i) == 'r' { i } else { i + 1 };
                let hashes = (r + 1..c.len()).take_while(|&j| c[j] == '#').count();
                at(r + 1 + hashes) == '"'
            }
        {
            // A raw string: r"…", r#"…"#, br"…".
            let r = if at(i) == 'r' { i } else { i + 1 };
            let hashes = (r + 1..c.len()).take_while(|&j| c[j] == '#').count();
            let mut j = r + hashes + 2;
            while j < c.len() && !(c[j] == '"' && (1..=hashes).all(|h| at(j + h) == '#')) {
                j += 1;
            }
            j + 1 + hashes
        } else if at(i) == '\'' && at(i + 1) == '\\' {
            // An escaped character literal: '\n', '\'', '\u{7f}'.
            (i + 3..c.len())
                .find(|&j| c[j] == '\'')
                .map_or(c.len(), |j| j + 1)
        } else if at(i) == '\'' && at(i + 2) == '\'' {
            i + 3
        } else {
            out.push(c[i]);
            i += 1;
            continue;
        };
        blank(&mut out, i, end);
        i = end;
    }
    out
}

/// A word, `::` or another character of code, with its line.
#[derive(Clone, Debug)]
pub struct Token {
    pub text: String,
    pub line: usize,
}

/// Whether a token is a word (a name or a keyword).
pub fn is_ident(text: &str) -> bool {
    text.starts_with(|ch: char| ch.is_alphabetic() || ch == '_')
}

/// The tokens of code without comments or literals: words, `::` and single other characters.
pub fn tokens(code: &str) -> Vec<Token> {
    let c: Vec<char> = code.chars().collect();
    let mut tokens = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < c.len() {
        let ch = c[i];
        let len = if ch == '\n' {
            line += 1;
            i += 1;
            continue;
        } else if ch.is_whitespace() {
            i += 1;
            continue;
        } else if ch.is_alphanumeric() || ch == '_' {
            (i..c.len())
                .take_while(|&j| c[j].is_alphanumeric() || c[j] == '_')
                .count()
        } else if ch == ':' && c.get(i + 1) == Some(&':') {
            2
        } else {
            1
        };
        let text = c[i..i + len].iter().collect();
        tokens.push(Token { text, line });
        i += len;
    }
    tokens
}

/// Whether the tokens from `i` on are `texts`.
pub fn is(tokens: &[Token], i: usize, texts: &[&str]) -> bool {
    texts
        .iter()
        .enumerate()
        .all(|(k, text)| tokens.get(i + k).is_some_and(|t| t.text == *text))
}

/// The tokens left when the items under `#[cfg(test)]` are taken out, and the modules declared
/// as `#[cfg(test)] mod NAME;` (files that are test code). `None` for a file that is all test
/// code (`#![cfg(test)]`).
pub fn without_tests(mut tokens: Vec<Token>) -> Option<(Vec<Token>, Vec<String>)> {
    const CFG_TEST: [&str; 7] = ["#", "[", "cfg", "(", "test", ")", "]"];
    let mut test_modules = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        if is(&tokens, i, &["#", "!"]) && is(&tokens, i + 2, &CFG_TEST[1..]) {
            return None;
        }
        if !is(&tokens, i, &CFG_TEST) {
            i += 1;
            continue;
        }
        let mut k = i + CFG_TEST.len();
        // Further attributes of the same item.
        while is(&tokens, k, &["#", "["]) {
            let mut depth = 0;
            while k < tokens.len() {
                match tokens[k].text.as_str() {
                    "[" => depth += 1,
                    "]" => depth -= 1,
                    _ => {}
                }
                k += 1;
                if depth == 0 && tokens[k - 1].text == "]" {
                    break;
                }
            }
        }
        if tokens.get(k).is_some_and(|t| t.text == "mod") && is(&tokens, k + 2, &[";"]) {
            test_modules.push(tokens[k + 1].text.clone());
        }
        // The item (or field, or statement): to its `;` or `,`, or past its body's `}`.
        let mut depth = 0i32;
        while k < tokens.len() {
            match tokens[k].text.as_str() {
                "(" | "[" | "{" => depth += 1,
                ")" | "]" => depth -= 1,
                "}" => {
                    depth -= 1;
                    if depth == 0 {
                        k += 1;
                        break;
                    }
                }
                ";" | "," if depth == 0 => {
                    k += 1;
                    break;
                }
                _ => {}
            }
            if depth < 0 {
                break;
            }
            k += 1;
        }
        tokens.drain(i..k);
    }
    Some((tokens, test_modules))
}
