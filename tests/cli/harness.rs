//! What several topics share beyond `common::run` (running `raylab` and reading its standard
//! error): a tiny bench, the check that every command's help names some flags, the mean
//! difference of two images, and running `raylab` where no window can open.

use std::path::Path;
use std::process::{Command, Output};

use crate::common::run::{raylab, stderr};

/// A bench of one tiny scene, run once.
pub const SMALL_BENCH: [&str; 7] = [
    "bench",
    "--scenes",
    "spd:tetra:1",
    "--size",
    "8",
    "--repeat",
    "1",
];

/// Each command that renders a scene asserts that its `--help` names every one of `flags`.
pub fn assert_every_help_names(flags: &[&str], dir: &Path) {
    for args in [
        &["render", "--help"][..],
        &["inspect", "--help"],
        &["view", "--help"],
        &["--help"],
    ] {
        let out = raylab(args, dir);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        let help = String::from_utf8_lossy(&out.stdout);
        for flag in flags {
            assert!(help.contains(flag), "{args:?} lacks {flag}: {help}");
        }
    }
}

/// `raylab ARGS` where no window can open (no display).
pub fn raylab_without_display(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap()
}

/// The mean absolute difference of two images' bytes, in levels.
pub fn mean_level_difference(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len(), "images of the same size");
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| f64::from(x.abs_diff(*y)))
        .sum();
    sum / a.len() as f64
}
