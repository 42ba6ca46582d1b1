//! What `raylab bench` measured for a scene, and how it is shown: a table row on the terminal
//! (with a line for the caustics of a scene that has them), and JSON.

use std::io::{self, Write};
use std::time::Duration;

use raylab::stats::RayCounts;
use serde_json::{Value, json};

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

/// `d` in milliseconds, to the microsecond.
fn ms_json(d: Duration) -> f64 {
    thousandths(ms(d))
}

/// `x` rounded to three decimals, as the JSON gives figures.
fn thousandths(x: f64) -> f64 {
    (x * 1e3).round() / 1e3
}

/// The first hits' JSON object.
fn first_hits_json(f: &FirstHitBench) -> Value {
    json!({
        "eye_rays": f.eye_rays,
        "from_item_buffer": f.from_item_buffer,
        "raster_ms": ms_json(f.raster),
        "first_hits_rays_ms": ms_json(f.first_hits_rays),
        "first_hits_raster_ms": ms_json(f.first_hits_raster),
        "nodes_per_eye_ray_rays": thousandths(f.cost_rays.0),
        "nodes_per_eye_ray_raster": thousandths(f.cost_raster.0),
        "prims_per_eye_ray_rays": thousandths(f.cost_rays.1),
        "prims_per_eye_ray_raster": thousandths(f.cost_raster.1),
    })
}

/// The caustics' JSON object.
fn caustics_json(c: &CausticBench) -> Value {
    json!({
        "photons": c.photons,
        "stored": c.stored,
        "shoot_ms": ms_json(c.shoot),
        "shoot_one_thread_ms": c.shoot_one_thread.map(ms_json),
        "mphotons_per_s": thousandths(c.mphotons_per_second(c.shoot)),
        "build_ms": ms_json(c.build),
        "gather_us": thousandths(c.gather.as_secs_f64() * 1e6),
        "render_off_ms": ms_json(c.render_off),
    })
}

/// One scene's JSON object.
fn scene_json(r: &BenchResult) -> Value {
    json!({
        "scene": r.name,
        "primitives": r.primitives,
        "setup_ms": ms_json(r.setup),
        "build_ms": ms_json(r.build),
        "first_pass_ms": ms_json(r.first_pass),
        "render_ms": ms_json(r.render),
        "render_one_thread_ms": r.render_one_thread.map(ms_json),
        "scaling": r.scaling().map(thousandths),
        "eye_rays": r.rays.primary,
        "eye_hits": r.rays.primary_hits,
        "shadow_rays": r.rays.shadow,
        "reflected_rays": r.rays.reflected,
        "transmitted_rays": r.rays.transmitted,
        "mrays_per_s": thousandths(r.mrays_per_second()),
        "scene_bytes": r.scene_bytes,
        "bytes_per_primitive": (r.bytes_per_primitive() * 10.0).round() / 10.0,
        "peak_rss_bytes": r.peak_rss_bytes,
        "caustics": r.caustics.as_ref().map(caustics_json),
        "first_hits": r.first_hits.as_ref().map(first_hits_json),
    })
}

/// The whole run as JSON: the image size, the threads and each scene's figures.
pub fn to_json(results: &[BenchResult], (width, height): (u32, u32), threads: usize) -> String {
    let report = json!({
        "width": width,
        "height": height,
        "threads": threads,
        "scenes": results.iter().map(scene_json).collect::<Vec<_>>(),
    });
    let mut text = serde_json::to_string_pretty(&report).expect("JSON of numbers and strings");
    text.push('\n');
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scene_names_are_escaped_in_the_json() {
        let name = "a \"quoted\" \\ name\twith\ncontrol characters";
        let result = BenchResult {
            name: name.into(),
            primitives: 3,
            setup: Duration::from_millis(1),
            build: Duration::from_millis(2),
            first_pass: Duration::from_millis(3),
            render: Duration::from_millis(40),
            render_one_thread: None,
            rays: RayCounts {
                primary: 100,
                shadow: 50,
                ..RayCounts::default()
            },
            scene_bytes: 1000,
            peak_rss_bytes: None,
            caustics: None,
            first_hits: None,
        };
        let text = to_json(&[result], (10, 10), 2);
        let parsed: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(parsed["scenes"][0]["scene"], name);
        assert_eq!(parsed["scenes"][0]["render_ms"], 40.0);
        assert_eq!(parsed["scenes"][0]["render_one_thread_ms"], Value::Null);
        assert_eq!(parsed["threads"], 2);
    }
}
