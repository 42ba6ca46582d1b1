//! Splitting SDL text into tokens the way the book's `Scene::nexttoken` does: whitespace
//! separates tokens, `{` and `}` are tokens of their own even when glued to a word (`bar{`,
//! `pop}`, `}def`), and `!` starts a comment anywhere, even inside a word, that runs to the end
//! of its line and swallows the line break, so the word goes on with the next line's first
//! characters (`cube!note⏎sphere` is the one word `cubesphere`, as in the book).

use std::borrow::Cow;
use std::ops::Range;

/// A token and where its first character lies in the text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Token<'a> {
    pub text: Cow<'a, str>,
    /// Where the token starts, and its first piece ends (a comment may cut it in two).
    pub span: Range<usize>,
}

/// The book's whitespace: space, tab, the line breaks, vertical tab, form feed, bell, backspace.
fn is_space(c: u8) -> bool {
    matches!(c, b' ' | b'\t' | b'\n' | b'\r' | 0x0b | 0x0c | 0x07 | 0x08)
}

/// The tokens of a text, in order.
#[derive(Clone, Debug)]
pub(crate) struct Lexer<'a> {
    text: &'a str,
    position: usize,
}

impl<'a> Lexer<'a> {
    pub fn new(text: &'a str) -> Self {
        Lexer { text, position: 0 }
    }

    /// Skips a comment that starts at `i` (a `!`), its line break included.
    fn after_comment(&self, i: usize) -> usize {
        self.text[i..]
            .find('\n')
            .map_or(self.text.len(), |n| i + n + 1)
    }
}

impl<'a> Iterator for Lexer<'a> {
    type Item = Token<'a>;

    fn next(&mut self) -> Option<Token<'a>> {
        let bytes = self.text.as_bytes();
        let mut i = self.position;
        loop {
            match bytes.get(i)? {
                &b if is_space(b) => i += 1,
                b'!' => i = self.after_comment(i),
                _ => break,
            }
        }
        let start = i;
        if matches!(bytes[i], b'{' | b'}') {
            self.position = i + 1;
            return Some(Token {
                text: Cow::Borrowed(&self.text[i..i + 1]),
                span: i..i + 1,
            });
        }
        // The token's pieces: more than one only when comments cut it.
        let mut text: Cow<'a, str> = Cow::Borrowed("");
        let mut first_end = None;
        let mut piece = i;
        loop {
            let end_of_piece =
                i >= bytes.len() || is_space(bytes[i]) || matches!(bytes[i], b'{' | b'}' | b'!');
            if end_of_piece {
                // Pieces end only at ASCII bytes, so both ends are character boundaries.
                let part = &self.text[piece..i];
                text = if text.is_empty() {
                    Cow::Borrowed(part)
                } else {
                    Cow::Owned(text.into_owned() + part)
                };
                first_end.get_or_insert(i);
                if bytes.get(i) == Some(&b'!') {
                    i = self.after_comment(i);
                    piece = i;
                    continue;
                }
                break;
            }
            i += 1;
        }
        self.position = i;
        Some(Token {
            text,
            span: start..first_end.unwrap_or(i),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(text: &str) -> Vec<String> {
        Lexer::new(text).map(|t| t.text.into_owned()).collect()
    }

    #[test]
    fn braces_are_tokens_even_when_glued_to_words() {
        assert_eq!(
            texts("def bar{ pop}def x{sphere}"),
            [
                "def", "bar", "{", "pop", "}", "def", "x", "{", "sphere", "}"
            ]
        );
    }

    #[test]
    fn bangs_start_comments_anywhere() {
        assert_eq!(
            texts("! header\nlight 1 2 3 ! a light\n  sphere"),
            ["light", "1", "2", "3", "sphere"]
        );
        assert_eq!(texts("use cube1!The center\n pop"), ["use", "cube1", "pop"]);
    }

    #[test]
    fn a_comment_inside_a_word_glues_the_next_line_on() {
        let tokens: Vec<Token> = Lexer::new("x cube!note\nsphere y").collect();
        assert_eq!(tokens[1].text, "cubesphere");
        assert_eq!(tokens[1].span, 2..6);
        assert_eq!(tokens[2].text, "y");
    }

    #[test]
    fn every_book_whitespace_separates() {
        assert_eq!(
            texts("a\tb\r\nc\x0bd\x0ce\x07f\x08g"),
            ["a", "b", "c", "d", "e", "f", "g"]
        );
        assert!(texts(" \n! only a comment").is_empty());
    }
}
