//! No input makes the reader panic: seeded mutations of the shipped scenes and the full-feature
//! file are each read or rejected at a line and column.

use std::path::Path;

use raylab::formats::toml::parse_scene;

use crate::common::fuzz::mutate;
use crate::common::random::Rng;
use crate::harness::{FULL, scenes_dir};

/// Characters that mean something to TOML or to the schema, and a few that do not.
const ALPHABET: &[char] = &[
    '[', ']', '{', '}', '=', '"', '\'', ',', '.', '#', '\n', ' ', '-', '+', '0', '1', '9', 'e',
    'a', 'z', '_', 'é', '\t', '\\',
];

#[test]
fn mutated_scene_files_never_panic() {
    let mut rng = Rng::with_seed(0x5EED_CAFE_F00D_1234);
    let mut originals: Vec<String> = std::fs::read_dir(scenes_dir())
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .map(|path| std::fs::read_to_string(path).unwrap())
        .collect();
    originals.sort();
    assert!(originals.len() >= 5);
    originals.push(FULL.to_string());
    let (mut parsed, mut rejected) = (0, 0);
    for _ in 0..20_000 {
        let original = &originals[rng.usize(..originals.len())];
        let text = mutate(original, &mut rng, ALPHABET);
        let outcome = std::panic::catch_unwind(|| {
            parse_scene(&text, Path::new("fuzz.toml"), &scenes_dir()).map(|_| ())
        });
        match outcome {
            Ok(Ok(())) => parsed += 1,
            Ok(Err(error)) => {
                assert!(error.line >= 1 && error.column >= 1, "{error}");
                rejected += 1;
            }
            Err(_) => panic!("parse_scene panicked on:\n{text}"),
        }
    }
    // Both outcomes must be common, or the mutations are too mild or too wild to test much.
    assert!(
        parsed > 1000 && rejected > 1000,
        "{parsed} parsed, {rejected} rejected"
    );
}
