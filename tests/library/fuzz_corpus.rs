//! The fuzz targets' code (`fuzz/src/harness.rs`) run as ordinary tests, without nightly or
//! cargo-fuzz: the inputs kept in `fuzz/regressions/TARGET/` must each be read or refused with
//! an error, never panic; and the files the fuzz corpora are seeded from must read and render.

#[path = "../../fuzz/src/harness.rs"]
mod harness;

use std::panic::catch_unwind;
use std::path::{Path, PathBuf};

/// What a fuzz target does with one input.
type Target = fn(&[u8]) -> Result<(), String>;

/// The files in `folder` (relative to the repository) whose names end in `extension` ("" for
/// all), sorted.
fn files(folder: &str, extension: &str) -> Vec<PathBuf> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.to_string_lossy().ends_with(extension))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no inputs", folder.display());
    files
}

/// Runs every input kept for the fuzz target `name` through `target`.
fn replay(name: &str, target: Target) {
    for path in files(&format!("fuzz/regressions/{name}"), "") {
        let input = std::fs::read(&path).unwrap();
        let outcome = catch_unwind(|| target(&input));
        assert!(outcome.is_ok(), "{name}: {} panics", path.display());
    }
}

/// Runs every file of `folder` ending in `extension` through `target`, which must read it.
fn read_all(folder: &str, extension: &str, target: Target) {
    for path in files(folder, extension) {
        let input = std::fs::read(&path).unwrap();
        if let Err(message) = target(&input) {
            panic!("{}: {message}", path.display());
        }
    }
}

#[test]
fn the_kept_toml_scenes_read_or_fail_cleanly() {
    replay("toml_scene", harness::toml_scene);
}

#[test]
fn the_kept_nff_files_read_or_fail_cleanly() {
    replay("nff", harness::nff);
}

#[test]
fn the_kept_obj_files_read_or_fail_cleanly() {
    replay("obj", harness::obj);
}

#[test]
fn the_kept_mtl_files_read_or_fail_cleanly_and_the_seeds_read() {
    replay("mtl", harness::mtl);
    read_all("fuzz/regressions/mtl", ".mtl", harness::mtl);
}

#[test]
fn the_kept_ply_files_read_or_fail_cleanly() {
    replay("ply", harness::ply);
    let seeds = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/ply");
    for seed in ["seed_ascii.ply", "seed_binary_le.ply", "seed_binary_be.ply"] {
        let bytes = std::fs::read(seeds.join(seed)).unwrap();
        assert_eq!(harness::ply(&bytes), Ok(()), "{seed}");
    }
}

#[test]
fn the_kept_gltf_files_read_or_fail_cleanly() {
    replay("gltf", harness::gltf);
    let seeds = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/gltf");
    for seed in ["seed_cubes.gltf", "seed_cubes.glb", "seed_textured.glb"] {
        let bytes = std::fs::read(seeds.join(seed)).unwrap();
        assert_eq!(harness::gltf(&bytes), Ok(()), "{seed}");
    }
}

#[test]
fn the_kept_sdl_files_read_or_fail_cleanly() {
    replay("sdl", harness::sdl);
}

#[test]
fn the_kept_views_files_read_or_fail_cleanly() {
    replay("views", harness::views);
    // A good one reads, writes back the same, and its path and turntable have cameras.
    let good = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/views/seed_two_views");
    assert_eq!(harness::views(&std::fs::read(good).unwrap()), Ok(()));
}

#[test]
fn the_kept_assignments_read_or_fail_cleanly() {
    replay("assignment", harness::assignment);
    let good = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/assignment/seed_two");
    assert_eq!(harness::assignment(&std::fs::read(good).unwrap()), Ok(()));
}

