//! The names the WGSL gives Rust's enum variants: `ShapeKind::TaperedCylinder` is the file
//! `shapes/tapered_cylinder.wgsl` with `intersect_tapered_cylinder`, and the constant
//! `SHAPE_TAPERED_CYLINDER` of the prelude.

use std::fmt::Debug;

/// A variant's name in snake case: `TaperedCylinder` as `tapered_cylinder`, `Checker3d` as
/// `checker3d`.
pub fn snake_case(variant: &impl Debug) -> String {
    let name = format!("{variant:?}");
    let mut out = String::new();
    let mut after_lower = false;
    for ch in name.chars() {
        if ch.is_uppercase() && after_lower {
            out.push('_');
        }
        after_lower = ch.is_lowercase() || ch.is_ascii_digit();
        out.extend(ch.to_lowercase());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug)]
    enum Example {
        TaperedCylinder,
        Checker3d,
        Uv,
    }

    #[test]
    fn words_are_parted_where_a_capital_follows_a_small_letter_or_a_digit() {
        assert_eq!(snake_case(&Example::TaperedCylinder), "tapered_cylinder");
        assert_eq!(snake_case(&Example::Checker3d), "checker3d");
        assert_eq!(snake_case(&Example::Uv), "uv");
    }
}
