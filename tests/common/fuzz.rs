//! Seeded mutations of scene texts, for the tests that feed broken files to a reader: a failure
//! can be replayed from its seed.

use super::random::Rng;

/// `text` with one to four random edits: characters from `alphabet` deleted, inserted or
/// replaced, two lines swapped, the text cut short, or a stretch of it copied elsewhere.
pub fn mutate(text: &str, rng: &mut Rng, alphabet: &[char]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for _ in 0..1 + rng.usize(..4) {
        let at = rng.usize(..=chars.len());
        match rng.usize(..6) {
            0 if at < chars.len() => {
                chars.remove(at);
            }
            1 => chars.insert(at, alphabet[rng.usize(..alphabet.len())]),
            2 if at < chars.len() => chars[at] = alphabet[rng.usize(..alphabet.len())],
            3 => {
                let text: String = chars.iter().collect();
                let mut lines: Vec<&str> = text.lines().collect();
                if lines.len() > 1 {
                    let (a, b) = (rng.usize(..lines.len()), rng.usize(..lines.len()));
                    lines.swap(a, b);
                }
                chars = lines.join("\n").chars().collect();
            }
            4 => chars.truncate(at),
            _ => {
                // Copy a stretch of the text elsewhere: duplicated keys, tables or entities.
                let from = rng.usize(..=chars.len());
                let len = rng.usize(..40).min(chars.len() - from);
                let piece: Vec<char> = chars[from..from + len].to_vec();
                let at = at.min(chars.len());
                chars.splice(at..at, piece);
            }
        }
    }
    chars.into_iter().collect()
}
