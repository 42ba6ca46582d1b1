//! `raylab gen`: one of the built-in SPD scenes as an NFF file, or on standard output.

use std::path::{Path, PathBuf};

use clap::Args;
use raylab::formats::spd::Database;
use raylab::output::write_atomically;

#[derive(Args, Debug)]
pub struct GenArgs {
    /// The database: balls, gears, mount, rings, teapot, tetra or tree.
    database: Database,
    /// Size factor (default: the standard size, whose statistics the SPD readme publishes).
    #[arg(short, long)]
    size: Option<u32>,
    /// Output file (.nff); standard output when left out.
    #[arg(short, long)]
    output: Option<PathBuf>,
}

pub fn run(args: GenArgs) -> Result<(), String> {
    if let Some(path) = &args.output {
        check_nff_extension(path)?;
    }
    let database = args.database;
    let size = args.size.unwrap_or(database.standard_size());
    let document = database.generate(size)?;
    match &args.output {
        Some(path) => {
            write_atomically(path, |e| e, |out| document.write_nff(out))
                .map_err(|e| format!("{}: {e}", path.display()))?;
            eprintln!(
                "{database} size {size}: {} → {}",
                document.primitive_counts(),
                path.display()
            );
            Ok(())
        }
        None => super::print_out(|out| document.write_nff(out)),
    }
}

/// `gen` writes NFF: an output named otherwise (`x.png`) is a mistake, not a wish.
fn check_nff_extension(path: &Path) -> Result<(), String> {
    let is_nff = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("nff"));
    if is_nff {
        Ok(())
    } else {
        Err(format!(
            "-o/--output {}: gen writes NFF, so the file name must end in .nff",
            path.display()
        ))
    }
}
