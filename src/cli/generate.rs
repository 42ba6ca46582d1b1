//! `raylab gen`: one of the built-in SPD scenes as an NFF file, or on standard output.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use raylab::output::write_atomically;
use raylab::spd::Database;

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
        }
        None => {
            let mut out = std::io::BufWriter::new(std::io::stdout().lock());
            document
                .write_nff(&mut out)
                .and_then(|()| out.flush())
                .map_err(|e| format!("cannot write to standard output: {e}"))?;
        }
    }
    Ok(())
}
