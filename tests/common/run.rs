//! Running the `raylab` binary as a user does, for the tests of its command line.

use std::path::Path;
use std::process::{Command, Output};

/// Runs `raylab ARGS` in `dir` and returns what it did.
pub fn raylab(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// What a run wrote to standard error.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}
