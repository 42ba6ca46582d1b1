//! `raylab bench`: renders a fixed set of scenes headless and reports, per scene, primitives,
//! BVH build time, render time to block size 1 (and of the coarsest pass), rays by kind,
//! Mrays/s and memory, and for a scene with caustics what they cost (photons shot per second,
//! the map's build time, the time of one estimate, the render with and without them); `--json`
//! writes the same as JSON ([`super::bench_report`]).
//!
//! Timings on a shared machine vary from run to run, so each scene is built and rendered
//! `--repeat` times and the medians are reported; `--scaling` also renders each scene on one
//! thread, interleaved with the other renders so that both see the same machine.

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use clap::Args;
use raylab::backend::{Backend, RenderError};
use raylab::bvh::Bvh;
use raylab::color::Color;
use raylab::film::Film;
use raylab::formats::load_any;
use raylab::formats::toml::default_scene;
use raylab::gpu::bvh::NodeLayout;
use raylab::inspect::DebugView;
use raylab::large_mesh::{bumpy_sphere_scene, check_bumpy_triangles};
use raylab::output::{check_writable, write_atomically};
use raylab::photon::{Caustics, PhotonMap};
use raylab::progressive::{RenderControl, RenderStats};
use raylab::render::{Assembled, Device, FirstHit};
use raylab::scene::Scene;
use raylab::whitted::Tracer;

use super::bench_first_hits::bench_first_hits;
use super::bench_report::{self, BenchResult, CausticBench};
use super::median;
use super::overrides::parse_size;

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Scenes to run (default: the standard set). `default`, `bumpy:N` for the generated
    /// N-triangle mesh, or any scene `render` takes (`spd:balls`, a .nff or .toml file).
    #[arg(long, value_delimiter = ',')]
    scenes: Vec<String>,
    /// Image size: N for N×N, or WxH.
    #[arg(long, value_name = "N|WxH", default_value = "512", value_parser = parse_size)]
    size: (u32, u32),
    /// Worker threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Builds and renders per scene; the medians are reported.
    #[arg(long, default_value_t = 3)]
    repeat: usize,
    /// Also render each scene on one thread and report the speed-up of all threads over one.
    #[arg(long)]
    scaling: bool,
    /// Also write the results as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Which tracer renders: cpu (all cores) or gpu (wgpu compute, the adapter WGPU_BACKEND and
    /// WGPU_ADAPTER_NAME choose).
    #[arg(long, default_value_t = Device::Cpu)]
    device: Device,
    /// With --device gpu: how the GPU holds the BVH's nodes, wide (the CPU's eight-wide nodes,
    /// 256 bytes) or binary (two-wide nodes of 64 bytes over the same leaves).
    #[arg(long, default_value_t = NodeLayout::default())]
    gpu_nodes: NodeLayout,
    /// Where the eye rays find their first hits: rays, or raster (from the item buffer drawn
    /// on the GPU, which is timed too, with the first hits found both ways).
    #[arg(long, default_value_t = FirstHit::Rays)]
    first_hit: FirstHit,
}

/// The standard set: the default scene, the seven SPD databases at their standard sizes, and a
/// million generated triangles for traversal.
const STANDARD_SCENES: &[&str] = &[
    "default",
    "spd:balls:4",
    "spd:gears:4",
    "spd:mount:6",
    "spd:rings:7",
    "spd:teapot:12",
    "spd:tetra:6",
    "spd:tree:11",
    "bumpy:1000000",
];

