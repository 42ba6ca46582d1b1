//! `def` and `use`, SDL's macros, as the book has them: `def NAME { … }` keeps the tokens up to
//! the first `}` (braces do not nest), and `use NAME` splices them in front of the rest of the
//! input, to be read with whatever transform and material are current there. Unlike the book,
//! a `def` that uses itself (directly or through others) is an error, and expansion is bounded
//! ([`MAX_USE_DEPTH`], [`MAX_EXPANDED_TOKENS`]), so no file expands forever or without bound.

use std::borrow::Cow;
use std::collections::HashMap;
use std::ops::Range;
use std::rc::Rc;

use super::lexer::{Lexer, Token};
use crate::formats::{SceneError, Source};

/// How many `use`s may be open inside one another.
pub const MAX_USE_DEPTH: usize = 64;

/// How many tokens all the `use`s of a file may splice in, together.
pub const MAX_EXPANDED_TOKENS: usize = 1_000_000;

/// A token with the `use`s it was spliced in by, if any.
#[derive(Clone, Debug)]
pub(crate) struct Word<'a> {
    pub token: Token<'a>,
    /// The `use` that spliced it in, innermost first; `None` for the file's own text.
    pub context: Option<Rc<Expansion>>,
}

/// A `use` being expanded: the `def`'s name, where the name after `use` stands, and the `use`
/// this one was spliced in by. Turned into words only for an error message.
#[derive(Debug)]
pub(crate) struct Expansion {
    name: String,
    used_at: Range<usize>,
    outer: Option<Rc<Expansion>>,
}

impl Word<'_> {
    pub fn text(&self) -> &str {
        &self.token.text
    }
}

/// A `def` being read out: its name, its body and how far it has been read.
#[derive(Debug)]
struct Frame<'a> {
    body: Rc<[Token<'a>]>,
    next: usize,
    context: Rc<Expansion>,
}

/// A definition: its body and where its name stands.
#[derive(Debug)]
struct Def<'a> {
    body: Rc<[Token<'a>]>,
    at: Range<usize>,
}

/// The token stream the parser reads: the file's tokens with every `use` expanded.
#[derive(Debug)]
pub(crate) struct Tokens<'a> {
    source: Source<'a>,
    lexer: Lexer<'a>,
    defs: HashMap<String, Def<'a>>,
    frames: Vec<Frame<'a>>,
    expanded: usize,
}

impl<'a> Tokens<'a> {
    pub fn new(source: Source<'a>) -> Self {
        Tokens {
            source,
            lexer: Lexer::new(source.text),
            defs: HashMap::new(),
            frames: Vec::new(),
            expanded: 0,
        }
    }

