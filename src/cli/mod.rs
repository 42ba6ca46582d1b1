//! The command line: its arguments (clap) and the subcommands, and what they share: loading
//! a scene, the overrides of its settings (`overrides`), the `--threads` limit, writing to
//! standard output and legends, the exit status, and removing unfinished files when a signal
//! stops the program.

mod bench;
mod bench_first_hits;
mod bench_report;
mod check;
mod diff;
mod figure;
mod generate;
mod grade;
mod inspect;
mod jobs;
mod merge;
mod overrides;
mod render;
mod sequence;
mod view;

use std::io::{self, BufWriter, StdoutLock, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

use clap::{Parser, Subcommand};
use raylab::backend::{GpuUse, RenderError};
use raylab::compare::difference::Difference;
use raylab::formats::image::save_image;
use raylab::formats::nff::NffLighting;
use raylab::formats::toml::default_scene;
use raylab::formats::{SceneFormat, camera_file_beside, load_any_as};
use raylab::gpu::device::GpuDevice;
use raylab::inspect::{DebugView, Legend};
use raylab::render::FirstHit;
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
    /// Compare an image with a reference: mean and largest difference, RMSE, PSNR, FLIP, the
    /// pixels over a tolerance, a heat map. Exits as `cmp` does: 0 within the tolerance, 1
    /// different, 2 trouble.
    Diff(diff::DiffArgs),
    /// Render a scene at an image's size and say why the image differs from raylab's: the
    /// common mistakes that account for it (shadows, specular, reflection or transmission
    /// missing, a wrong index of refraction, pixel corners, a flipped image, gamma, clamping),
    /// and raylab's ray tree at the worst pixels. Exits as `diff` does.
    Check(check::CheckArgs),
    /// Grade a class: each student's image of each scene of an assignment against raylab's,
    /// a report a browser opens offline (index.html, a page per student, grades.csv). Exits 0
    /// when it graded, 1 when the assignment is wrong, 2 for a mistyped command line.
    Grade(grade::GradeArgs),
}

/// Runs the command, printing its error, and gives the exit status: 0 when it succeeds, 1 when
/// it fails; `diff` and `check` give `cmp`'s ([`Verdict`]).
pub fn run(cli: Cli) -> ExitCode {
    if let Err(message) = remove_unfinished_files_on_signals() {
        return failed(&message, ExitCode::FAILURE);
    }
    let result = match cli.command {
        Some(Command::Render(args)) => render::run(args),
        Some(Command::Merge(args)) => merge::run(args),
        Some(Command::Gen(args)) => generate::run(args),
        Some(Command::Bench(args)) => bench::run(args),
        Some(Command::Inspect(args)) => inspect::run(args),
        Some(Command::Grade(args)) => grade::run(args),
        Some(Command::View(args)) => view::run(args),
        Some(Command::Diff(args)) => return compared(diff::run(args)),
        Some(Command::Check(args)) => return compared(check::run(args)),
        None => view::run(cli.view),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => failed(&message, ExitCode::FAILURE),
    }
}

/// The exit status of a comparison: its verdict, or trouble.
fn compared(result: Result<Verdict, String>) -> ExitCode {
    match result {
        Ok(verdict) => ExitCode::from(verdict as u8),
        Err(message) => failed(&message, ExitCode::from(Verdict::TROUBLE)),
    }
}

fn failed(message: &str, code: ExitCode) -> ExitCode {
    eprintln!("error: {message}");
    code
}

/// What a comparison found, as its exit status (`cmp`'s): the images are the same within the
/// tolerance (0), or they differ (1). Trouble (an unreadable file, images of different sizes)
/// is [`Verdict::TROUBLE`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Verdict {
    Same = 0,
    Different = 1,
}

impl Verdict {
    /// The exit status of a comparison that could not be made.
    const TROUBLE: u8 = 2;

    fn from_difference(difference: &Difference) -> Verdict {
        if difference.within_tolerance() {
            Verdict::Same
        } else {
            Verdict::Different
        }
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
    for note in &scene.notes {
        eprintln!("note: {note}");
    }
    if let Some(camera_file) = name.and_then(camera_file_beside) {
        eprintln!("note: the camera is from {}", camera_file.display());
    }
    Ok(scene)
}

/// What the command line says when a render of `view` with first hits found by `first_hit`
/// does not come: the flags that asked for what could not be done.
fn explain(error: RenderError, view: DebugView, first_hit: FirstHit) -> String {
    let items_flag = match first_hit {
        FirstHit::Raster => "--first-hit raster".to_string(),
        FirstHit::Rays => format!("--view {view}"),
    };
    match error {
        RenderError::ViewOnCpuOnly(view) => {
            format!("--view {view} traces on the CPU only: leave out --device gpu")
        }
        RenderError::NoGpu {
            needed_for: GpuUse::ItemBuffer,
            why,
        } => format!("{items_flag} draws the item buffer on the GPU: {why}"),
        RenderError::NotOnGpu {
            needed_for: GpuUse::ItemBuffer,
            why,
        } => format!("{items_flag}: {why}"),
        error => error.to_string(),
    }
}

/// The size of a legend's colour bar image.
const LEGEND_SIZE: (u32, u32) = (256, 24);

/// Where the legend of the image at `image` goes: beside it, as NAME.legend.png.
fn legend_path(image: &Path) -> PathBuf {
    image.with_extension("legend.png")
}

/// Writes `legend`'s colour bar beside the image at `image` ([`legend_path`]) and gives its path.
fn save_legend(legend: &Legend, image: &Path) -> Result<PathBuf, String> {
    let path = legend_path(image);
    let (width, height) = LEGEND_SIZE;
    save_image(&path, width, height, &legend.bar_image(width, height))
        .map_err(|e| e.to_string())?;
    Ok(path)
}

/// What the command line says before the GPU tracer is compiled for `device`, which takes a
/// minute or two on a software adapter: the run is not stuck.
fn compiling_notice(device: &GpuDevice) -> String {
    let wait = if device.is_software() {
        ", which a software adapter takes a minute or two for"
    } else {
        ""
    };
    format!(
        "compiling the GPU tracer for {}, once for this run{wait}…",
        device.name()
    )
}

/// The median of the times a bench measured (at least one).
fn median(mut times: Vec<Duration>) -> Duration {
    times.sort();
    times[times.len() / 2]
}

/// A rayon pool of `threads` workers (default: one per core).
fn thread_pool(threads: Option<usize>) -> Result<Arc<rayon::ThreadPool>, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(thread_count(threads)?)
        .build()
        .map(Arc::new)
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
