//! Splitting NFF text into tokens: runs of characters between whitespace, wherever the line
//! breaks fall (SPD writes a whole `c` on one line, the format's description on three). A `#`
//! starts a comment that runs to the end of its line. Tokens borrow the text; nothing is copied.

use std::ops::Range;

/// A token and where it starts in the text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Token<'a> {
    pub text: &'a str,
    pub start: usize,
}

impl Token<'_> {
    /// The token's byte range in the text.
    pub fn span(&self) -> Range<usize> {
        self.start..self.start + self.text.len()
    }
}

/// The tokens of a text, in order.
#[derive(Clone, Debug)]
pub(crate) struct Tokens<'a> {
    text: &'a str,
    position: usize,
}

impl<'a> Tokens<'a> {
    pub fn new(text: &'a str) -> Self {
        Tokens { text, position: 0 }
    }
}

impl<'a> Iterator for Tokens<'a> {
    type Item = Token<'a>;

    fn next(&mut self) -> Option<Token<'a>> {
        let bytes = self.text.as_bytes();
        let mut i = self.position;
        loop {
            match bytes.get(i)? {
                b if b.is_ascii_whitespace() => i += 1,
                b'#' => {
                    i += bytes[i..]
                        .iter()
                        .position(|&b| b == b'\n')
                        .unwrap_or(bytes.len() - i);
                }
                _ => break,
            }
        }
        let start = i;
        while i < bytes.len() && !bytes[i].is_ascii_whitespace() && bytes[i] != b'#' {
            i += 1;
        }
        self.position = i;
        // Tokens end only at ASCII bytes, so both ends are character boundaries.
        Some(Token {
            text: &self.text[start..i],
            start,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(text: &str) -> Vec<&str> {
        Tokens::new(text).map(|t| t.text).collect()
    }

    #[test]
    fn splits_on_any_whitespace_and_skips_comments() {
        assert_eq!(
            texts("# header\nc 0 0 0 1\t0 0 1 1 # a cone\r\ns 1e-3 -2 +3 .5#tail\n"),
            [
                "c", "0", "0", "0", "1", "0", "0", "1", "1", "s", "1e-3", "-2", "+3", ".5"
            ]
        );
        assert!(texts("  \n# only a comment").is_empty());
    }

    #[test]
    fn tokens_know_where_they_start() {
        let tokens: Vec<Token> = Tokens::new("p 3\n  é1 x").collect();
        assert_eq!(tokens[2].text, "é1");
        assert_eq!(tokens[2].span(), 6..9);
        assert_eq!(tokens[3].start, 10);
    }
}
