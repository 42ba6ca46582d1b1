//! What `raylab bench` measured for a scene, and how it is shown: a table row on the terminal
//! (with a line for the caustics of a scene that has them), and JSON.

use std::io::{self, Write};
use std::time::Duration;

use raylab::stats::RayCounts;

use super::bench_first_hits::FirstHitBench;

/// What one scene measured (times are medians over the repeats).
pub struct BenchResult {
    pub name: String,
    pub primitives: usize,
    /// Reading or generating the scene.
    pub setup: Duration,
    pub build: Duration,
    /// The coarsest pass of the progressive render.
    pub first_pass: Duration,
    /// The whole render, to block size 1.
    pub render: Duration,
    /// The whole render on one thread, with `--scaling`.
    pub render_one_thread: Option<Duration>,
    pub rays: RayCounts,
    /// Geometry and BVH.
    pub scene_bytes: usize,
    /// Peak resident memory while the scene was loaded, built and rendered.
    pub peak_rss_bytes: Option<u64>,
    /// For a scene with caustics on; `render` is then the render with them.
    pub caustics: Option<CausticBench>,
    /// With `--first-hit raster`; `render` is then the render from the item buffer.
    pub first_hits: Option<FirstHitBench>,
}

/// What the caustics of a scene cost (times are medians over the repeats).
pub struct CausticBench {
    /// Photons shot, and of them stored in the map.
    pub photons: u32,
    pub stored: usize,
    /// Shooting the photons on all threads, and on one with `--scaling`.
    pub shoot: Duration,
    pub shoot_one_thread: Option<Duration>,
    /// Building the kd-tree.
    pub build: Duration,
    /// One estimate (`caustic_gather` photons) at a diffuse point.
    pub gather: Duration,
    /// The render with caustics off.
    pub render_off: Duration,
}

impl CausticBench {
    /// Millions of photons shot per second in `time`.
    fn mphotons_per_second(&self, time: Duration) -> f64 {
        f64::from(self.photons) / time.as_secs_f64() / 1e6
    }
}

impl BenchResult {
    pub fn mrays_per_second(&self) -> f64 {
        self.rays.total() as f64 / self.render.as_secs_f64() / 1e6
    }

    pub fn bytes_per_primitive(&self) -> f64 {
        self.scene_bytes as f64 / self.primitives.max(1) as f64
    }

