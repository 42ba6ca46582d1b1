//! The GNU parallel recipe of docs/cluster.md run for real: `examples/cluster/parallel/local.sh`
//! renders a scene as tiles with `--tile auto` (each job's number in `PARALLEL_SEQ`) and merges
//! them, and the merged image must equal a single render of the scene byte for byte. The test
//! needs Debian's `parallel` (`scripts/test` installs it); without it the test fails, saying
//! what to install.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::common::run::raylab;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn assert_success(out: &Output, what: &str) {
    assert!(
        out.status.success(),
        "{what}:\nstdout: {}\nstderr: {}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Fails, saying how to get it, where GNU parallel is not installed.
fn require_parallel() {
    let found = Command::new("sh")
        .args(["-c", "command -v parallel"])
        .output()
        .is_ok_and(|out| out.status.success());
    assert!(
        found,
        "the cluster tests run GNU parallel, which is not installed. Install it (Debian: sudo \
         apt-get install parallel) and run `cargo test --test cli cluster`, or scripts/test, \
         which installs it"
    );
}

/// `examples/cluster/parallel/local.sh` rendering `scene` as `tiles` tiles into `output` (in
/// `dir`), with this build's raylab first on the PATH; the folder of the tiles.
fn parallel_recipe(
    dir: &Path,
    scene: &Path,
    tiles: u32,
    output: &str,
    options: &[&str],
) -> PathBuf {
    let bin = Path::new(env!("CARGO_BIN_EXE_raylab")).parent().unwrap();
    let path = std::env::join_paths(std::iter::once(bin.to_path_buf()).chain(
        std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()),
    ))
    .unwrap();
    let out = Command::new(repo().join("examples/cluster/parallel/local.sh"))
        .arg(scene)
        .arg(tiles.to_string())
        .arg(output)
        .args(options)
        .env("PATH", path)
        .current_dir(dir)
        .output()
        .expect("the recipe runs");
    assert_success(&out, "examples/cluster/parallel/local.sh");
    let parts = dir.join(output).with_extension("parts");
    assert!(parts.is_dir(), "the tiles go to {}", parts.display());
    parts
}

/// The tiles of `scene` through GNU parallel, merged, equal one render of it, for each count of
/// tiles: as an 8-bit PNG byte for byte, and as an EXR of linear values, value for value.
fn tiles_through_parallel_equal_one_render(scene: &str, options: &[&str], tile_counts: &[u32]) {
    require_parallel();
    let dir = tempfile::tempdir().unwrap();
    let scene = repo().join(scene);
    let scene_arg = scene.to_str().unwrap();
    for single in ["single.png", "single.exr"] {
        let mut args = vec!["render", scene_arg, "-o", single];
        args.extend(options);
        assert_success(&raylab(&args, dir.path()), "the single render");
    }
    let single_png = std::fs::read(dir.path().join("single.png")).unwrap();
    let single_exr = image::open(dir.path().join("single.exr"))
        .unwrap()
        .to_rgba32f();
    for &tiles in tile_counts {
        let output = format!("tiles{tiles}.png");
        let parts = parallel_recipe(dir.path(), &scene, tiles, &output, options);
        let files = std::fs::read_dir(&parts).unwrap().count();
        assert_eq!(
            files,
            tiles as usize,
            "one file a tile in {}",
            parts.display()
        );
        let merged = std::fs::read(dir.path().join(&output)).unwrap();
        assert!(
            merged == single_png,
            "{tiles} tiles merged into a PNG differ from the single render"
        );

        // The same tiles merged into linear values: differences that 8 bits would round away.
        let exr = format!("tiles{tiles}.exr");
        let parts_arg = parts.to_str().unwrap();
        let out = raylab(&["merge", parts_arg, "-o", &exr], dir.path());
        assert_success(&out, "raylab merge into .exr");
        let merged = image::open(dir.path().join(&exr)).unwrap().to_rgba32f();
        assert_eq!(merged.dimensions(), single_exr.dimensions());
        let differing = merged
            .pixels()
            .zip(single_exr.pixels())
            .filter(|(a, b)| a.0.map(f32::to_bits) != b.0.map(f32::to_bits))
            .count();
        assert_eq!(
            differing, 0,
            "{tiles} tiles merged into an EXR: pixels differing from the single render"
        );
    }
}

#[test]
fn anti_aliased_tiles_through_gnu_parallel_equal_one_render() {
    // Adaptive anti-aliasing decides from neighbouring pixels; the size divides by no count.
    tiles_through_parallel_equal_one_render(
        "assets/scenes/glass.toml",
        &[
            "--size",
            "97x61",
            "--samples",
            "4",
            "--aa-threshold",
            "0.03",
        ],
        &[1, 3, 7],
    );
}

#[test]
fn caustic_tiles_through_gnu_parallel_equal_one_render() {
    // Every task shoots the same photons and builds the same map before tracing its tile.
    tiles_through_parallel_equal_one_render(
        "assets/scenes/caustic_glass_ball.toml",
        &["--size", "80x60", "--caustic-photons", "20000"],
        &[4],
    );
}
