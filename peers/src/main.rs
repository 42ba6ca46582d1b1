//! `raylab-peers DUMP_DIR [--meshes a,b] [--reps N] [--embree FILE] [--peers bvh,obvhs]`: builds
//! raylab's BVH, the
//! `bvh` crate's and `obvhs`'s over the meshes that `embree_anchor.py --dump DUMP_DIR` wrote,
//! traces the same rays with each on 1 and 2 threads, checks every answer against Embree's and
//! prints markdown tables: build times, Mrays/s, ratios to raylab, mismatches, and the interior
//! nodes visited and triangles tested per ray.
//! With `--embree FILE` (from `embree_anchor.py --json FILE`) Embree's own figures join them;
//! `--peers` names the crates to compare (none: `--peers ''`, raylab alone, e.g. for profiling).

mod anchor;
mod bvh_crate_tracer;
mod embree;
mod measure;
mod obvhs_tracer;
mod raylab_tracer;
mod tracer;

use std::path::PathBuf;

use anchor::{AnchorMesh, TILES};
use bvh_crate_tracer::BvhCrateTracer;
use embree::EmbreeFigures;
use measure::{THREADS, TracerReport, measure};
use obvhs_tracer::ObvhsTracer;
use raylab_tracer::RaylabTracer;

const USAGE: &str =
    "usage: raylab-peers DUMP_DIR [--meshes a,b] [--reps N] [--embree FILE] [--peers bvh,obvhs]";

struct Options {
    dump: PathBuf,
    meshes: Vec<String>,
    reps: usize,
    embree: Option<PathBuf>,
    peers: Vec<String>,
}

fn parse_options() -> Result<Options, String> {
    let mut args = std::env::args().skip(1);
    let mut options = Options {
        dump: PathBuf::new(),
        meshes: Vec::new(),
        reps: 3,
        embree: None,
        peers: vec!["bvh".into(), "obvhs".into()],
    };
    let mut dump = None;
    while let Some(arg) = args.next() {
        let mut value = || args.next().ok_or(format!("{arg} needs a value\n{USAGE}"));
        match arg.as_str() {
            "--meshes" => options.meshes = value()?.split(',').map(String::from).collect(),
            "--reps" => {
                options.reps = value()?
                    .parse()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or(format!("--reps needs a positive whole number\n{USAGE}"))?;
            }
            "--embree" => options.embree = Some(PathBuf::from(value()?)),
            "--peers" => {
                options.peers = value()?
                    .split(',')
                    .filter(|name| !name.is_empty())
                    .map(String::from)
                    .collect();
                if let Some(other) = options.peers.iter().find(|p| *p != "bvh" && *p != "obvhs") {
                    return Err(format!("no peer `{other}` (bvh, obvhs)\n{USAGE}"));
                }
            }
            _ if arg.starts_with('-') => return Err(format!("unknown option {arg}\n{USAGE}")),
            _ if dump.is_none() => dump = Some(PathBuf::from(arg)),
            _ => return Err(format!("one dump folder only\n{USAGE}")),
        }
    }
    options.dump = dump.ok_or(USAGE)?;
    Ok(options)
}

fn main() {
    if let Err(e) = run() {
        eprintln!("raylab-peers: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), String> {
    let options = parse_options()?;
    let embree = options
        .embree
        .as_deref()
        .map(EmbreeFigures::load)
        .transpose()?;
    let meshes = anchor::load(&options.dump, &options.meshes)?;
    if meshes.is_empty() {
        return Err(format!("no such mesh in {}", options.dump.display()));
    }
    let pools = THREADS.map(|n| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .expect("a thread pool")
    });
    let mut reports = Vec::new();
    for mesh in &meshes {
        eprintln!("{}: {} triangles", mesh.name, mesh.faces.len());
        let mut tracers = vec![measure::<RaylabTracer>(mesh, &pools, options.reps)?];
        for peer in &options.peers {
            tracers.push(match peer.as_str() {
                "bvh" => measure::<BvhCrateTracer>(mesh, &pools, options.reps)?,
                _ => measure::<ObvhsTracer>(mesh, &pools, options.reps)?,
            });
        }
        reports.push((mesh, tracers));
    }
    print_builds(&reports, embree.as_ref());
    print_traces(&reports, embree.as_ref());
    Ok(())
}

fn print_builds(reports: &[(&AnchorMesh, Vec<TracerReport>)], embree: Option<&EmbreeFigures>) {
    println!("\n### BVH build, median ms (1 thread / 2 threads)\n");
    let names: Vec<&str> = reports.first().map_or(Vec::new(), |(_, tracers)| {
        tracers.iter().map(|t| t.name).collect()
    });
    println!(
        "| mesh | triangles | {} | Embree (2 CPUs) |",
        names.join(" | ")
    );
    println!("|---|---|{}---|", "---|".repeat(names.len()));
    for (mesh, tracers) in reports {
        let cells: Vec<String> = tracers
            .iter()
            .map(|t| format!("{:.0} / {:.0}", t.build_ms[0], t.build_ms[1]))
            .collect();
        let embree = embree
            .and_then(|e| e.build_ms(&mesh.name, 2))
            .map_or("–".into(), |ms| format!("{ms:.0}"));
        println!(
            "| {} | {} | {} | {embree} |",
            mesh.name,
            mesh.faces.len(),
            cells.join(" | ")
        );
    }
}

fn print_traces(reports: &[(&AnchorMesh, Vec<TracerReport>)], embree: Option<&EmbreeFigures>) {
    println!("\n### Traversal, median Mrays/s (1 thread / 2 threads), raylab ÷ peer\n");
    println!(
        "| mesh | rays | tracer | Mrays/s 1T / 2T | raylab ÷ it 1T / 2T | ≠ Embree | nodes/ray | tris/ray |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (mesh, tracers) in reports {
        let ours = &tracers[0];
        for (k, set) in ours.sets.iter().enumerate() {
            let rows = tracers.iter().map(|t| {
                let s = &t.sets[k];
                let (nodes, tris) =
                    s.cost_per_ray.map_or(("–".into(), "–".into()), |(n, t)| {
                        (format!("{n:.1}"), format!("{t:.1}"))
                    });
                (t.name, s.mrays, format!("{}", s.mismatches), nodes, tris)
            });
            let embree_row = embree.map(|e| {
                let mrays = THREADS.map(|n| {
                    e.mrays(&mesh.name, set.set.trim_end_matches(TILES), n)
                        .unwrap_or(f64::NAN)
                });
                ("Embree", mrays, "–".into(), "–".into(), "–".into())
            });
            for (name, mrays, mismatches, nodes, tris) in rows.chain(embree_row) {
                println!(
                    "| {} | {} ({}) | {name} | {:.2} / {:.2} | {:.2} / {:.2} | {mismatches} | {nodes} | {tris} |",
                    mesh.name,
                    set.set,
                    set.rays,
                    mrays[0],
                    mrays[1],
                    set.mrays[0] / mrays[0],
                    set.mrays[1] / mrays[1],
                );
            }
        }
    }
}