pub fn run(args: BenchArgs) -> Result<(), String> {
    if args.repeat == 0 {
        return Err("--repeat must be at least 1".into());
    }
    if let Some(path) = &args.json {
        check_writable(path).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let pool = super::thread_pool(args.threads)?;
    let mut backend = Backend::new(Arc::clone(&pool));
    backend.set_device(args.device);
    backend.set_first_hit(args.first_hit);
    backend.set_gpu_nodes(args.gpu_nodes);
    let device = match args.device {
        Device::Cpu if args.gpu_nodes != NodeLayout::default() => {
            return Err("--gpu-nodes lays out the GPU's BVH: add --device gpu".into());
        }
        Device::Cpu => format!("{} threads", pool.current_num_threads()),
        Device::Gpu if args.scaling => {
            return Err("--scaling measures the CPU's threads: leave out --device gpu".into());
        }
        Device::Gpu => {
            let gpu = backend.gpu().map_err(|e| e.to_string())?;
            eprintln!("{}", super::compiling_notice(&gpu));
            match args.gpu_nodes {
                NodeLayout::Wide => format!("gpu: {}", gpu.name()),
                nodes => format!("gpu: {}; BVH nodes: {nodes}", gpu.name()),
            }
        }
    };
    // With --scaling, the same renders on one thread.
    let mut single = match args.scaling {
        true => Some(Backend::new(super::thread_pool(Some(1))?)),
        false => None,
    };
    let names: Vec<String> = if args.scenes.is_empty() {
        STANDARD_SCENES.iter().map(|s| s.to_string()).collect()
    } else {
        args.scenes.clone()
    };
    super::print_out(|out| {
        writeln!(out, "{}×{} pixels, {device}", args.size.0, args.size.1)?;
        bench_report::write_header(out, args.scaling)
    })?;
    let mut results = Vec::new();
    for name in &names {
        let result = bench_scene(name, &args, &mut backend, single.as_mut())?;
        super::print_out(|out| bench_report::write_row(out, &result))?;
        results.push(result);
    }
    let threads = pool.current_num_threads();
    if let Some(path) = &args.json {
        let json = bench_report::to_json(&results, args.size, threads);
        write_atomically(path, |e| e, |out| out.write_all(json.as_bytes()))
            .map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

fn load(name: &str, (width, height): (u32, u32)) -> Result<Scene, String> {
    let mut scene = if name == "default" {
        default_scene().map_err(|e| e.to_string())?
    } else if let Some(n) = name.strip_prefix("bumpy:") {
        let n: usize = n
            .parse()
            .map_err(|_| format!("`{name}`: expected bumpy:N with N a number of triangles"))?;
        check_bumpy_triangles(n).map_err(|e| format!("`{name}`: {e}"))?;
        bumpy_sphere_scene(n, width, height)
    } else {
        load_any(name).map_err(|e| e.to_string())?
    };
    scene.settings.width = width;
    scene.settings.height = height;
    scene.settings.validate()?;
    Ok(scene)
}

fn bench_scene(
    name: &str,
    args: &BenchArgs,
    backend: &mut Backend,
    mut single: Option<&mut Backend>,
) -> Result<BenchResult, String> {
    reset_peak_rss();
    let start = Instant::now();
    let scene = load(name, args.size)?;
    let setup = start.elapsed();
    // The render's BVH is the first of the `--repeat` builds timed.
    let pool = backend.pool();
    let mut assembled = pool.install(|| Assembled::without_caustics(scene));
    let mut builds = vec![assembled.bvh_time];
    for _ in 1..args.repeat {
        let start = Instant::now();
        drop(pool.install(|| Bvh::build(&assembled.scene.geometry)));
        builds.push(start.elapsed());
    }
    let caustics = match assembled.scene.settings.caustic_photons {
        0 => None,
        _ => {
            let (map, bench) = bench_caustics(
                &assembled.tracer(),
                args,
                pool,
                single.as_ref().map(|s| &**s.pool()),
            )?;
            assembled.caustics = Some(Arc::new(map));
            Some(bench)
        }
    };
    let view = DebugView::Shaded;
    let failed = |e| format!("{name}: {}", super::explain(e, view, args.first_hit));
    backend.prepare(&assembled, view).map_err(failed)?;
    // The CPU tracer's item buffers are drawn on the GPU before its render; the GPU tracer
    // draws its own within its render.
    let first_hits = match (args.first_hit, backend.device()) {
        (FirstHit::Raster, Device::Cpu) => {
            let size = (
                assembled.scene.settings.width,
                assembled.scene.settings.height,
            );
            let pool = Arc::clone(backend.pool());
            let mut draw = || match backend.item_buffer(&assembled, ((0, 0), size)) {
                Ok(Some(items)) => Ok(items),
                Ok(None) => Err(format!("{name}: no item buffer was drawn")),
                Err(e) => Err(failed(e)),
            };
            let tracer = assembled.tracer();
            Some(pool.install(|| bench_first_hits(&tracer, &mut draw, args.repeat))?)
        }
        _ => None,
    };
    let (mut renders, mut first_passes, mut single_renders) = (Vec::new(), Vec::new(), Vec::new());
    let mut renders_off = Vec::new();
    let mut rays = Default::default();
    let plain = Assembled {
        caustics: None,
        ..assembled.clone()
    };
    for _ in 0..args.repeat {
        if caustics.is_some() {
            renders_off.push(render(backend, &plain).map_err(failed)?.time);
        }
        let stats = render(backend, &assembled).map_err(failed)?;
        renders.push(stats.time);
        first_passes.push(stats.passes.first().map_or(Duration::ZERO, |p| p.time));
        rays = stats.rays;
        if let Some(single) = single.as_deref_mut() {
            single_renders.push(render(single, &assembled).map_err(failed)?.time);
        }
    }
    Ok(BenchResult {
        name: name.to_string(),
        primitives: assembled.scene.geometry.len(),
        setup,
        build: median(builds),
        first_pass: median(first_passes),
        render: median(renders),
        render_one_thread: single.map(|_| median(single_renders)),
        rays,
        scene_bytes: assembled.scene.geometry.memory_bytes() + assembled.bvh.memory_bytes(),
        peak_rss_bytes: peak_rss_bytes(),
        caustics: caustics.map(|c| CausticBench {
            render_off: median(renders_off),
            ..c
        }),
        first_hits,
    })
}

/// Renders `assembled`'s scene with `backend` pass after pass, as the viewer does.
fn render(backend: &mut Backend, assembled: &Assembled) -> Result<RenderStats, RenderError> {
    let settings = &assembled.scene.settings;
    let film = Film::new(settings.width, settings.height);
    let control = RenderControl::default();
    backend.render(assembled, DebugView::Shaded, (&film, &control), |_| {})
}

/// How many estimates the gather cost is the mean of.
const GATHER_QUERIES: usize = 20_000;

/// Shoots the scene's caustic photons `--repeat` times (on all threads, and on one with
/// `--scaling`), builds their map, and times estimates at the points where photons landed. The
/// map, and what it cost (its `render_off` left for the caller).
fn bench_caustics(
    tracer: &Tracer,
    args: &BenchArgs,
    pool: &rayon::ThreadPool,
    single: Option<&rayon::ThreadPool>,
) -> Result<(PhotonMap, CausticBench), String> {
    let settings = &tracer.scene.settings;
    let photons = settings.caustic_photons;
    let (mut shots, mut single_shots, mut builds) = (Vec::new(), Vec::new(), Vec::new());
    let mut map = PhotonMap::default();
    for _ in 0..args.repeat {
        let mut caustics = Caustics::new(tracer);
        let start = Instant::now();
        pool.install(|| caustics.shoot(tracer, photons))?;
        shots.push(start.elapsed());
        if let Some(single) = single {
            let mut caustics = Caustics::new(tracer);
            let start = Instant::now();
            single.install(|| caustics.shoot(tracer, photons))?;
            single_shots.push(start.elapsed());
        }
        let start = Instant::now();
        map = caustics.map()?;
        builds.push(start.elapsed());
    }
    // On one thread, at the photons' own landing points, seen from the side they came from.
    let stride = (map.len() / GATHER_QUERIES).max(1);
    let points: Vec<_> = map.photons().iter().step_by(stride).collect();
    let k = settings.caustic_gather as usize;
    let start = Instant::now();
    let total: Color = points
        .iter()
        .map(|p| map.irradiance(p.position, -p.dir, k))
        .sum();
    std::hint::black_box(total);
    let gather = start.elapsed() / points.len().max(1) as u32;
    let bench = CausticBench {
        photons,
        stored: map.len(),
        shoot: median(shots),
        shoot_one_thread: single.map(|_| median(single_shots)),
        build: median(builds),
        gather,
        render_off: Duration::ZERO,
    };
    Ok((map, bench))
}

/// Starts measuring the process's peak resident memory afresh (Linux: writing 5 to
/// /proc/self/clear_refs), so that each scene's peak is its own. Elsewhere the peak stays the
/// process's.
fn reset_peak_rss() {
    // Without the file there is nothing to reset, and the peak stays the whole process's.
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// The process's peak resident memory since the last reset (Linux: VmHWM in
/// /proc/self/status).
fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