#[test]
fn the_kept_parts_read_or_fail_cleanly() {
    replay("part", harness::part);
    let kept = |name: &str| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/part");
        std::fs::read(path.join(name)).unwrap()
    };
    // The seeds, parts raylab wrote, read.
    for seed in ["seed_whole_4x3.exr", "seed_tile_1_of_4.exr"] {
        assert_eq!(harness::part(&kept(seed)), Ok(()), "{seed}");
    }
    // A header that claims a million pixels a side is refused with raylab's limit.
    for huge in ["huge_window_1000000x1000000.exr", "huge_display_window.exr"] {
        let message = harness::part(&kept(huge)).unwrap_err();
        assert!(
            message.contains("image sides must be at most 16384, got 1000000×1000000"),
            "{huge}: {message}"
        );
    }
    // A 4 × 3 part in tiles of 16515136 × 64 pixels, for which the OpenEXR reader allocated
    // gigabytes, is refused before its pixels are read.
    let message = harness::part(&kept("oom-tile-16515136x64")).unwrap_err();
    assert!(message.contains("tiles of at most 256 pixels"), "{message}");
    // One in B44 compression, whose block overflowed the OpenEXR reader's B44 decompressor (a
    // panic on a thread of its own, which aborted).
    let message =
        harness::part(&kept("crash-2df55c039b013a6fadc2006818455ac217d30ac1")).unwrap_err();
    assert!(
        message.ends_with("this one has b44 compression"),
        "{message}"
    );
}

#[test]
fn the_shipped_scenes_read_and_render_with_the_fuzz_targets_files() {
    read_all("assets/scenes", ".toml", harness::toml_scene);
}

#[test]
fn the_shipped_sdl_scenes_read_and_render() {
    read_all("assets/scenes", ".dat", harness::sdl);
}

#[test]
fn the_tests_nff_files_read_back_the_same_and_render() {
    read_all("tests/nff", ".nff", harness::nff);
}

#[test]
fn the_shipped_models_read_and_render() {
    read_all("assets/models", ".obj", harness::obj);
}

#[test]
fn a_broken_input_is_an_error_with_its_place() {
    let message = harness::toml_scene(b"[camera]\neye = 1\n").unwrap_err();
    assert!(message.starts_with("fuzz.toml:2:7:"), "{message}");
    let message = harness::obj(b"f 1 2 3\n").unwrap_err();
    assert!(message.contains("model.obj"), "{message}");
}

#[test]
fn the_kept_images_read_or_fail_cleanly() {
    replay("image", harness::image);
    let kept = |name: &str| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz/regressions/image");
        std::fs::read(path.join(name)).unwrap()
    };
    // The seeds, in every format `raylab diff` reads, read.
    for seed in [
        "seed_plain.ppm",
        "seed_small_max.ppm",
        "seed_binary.ppm",
        "seed_raylab.png",
        "seed_raylab.bmp",
        "seed_raylab.jpg",
        "seed_raylab.exr",
        "seed_raylab.hdr",
    ] {
        assert_eq!(harness::image(&kept(seed)), Ok(()), "{seed}");
    }
    // OpenEXR's B44 compression (whose decompressor overflows on this file) and tiles as large
    // as the image are refused from the header, before any block is read.
    let message = harness::image(&kept("b44_crash.exr")).unwrap_err();
    assert!(message.contains("b44 compression"), "{message}");
    let message = harness::image(&kept("oom_tile_16515136x64.exr")).unwrap_err();
    assert!(message.contains("tiles of at most 256 pixels"), "{message}");
    // An 8 × 6 OpenEXR image in a display window 33554440 pixels wide, for which the `image`
    // crate allocated the whole window (16 GB), reads as its 8 × 6 pixels.
    assert_eq!(
        harness::image(&kept("oom_display_window_33554440x6.exr")),
        Ok(())
    );
    // Ten billion pixels are refused, not allocated; no pixels and too few are errors.
    for name in [
        "huge_100000x100000.ppm",
        "huge_window_1000000x1000000.exr",
        "no_pixels.ppm",
        "truncated.ppm",
    ] {
        assert!(harness::image(&kept(name)).is_err(), "{name}");
    }
}
