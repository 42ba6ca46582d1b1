//! The `raylab` command as a user runs it: exit codes, messages, files written.

#[path = "../common/mod.rs"]
mod common;
mod harness;

mod camera;
mod check;
mod cluster;
mod diff;
mod figure;
mod first_hit;
mod gen_and_bench;
mod gpu;
mod grade;
mod inspect;
mod outputs;
mod overrides;
mod proportion;
mod render;
mod report_in_browser;
mod sequences;
mod tone;
mod user_files;
