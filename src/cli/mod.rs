//! The command line: its arguments (clap) and the subcommands.

mod bench;
mod bench_report;
mod generate;
mod inspect;
mod render;
mod view;

use clap::{Parser, Subcommand};
use raylab::nff::NffLighting;
use raylab::scene::{self, Scene};

#[derive(Parser, Debug)]
#[command(
    name = "raylab",
    version,
    about = "An interactive Whitted ray tracer",
    long_about = "An interactive Whitted ray tracer. With no subcommand, opens the viewer (the \
                  options below are the viewer's; see also `raylab view --help`).",
    args_conflicts_with_subcommands = true
)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    #[command(flatten)]
    view: view::ViewArgs,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Open the viewer on a scene file (or the built-in default scene): the image refines live
    /// from coarse blocks to single pixels while you move the camera and change the settings.
    View(view::ViewArgs),
    /// Render a scene file (or the built-in default scene) to an image.
    Render(render::RenderArgs),
    /// Write one of the Standard Procedural Databases as an NFF file.
    Gen(generate::GenArgs),
    /// Render a fixed set of scenes and report speed and memory.
    Bench(bench::BenchArgs),
    /// Print the ray tree of one pixel: every eye, reflected, transmitted and shadow ray, what
    /// it hit, the colours it carried and why each branch stopped.
    Inspect(inspect::InspectArgs),
}

/// Runs the command; the error is the message to print.
pub fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Some(Command::Render(args)) => render::run(args),
        Some(Command::Gen(args)) => generate::run(args),
        Some(Command::Bench(args)) => bench::run(args),
        Some(Command::Inspect(args)) => inspect::run(args),
        Some(Command::View(args)) => view::run(args),
        None => view::run(cli.view),
    }
}

/// Loads the scene `name` names (a TOML or NFF file, or `spd:NAME[:SIZE]`), or the built-in
/// default scene when there is none, and prints the reader's warnings. `lighting` applies to
/// NFF and SPD scenes.
fn load_scene(name: Option<&str>, lighting: NffLighting) -> Result<Scene, String> {
    let scene = match name {
        Some(name) => scene::load_any_with(name, lighting),
        None => scene::default_scene(),
    }
    .map_err(|e| e.to_string())?;
    for warning in &scene.warnings {
        eprintln!("warning: {warning}");
    }
    Ok(scene)
}

/// A rayon pool of `threads` workers (default: one per core).
fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, String> {
    if threads == Some(0) {
        return Err("--threads must be at least 1".into());
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| format!("cannot start worker threads: {e}"))
}
