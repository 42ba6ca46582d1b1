//! Near-miss suggestions for misspelt words (`exponent` → did you mean `specularExponent`?).

/// `, did you mean `X`?` for the candidate most like `word`, or nothing when none is close.
/// A candidate is close when it is a few edits away, or when one word contains the other
/// (`exponent` is part of `specularExponent`).
pub(crate) fn did_you_mean<'c>(
    word: &str,
    candidates: impl IntoIterator<Item = &'c str>,
) -> String {
    let lower = word.to_ascii_lowercase();
    let score = |candidate: &str| {
        let candidate = candidate.to_ascii_lowercase();
        let similarity = strsim::normalized_damerau_levenshtein(&lower, &candidate);
        let contains =
            lower.len() >= 3 && (candidate.contains(&lower) || lower.contains(&candidate));
        if contains {
            similarity.max(0.7)
        } else {
            similarity
        }
    };
    candidates
        .into_iter()
        .map(|candidate| (score(candidate), candidate))
        .filter(|(score, _)| *score >= 0.6)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map_or_else(String::new, |(_, best)| format!(", did you mean `{best}`?"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn close_words_are_suggested_and_far_ones_not() {
        let keywords = ["specularExponent", "sphere", "specular", "scale"];
        assert_eq!(
            did_you_mean("exponent", keywords),
            ", did you mean `specularExponent`?"
        );
        assert_eq!(did_you_mean("shpere", keywords), ", did you mean `sphere`?");
        assert_eq!(did_you_mean("Sphere", keywords), ", did you mean `sphere`?");
        assert_eq!(did_you_mean("xyzzy", keywords), "");
    }
}