    /// Render time on one thread over render time on all.
    pub fn scaling(&self) -> Option<f64> {
        self.render_one_thread
            .map(|one| one.as_secs_f64() / self.render.as_secs_f64())
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn mib(bytes: Option<u64>) -> String {
    bytes.map_or("-".into(), |b| format!("{:.1}", b as f64 / 1048576.0))
}

/// The table's header line.
pub fn write_header(out: &mut impl Write, scaling: bool) -> io::Result<()> {
    write!(
        out,
        "{:<14} {:>8} {:>8} {:>8} {:>8} {:>9} {:>8} {:>8} {:>8} {:>8} {:>8}",
        "scene",
        "prims",
        "setup ms",
        "build ms",
        "pass1 ms",
        "render ms",
        "eye",
        "shadow",
        "reflect",
        "transmit",
        "Mrays/s"
    )?;
    if scaling {
        write!(out, " {:>9} {:>7}", "1-thr ms", "scaling")?;
    }
    writeln!(out, " {:>7} {:>8}", "B/prim", "peak MiB")
}

/// One scene's line of the table.
pub fn write_row(out: &mut impl Write, r: &BenchResult) -> io::Result<()> {
    write!(
        out,
        "{:<14} {:>8} {:>8.1} {:>8.1} {:>8.2} {:>9.1} {:>8} {:>8} {:>8} {:>8} {:>8.2}",
        r.name,
        r.primitives,
        ms(r.setup),
        ms(r.build),
        ms(r.first_pass),
        ms(r.render),
        r.rays.primary,
        r.rays.shadow,
        r.rays.reflected,
        r.rays.transmitted,
        r.mrays_per_second(),
    )?;
    if let (Some(one), Some(scaling)) = (r.render_one_thread, r.scaling()) {
        write!(out, " {:>9.1} {:>7.2}", ms(one), scaling)?;
    }
    writeln!(
        out,
        " {:>7.1} {:>8}",
        r.bytes_per_primitive(),
        mib(r.peak_rss_bytes)
    )?;
    if let Some(c) = &r.caustics {
        write!(
            out,
            "  caustics: {} photons ({} stored), shot at {:.2} M/s",
            c.photons,
            c.stored,
            c.mphotons_per_second(c.shoot)
        )?;
        if let Some(one) = c.shoot_one_thread {
            write!(
                out,
                " ({:.2} M/s on one thread)",
                c.mphotons_per_second(one)
            )?;
        }
        writeln!(
            out,
            ", map built in {:.1} ms, {:.2} µs per estimate; render {:.1} ms with, {:.1} ms without",
            ms(c.build),
            c.gather.as_secs_f64() * 1e6,
            ms(r.render),
            ms(c.render_off)
        )?;
    }
    if let Some(f) = &r.first_hits {
        writeln!(
            out,
            "  first hits: raster, {} of {} eye rays from the item buffer; raster pass and \
             read-back {:.1} ms; the eye rays' first hits {:.1} ms from the rays, {:.1} ms from the \
             item buffer; per eye ray, BVH nodes {:.2} and {:.2}, primitives tested {:.2} and {:.2}",
            f.from_item_buffer,
            f.eye_rays,
            ms(f.raster),
            ms(f.first_hits_rays),
            ms(f.first_hits_raster),
            f.cost_rays.0,
            f.cost_raster.0,
            f.cost_rays.1,
            f.cost_raster.1
        )?;
    }
    Ok(())
}

/// The first hits' JSON object, or `null`.
fn first_hits_json(f: Option<&FirstHitBench>) -> String {
    let Some(f) = f else {
        return "null".into();
    };
    format!(
        concat!(
            "{{\"eye_rays\": {}, \"from_item_buffer\": {}, \"raster_ms\": {:.3}, ",
            "\"first_hits_rays_ms\": {:.3}, \"first_hits_raster_ms\": {:.3}, ",
            "\"nodes_per_eye_ray_rays\": {:.3}, \"nodes_per_eye_ray_raster\": {:.3}, ",
            "\"prims_per_eye_ray_rays\": {:.3}, \"prims_per_eye_ray_raster\": {:.3}}}"
        ),
        f.eye_rays,
        f.from_item_buffer,
        ms(f.raster),
        ms(f.first_hits_rays),
        ms(f.first_hits_raster),
        f.cost_rays.0,
        f.cost_raster.0,
        f.cost_rays.1,
        f.cost_raster.1,
    )
}

/// The caustics' JSON object, or `null`.
fn caustics_json(c: Option<&CausticBench>) -> String {
    let Some(c) = c else {
        return "null".into();
    };
    format!(
        concat!(
            "{{\"photons\": {}, \"stored\": {}, \"shoot_ms\": {:.3}, \"shoot_one_thread_ms\": {}, ",
            "\"mphotons_per_s\": {:.3}, \"build_ms\": {:.3}, \"gather_us\": {:.3}, ",
            "\"render_off_ms\": {:.3}}}"
        ),
        c.photons,
        c.stored,
        ms(c.shoot),
        c.shoot_one_thread
            .map_or("null".into(), |d| format!("{:.3}", ms(d))),
        c.mphotons_per_second(c.shoot),
        ms(c.build),
        c.gather.as_secs_f64() * 1e6,
        ms(c.render_off),
    )
}

pub fn to_json(results: &[BenchResult], (width, height): (u32, u32), threads: usize) -> String {
    let null_or = |v: Option<String>| v.unwrap_or_else(|| "null".into());
    let scenes: Vec<String> = results
        .iter()
        .map(|r| {
            format!(
                concat!(
                    "    {{\"scene\": \"{}\", \"primitives\": {}, \"setup_ms\": {:.3}, ",
                    "\"build_ms\": {:.3}, \"first_pass_ms\": {:.3}, \"render_ms\": {:.3}, ",
                    "\"render_one_thread_ms\": {}, \"scaling\": {}, ",
                    "\"eye_rays\": {}, \"eye_hits\": {}, \"shadow_rays\": {}, ",
                    "\"reflected_rays\": {}, \"transmitted_rays\": {}, \"mrays_per_s\": {:.3}, ",
                    "\"scene_bytes\": {}, \"bytes_per_primitive\": {:.1}, \"peak_rss_bytes\": {}, ",
                    "\"caustics\": {}, \"first_hits\": {}}}"
                ),
                r.name,
                r.primitives,
                ms(r.setup),
                ms(r.build),
                ms(r.first_pass),
                ms(r.render),
                null_or(r.render_one_thread.map(|d| format!("{:.3}", ms(d)))),
                null_or(r.scaling().map(|s| format!("{s:.3}"))),
                r.rays.primary,
                r.rays.primary_hits,
                r.rays.shadow,
                r.rays.reflected,
                r.rays.transmitted,
                r.mrays_per_second(),
                r.scene_bytes,
                r.bytes_per_primitive(),
                null_or(r.peak_rss_bytes.map(|b| b.to_string())),
                caustics_json(r.caustics.as_ref()),
                first_hits_json(r.first_hits.as_ref()),
            )
        })
        .collect();
    format!(
        "{{\n  \"width\": {width},\n  \"height\": {height},\n  \"threads\": {threads},\n  \"scenes\": [\n{}\n  ]\n}}\n",
        scenes.join(",\n")
    )
}
