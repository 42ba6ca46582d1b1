//! Seeded mutations of scene texts, for the tests that feed broken files to a reader: a failure
//! can be replayed from its seed.

/// xorshift64*: a small deterministic generator.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// `text` with one to four random edits: characters from `alphabet` deleted, inserted or
/// replaced, two lines swapped, the text cut short, or a stretch of it copied elsewhere.
pub fn mutate(text: &str, rng: &mut Rng, alphabet: &[char]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for _ in 0..1 + rng.below(4) {
        let at = rng.below(chars.len() + 1);
        match rng.below(6) {
            0 if at < chars.len() => {
                chars.remove(at);
            }
            1 => chars.insert(at, alphabet[rng.below(alphabet.len())]),
            2 if at < chars.len() => chars[at] = alphabet[rng.below(alphabet.len())],
            3 => {
                let text: String = chars.iter().collect();
                let mut lines: Vec<&str> = text.lines().collect();
                if lines.len() > 1 {
                    let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
                    lines.swap(a, b);
                }
                chars = lines.join("\n").chars().collect();
            }
            4 => chars.truncate(at),
            _ => {
                // Copy a stretch of the text elsewhere: duplicated keys, tables or entities.
                let from = rng.below(chars.len());
                let len = rng.below(40).min(chars.len() - from);
                let piece: Vec<char> = chars[from..from + len].to_vec();
                let at = at.min(chars.len());
                chars.splice(at..at, piece);
            }
        }
    }
    chars.into_iter().collect()
}