    /// The next token, from the innermost open `use` or else from the file; `None` at the end.
    pub fn next(&mut self) -> Option<Word<'a>> {
        while let Some(frame) = self.frames.last_mut() {
            if let Some(token) = frame.body.get(frame.next) {
                frame.next += 1;
                return Some(Word {
                    token: token.clone(),
                    context: Some(frame.context.clone()),
                });
            }
            self.frames.pop();
        }
        self.lexer.next().map(|token| Word {
            token,
            context: None,
        })
    }

    /// The text of the token [`Self::next`] would give, without reading it.
    pub fn peek(&self) -> Option<Cow<'a, str>> {
        let spliced = self.frames.iter().rev().find_map(|f| f.body.get(f.next));
        match spliced {
            Some(token) => Some(token.text.clone()),
            None => self.lexer.clone().next().map(|token| token.text),
        }
    }

    /// An error at `word`, naming the `def`s it was spliced in from.
    pub fn error(&self, word: &Word, message: impl Into<String>) -> SceneError {
        let mut message = message.into();
        let mut expansion = word.context.as_deref();
        let mut separator = " (";
        while let Some(e) = expansion {
            let at = self.place(e.used_at.clone());
            message += &format!("{separator}in def `{}`, used at {at}", e.name);
            separator = ", ";
            expansion = e.outer.as_deref();
        }
        if word.context.is_some() {
            message += ")";
        }
        self.source.error(word.token.span.clone(), message)
    }

    /// "line L, column C" of a place in the file.
    fn place(&self, span: Range<usize>) -> String {
        let at = self.source.error(span, "");
        format!("line {}, column {}", at.line, at.column)
    }

    /// Reads the rest of `def`, whose keyword was `keyword`: a name, `{`, and the body up to the
    /// first `}`.
    pub fn define(&mut self, keyword: &Word<'a>) -> Result<(), SceneError> {
        let name = self.next().ok_or_else(|| {
            self.error(
                keyword,
                "expected a name after `def`, found the end of the file",
            )
        })?;
        if !is_identifier(name.text()) {
            return Err(self.error(
                &name,
                format!(
                    "expected a name after `def` (a letter, then letters, digits or `.`), found `{}`",
                    name.text()
                ),
            ));
        }
        if let Some(def) = self.defs.get(name.text()) {
            let first = self.place(def.at.clone());
            return Err(self.error(
                &name,
                format!("`{}` is already defined (at {first})", name.text()),
            ));
        }
        match self.next() {
            Some(open) if open.text() == "{" => {}
            Some(other) => {
                return Err(self.error(
                    &other,
                    format!(
                        "expected `{{` after `def {}`, found `{}`",
                        name.text(),
                        other.text()
                    ),
                ));
            }
            None => {
                return Err(self.error(
                    &name,
                    format!(
                        "expected `{{` after `def {}`, found the end of the file",
                        name.text()
                    ),
                ));
            }
        }
        let mut body = Vec::new();
        loop {
            match self.next() {
                Some(word) if word.text() == "}" => break,
                Some(word) => body.push(word.token),
                None => {
                    return Err(
                        self.error(&name, format!("`def {}` has no closing `}}`", name.text()))
                    );
                }
            }
        }
        let at = name.token.span.clone();
        self.defs.insert(
            name.token.text.into_owned(),
            Def {
                body: body.into(),
                at,
            },
        );
        Ok(())
    }

    /// Reads the rest of `use`: a defined name, whose body is read next.
    pub fn expand(&mut self, keyword: &Word<'a>) -> Result<(), SceneError> {
        let name = self.next().ok_or_else(|| {
            self.error(
                keyword,
                "expected a name after `use`, found the end of the file",
            )
        })?;
        let Some(def) = self.defs.get(name.text()) else {
            let known: Vec<&str> = self.defs.keys().map(String::as_str).collect();
            let hint = super::suggest::did_you_mean(name.text(), known);
            return Err(self.error(
                &name,
                format!(
                    "`{}` is not defined (by a `def` before this `use`){hint}",
                    name.text()
                ),
            ));
        };
        if let Some(open) = self
            .frames
            .iter()
            .position(|f| f.context.name == name.text())
        {
            let mut chain: Vec<&str> = self.frames[open..]
                .iter()
                .map(|f| f.context.name.as_str())
                .collect();
            chain.push(name.text());
            return Err(self.error(
                &name,
                format!(
                    "`{}` uses itself ({}), which would expand forever",
                    name.text(),
                    chain.join(" → ")
                ),
            ));
        }
        if self.frames.len() >= MAX_USE_DEPTH {
            return Err(self.error(
                &name,
                format!(
                    "more than {MAX_USE_DEPTH} `use`s open inside one another (raylab's limit)"
                ),
            ));
        }
        self.expanded += def.body.len();
        if self.expanded > MAX_EXPANDED_TOKENS {
            return Err(self.error(
                &name,
                format!(
                    "the `use`s expand to more than {MAX_EXPANDED_TOKENS} tokens (raylab's limit)"
                ),
            ));
        }
        let body = def.body.clone();
        self.frames.push(Frame {
            body,
            next: 0,
            context: Rc::new(Expansion {
                name: name.token.text.into_owned(),
                used_at: name.token.span.clone(),
                outer: name.context.clone(),
            }),
        });
        Ok(())
    }
}

/// The book's `isidentifier`: a letter, then letters, digits or `.`.
fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '.')
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn words(text: &str) -> Result<Vec<String>, SceneError> {
        let mut tokens = Tokens::new(Source {
            origin: Path::new("t.sdl"),
            text,
        });
        let mut out = Vec::new();
        while let Some(word) = tokens.next() {
            match word.text() {
                "def" => tokens.define(&word)?,
                "use" => tokens.expand(&word)?,
                _ => out.push(word.text().to_string()),
            }
        }
        Ok(out)
    }

    #[test]
    fn use_splices_the_body_in_and_may_name_later_defs() {
        assert_eq!(
            words("def a { x use b } def b {y} use a z").unwrap(),
            ["x", "y", "z"]
        );
    }

    #[test]
    fn braces_do_not_nest() {
        // The body of `a` is `def b { q`; the `}` after it is left over, and `use a` takes the
        // next `}` to close `b`.
        assert_eq!(
            words("def a { def b { q } } use a } use b").unwrap(),
            ["}", "q"]
        );
    }

    #[test]
    fn a_def_that_uses_itself_is_an_error() {
        let error = words("def a { use b }\ndef b { sphere use a }\nuse a").unwrap_err();
        assert!(
            error.message.contains("`a` uses itself (a → b → a)"),
            "{error}"
        );
        assert_eq!((error.line, error.column), (2, 20));
        assert!(error.message.contains("in def `b`"), "{error}");
    }

    #[test]
    fn exponential_expansion_stops_at_the_limit() {
        let mut text = String::from("def d0 { x x }\n");
        for i in 1..40 {
            text += &format!("def d{i} {{ use d{} use d{} }}\n", i - 1, i - 1);
        }
        text += "use d39";
        let error = words(&text).unwrap_err();
        assert!(error.message.contains("1000000 tokens"), "{error}");
    }

    #[test]
    fn names_are_checked() {
        let error = words("def 3x { }").unwrap_err();
        assert_eq!((error.line, error.column), (1, 5));
        let error = words("def a { }\ndef a { }").unwrap_err();
        assert!(
            error
                .message
                .contains("already defined (at line 1, column 5)"),
            "{error}"
        );
        let error = words("def a sphere").unwrap_err();
        assert!(
            error.message.contains("expected `{` after `def a`"),
            "{error}"
        );
        let error = words("def red { }\nuse rde").unwrap_err();
        assert!(error.message.contains("did you mean `red`?"), "{error}");
        assert_eq!((error.line, error.column), (2, 5));
    }
}
