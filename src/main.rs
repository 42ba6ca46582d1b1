//! The `raylab` command: the interactive viewer (the default), and rendering scene files to
//! images from the command line.

mod cli;
mod viewer;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    cli::run(cli::Cli::parse())
}
