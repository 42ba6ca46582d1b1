//! `raylab bench`: renders a fixed set of scenes headless and reports, per scene, primitives,
//! BVH build time, render time to block size 1, rays by kind, Mrays/s and memory; `--json`
//! writes the same as JSON.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use raylab::bvh::Bvh;
use raylab::large_mesh::bumpy_sphere_scene;
use raylab::progressive;
use raylab::scene::{Scene, default_scene, load_any};
use raylab::stats::RayCounts;
use raylab::whitted::Tracer;

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Scenes to run (default: all). `default`, `bumpy:N` for the generated N-triangle mesh, or
    /// any scene `render` takes (`spd:balls`, a .nff or .toml file).
    #[arg(long, value_delimiter = ',')]
    scenes: Vec<String>,
    /// Image size (square).
    #[arg(long, default_value_t = 512)]
    size: u32,
    /// Worker threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Also write the results as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
}

/// The standard set.
const STANDARD_SCENES: &[&str] = &["default", "bumpy:1000000"];

/// What one scene measured.
struct BenchResult {
    name: String,
    primitives: usize,
    setup_seconds: f64,
    build_seconds: f64,
    render_seconds: f64,
    rays: RayCounts,
    scene_bytes: usize,
    peak_rss_bytes: Option<u64>,
}

pub fn run(args: BenchArgs) -> Result<(), String> {
    let pool = super::thread_pool(args.threads)?;
    let names: Vec<String> = if args.scenes.is_empty() {
        STANDARD_SCENES.iter().map(|s| s.to_string()).collect()
    } else {
        args.scenes.clone()
    };
    println!(
        "{:<16} {:>9} {:>9} {:>9} {:>10} {:>10} {:>10} {:>10} {:>9} {:>8} {:>9}",
        "scene",
        "prims",
        "setup ms",
        "build ms",
        "render ms",
        "eye",
        "shadow",
        "reflect",
        "refract",
        "Mrays/s",
        "B/prim"
    );
    let mut results = Vec::new();
    for name in &names {
        let r = bench_scene(name, args.size, &pool)?;
        let mrays = r.rays.total() as f64 / r.render_seconds / 1e6;
        println!(
            "{:<16} {:>9} {:>9.1} {:>9.1} {:>10.1} {:>10} {:>10} {:>10} {:>9} {:>8.2} {:>9.1}",
            r.name,
            r.primitives,
            r.setup_seconds * 1e3,
            r.build_seconds * 1e3,
            r.render_seconds * 1e3,
            r.rays.primary,
            r.rays.shadow,
            r.rays.reflected,
            r.rays.transmitted,
            mrays,
            r.scene_bytes as f64 / r.primitives.max(1) as f64,
        );
        results.push(r);
    }
    if let Some(peak) = results.last().and_then(|r| r.peak_rss_bytes) {
        println!(
            "peak resident memory of the process: {:.1} MiB",
            peak as f64 / 1048576.0
        );
    }
    if let Some(path) = &args.json {
        std::fs::write(
            path,
            to_json(&results, args.size, pool.current_num_threads()),
        )
        .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

fn load(name: &str, size: u32) -> Result<Scene, String> {
    let mut scene = if name == "default" {
        default_scene().map_err(|e| e.to_string())?
    } else if let Some(n) = name.strip_prefix("bumpy:") {
        let n: usize = n
            .parse()
            .map_err(|_| format!("`{name}`: expected bumpy:N with N a number of triangles"))?;
        bumpy_sphere_scene(n, size, size)
    } else {
        load_any(name).map_err(|e| e.to_string())?
    };
    scene.settings.width = size;
    scene.settings.height = size;
    scene.settings.validate()?;
    Ok(scene)
}

fn bench_scene(name: &str, size: u32, pool: &rayon::ThreadPool) -> Result<BenchResult, String> {
    let start = Instant::now();
    let scene = load(name, size)?;
    let setup_seconds = start.elapsed().as_secs_f64();
    pool.install(|| {
        let start = Instant::now();
        let bvh = Bvh::build(&scene.geometry);
        let build_seconds = start.elapsed().as_secs_f64();
        let (_, stats) = progressive::render_image(&Tracer::new(&scene, &bvh));
        Ok(BenchResult {
            name: name.to_string(),
            primitives: scene.geometry.len(),
            setup_seconds,
            build_seconds,
            render_seconds: stats.time.as_secs_f64(),
            rays: stats.rays,
            scene_bytes: scene.geometry.memory_bytes() + bvh.memory_bytes(),
            peak_rss_bytes: peak_rss_bytes(),
        })
    })
}

/// The process's peak resident memory (Linux: VmHWM in /proc/self/status).
fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

fn to_json(results: &[BenchResult], size: u32, threads: usize) -> String {
    let scenes: Vec<String> = results
        .iter()
        .map(|r| {
            format!(
                concat!(
                    "    {{\"scene\": \"{}\", \"primitives\": {}, \"setup_ms\": {:.3}, \"build_ms\": {:.3}, ",
                    "\"render_ms\": {:.3}, \"eye_rays\": {}, \"eye_hits\": {}, \"shadow_rays\": {}, ",
                    "\"reflected_rays\": {}, \"transmitted_rays\": {}, \"mrays_per_s\": {:.3}, ",
                    "\"scene_bytes\": {}, \"peak_rss_bytes\": {}}}"
                ),
                r.name,
                r.primitives,
                r.setup_seconds * 1e3,
                r.build_seconds * 1e3,
                r.render_seconds * 1e3,
                r.rays.primary,
                r.rays.primary_hits,
                r.rays.shadow,
                r.rays.reflected,
                r.rays.transmitted,
                r.rays.total() as f64 / r.render_seconds / 1e6,
                r.scene_bytes,
                r.peak_rss_bytes.map_or("null".to_string(), |b| b.to_string()),
            )
        })
        .collect();
    format!(
        "{{\n  \"width\": {size},\n  \"height\": {size},\n  \"threads\": {threads},\n  \"scenes\": [\n{}\n  ]\n}}\n",
        scenes.join(",\n")
    )
}
