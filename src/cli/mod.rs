//! The command line: its arguments (clap) and the subcommands, and what they share: loading
//! a scene, the overrides of its settings (`overrides`), the `--threads` limit, writing to
//! standard output, and removing unfinished files when a signal stops the program.

mod bench;
mod bench_first_hits;
mod bench_report;
mod generate;
mod inspect;
mod jobs;
mod merge;
mod overrides;
mod render;
mod sequence;
mod view;

use std::io::{self, BufWriter, StdoutLock, Write};
use std::sync::Arc;

use clap::{Parser, Subcommand};
use raylab::formats::nff::NffLighting;
use raylab::formats::toml::default_scene;
use raylab::formats::{SceneFormat, camera_file_beside, load_any_as};
use raylab::gpu::device::GpuDevice;
use raylab::scene::Scene;

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
    /// Merge the parts of an image rendered apart (`render --tile` or `--crop`) into the image
    /// one render would have written, after checking they fit; or list them (--status).
    Merge(merge::MergeArgs),
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
    remove_unfinished_files_on_signals()?;
    match cli.command {
        Some(Command::Render(args)) => render::run(args),
        Some(Command::Merge(args)) => merge::run(args),
        Some(Command::Gen(args)) => generate::run(args),
        Some(Command::Bench(args)) => bench::run(args),
        Some(Command::Inspect(args)) => inspect::run(args),
        Some(Command::View(args)) => view::run(args),
        None => view::run(cli.view),
    }
}

/// Loads the scene `name` names (a TOML, NFF or SDL file, or `spd:NAME[:SIZE]`), or the
/// built-in default scene when there is none, and prints the reader's warnings and a note when
/// the camera comes from a `NAME.camera.toml` beside the file. `lighting` applies to NFF and SPD
/// scenes; `format`, when given, is the file's format whatever its name.
fn load_scene(
    name: Option<&str>,
    lighting: NffLighting,
    format: Option<SceneFormat>,
) -> Result<Scene, String> {
    let scene = match name {
        Some(name) => load_any_as(name, lighting, format),
        None => default_scene(),
    }
    .map_err(|e| e.to_string())?;
    for warning in &scene.warnings {
        eprintln!("warning: {warning}");
    }
    if let Some(camera_file) = name.and_then(camera_file_beside) {
        eprintln!("note: the camera is from {}", camera_file.display());
    }
    Ok(scene)
}

/// The GPU that draws the item buffer `flag` asks for; the error says that it needs one, and
/// what to install.
fn item_buffer_gpu(flag: &str) -> Result<Arc<GpuDevice>, String> {
    GpuDevice::new()
        .map(Arc::new)
        .map_err(|e| format!("{flag} draws the item buffer on the GPU: {e}"))
}

/// A rayon pool of `threads` workers (default: one per core).
fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(thread_count(threads)?)
        .build()
        .map_err(|e| format!("cannot start worker threads: {e}"))
}

/// The most `--threads` per core: more only adds overhead (and a mistyped huge number would
/// start thousands of threads).
const THREADS_PER_CORE: usize = 4;

/// Checks `--threads`: from 1 to [`THREADS_PER_CORE`] per core. Left out, it is 0, which rayon
/// (and the viewer) read as one thread per core.
fn thread_count(threads: Option<usize>) -> Result<usize, String> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let most = THREADS_PER_CORE * cores;
    match threads {
        None => Ok(0),
        Some(0) => Err("--threads must be at least 1".into()),
        Some(n) if n > most => Err(format!(
            "--threads {n} is too many: at most {most} ({THREADS_PER_CORE} per core, and this \
             machine has {cores} cores)"
        )),
        Some(n) => Ok(n),
    }
}

/// Writes to standard output with `write`. When standard output is closed (its reader, such
/// as `head`, has had enough), exits quietly with status 0, as Unix tools do.
fn print_out(
    write: impl FnOnce(&mut BufWriter<StdoutLock<'static>>) -> io::Result<()>,
) -> Result<(), String> {
    let mut out = BufWriter::new(io::stdout().lock());
    match write(&mut out).and_then(|()| out.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => std::process::exit(0),
        result => result.map_err(|e| format!("cannot write to standard output: {e}")),
    }
}

/// On SIGINT, SIGTERM or SIGHUP, removes the temporary files of the writes in progress
/// ([`raylab::output::write_atomically`]) and exits with status 128 + the signal's number, as a shell
/// reports a process the signal stopped.
#[cfg(unix)]
fn remove_unfinished_files_on_signals() -> Result<(), String> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])
        .map_err(|e| format!("cannot handle signals: {e}"))?;
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            raylab::output::remove_temporary_files(|| std::process::exit(128 + signal));
        }
    });
    Ok(())
}

/// Elsewhere an interrupted write may leave its temporary file behind.
#[cfg(not(unix))]
fn remove_unfinished_files_on_signals() -> Result<(), String> {
    Ok(())
}
