//! `raylab render`: a scene to an image file, or to a numbered sequence of them (a turntable or a
//! camera path, see `sequence`), with one progress bar and a one-line summary; or a part of it
//! (a tile or crop of some frames, see `jobs`) for `raylab merge`.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use raylab::backend::{Backend, RenderError};
use raylab::film::Film;
use raylab::formats::SceneFormat;
use raylab::formats::image::{OutputFormat, check_image_path, save_toned_pixels};
use raylab::formats::nff::NffLighting;
use raylab::formats::part::{PartInfo, scene_hash, write_part};
use raylab::inspect::DebugView;
use raylab::memory;
use raylab::progressive::{self, RenderControl, RenderStats};
use raylab::render::{Assembled, Device, FirstHit, assemble};
use raylab::settings::{RenderSettings, SettingsOverrides};
use raylab::tiles::Rect;
use raylab::tone::{Tone, ToneCurve};
use raylab::whitted::RAY_BUDGET;

use super::jobs::{self, TileArgs};
use super::overrides::OverrideArgs;
use super::sequence::{SequenceArgs, frame_paths};

#[derive(Args, Debug)]
pub struct RenderArgs {
    /// Scene: a .toml, .nff, SDL (.dat, .sdl), .obj, .ply, .gltf or .glb file, or a built-in SPD scene `spd:NAME[:SIZE]` (balls, gears,
    /// mount, rings, teapot, tetra, tree); the built-in default scene when left out.
    scene: Option<String>,
    /// The scene file's format, whatever its name ends in: toml, nff, sdl, obj or ply.
    #[arg(long)]
    format: Option<SceneFormat>,
    /// Output image: .png or .ppm (8-bit sRGB), .exr or .hdr (linear floats).
    #[arg(short, long, default_value = "out.png")]
    output: PathBuf,
    /// What the image shows: shaded, normals, depth, uv, object, material, item-buffer (the
    /// objects the item buffer's raster pass found, drawn on the GPU), tree-depth, rays or
    /// bvh-cost. For depth and the heat maps the scale is printed and its colour bar written
    /// beside the image as NAME.legend.png.
    #[arg(long, default_value_t = DebugView::Shaded)]
    view: DebugView,
    /// Overrides of the scene's render settings.
    #[command(flatten)]
    overrides: OverrideArgs,
    /// Worker threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
    /// Which tracer renders: cpu (all cores) or gpu (wgpu compute, the adapter WGPU_BACKEND and
    /// WGPU_ADAPTER_NAME choose). The GPU renders the shaded image and the first-hit views
    /// (normals, depth, uv, object, material); the heat maps (tree-depth, rays, bvh-cost) trace
    /// on the CPU only.
    #[arg(long, default_value_t = Device::Cpu)]
    device: Device,
    /// Where the eye rays find their first hits: rays (each searches the BVH) or raster (each
    /// starts from the item buffer, the lecture's modified Z-buffer, drawn on the GPU by one
    /// raster pass over the scene). The image is the same bit for bit.
    #[arg(long, default_value_t = FirstHit::Rays)]
    first_hit: FirstHit,
    /// Brightness of NFF and SPD scenes' lights: `readme` (each light and the ambient light
    /// √N/2N for N lights, the SPD readme's suggestion) or `povray` (each light 1/√N, no
    /// ambient light, as SPD's POV-Ray exporter writes them).
    #[arg(long, default_value_t = NffLighting::default())]
    nff_lights: NffLighting,
    #[command(flatten)]
    tone: ToneArgs,
    /// An image sequence instead of one image.
    #[command(flatten)]
    sequence: SequenceArgs,
    /// A part of the image, for `raylab merge`.
    #[command(flatten)]
    tiles: TileArgs,
}

/// How 8-bit images show the linear values (`render` and `merge`).
#[derive(Args, Debug)]
pub struct ToneArgs {
    /// Exposure in stops for .png and .ppm output: each stop doubles the linear values before
    /// the tone curve (.exr and .hdr keep the linear values).
    #[arg(
        long,
        value_name = "STOPS",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    exposure: f32,
    /// Tone curve for .png and .ppm output: clamp (values above 1 are white), reinhard or
    /// filmic (an ACES-like curve); .exr and .hdr keep the linear values.
    #[arg(long, value_name = "CURVE", default_value_t = ToneCurve::Clamp)]
    tonemap: ToneCurve,
}

impl ToneArgs {
    /// The tone for an image of `format` written to `output`, warning when it has no effect.
    pub fn tone(&self, format: OutputFormat, output: &Path) -> Result<Tone, String> {
        let tone =
            Tone::new(self.exposure, self.tonemap).map_err(|e| format!("--exposure: {e}"))?;
        if tone != Tone::default() && matches!(format, OutputFormat::Exr | OutputFormat::Hdr) {
            eprintln!(
                "warning: --exposure and --tonemap shape 8-bit images only; {} keeps the linear values",
                output.display()
            );
        }
        Ok(tone)
    }
}

pub fn run(args: RenderArgs) -> Result<(), String> {
    // Before any long work: the scene, the cameras and file names of the frames, the BVH, the
    // render.
    let format = check_image_path(&args.output).map_err(|e| e.to_string())?;
    let tone = args.tone.tone(format, &args.output)?;
    let mut scene = super::load_scene(args.scene.as_deref(), args.nff_lights, args.format)?;
    let overrides = SettingsOverrides::from(args.overrides);
    overrides.apply(&mut scene.settings)?;
    scene.camera = overrides.apply_camera(scene.camera.spec)?;
    let sequence = args.sequence.cameras(scene.camera.spec)?;
    let total = sequence.as_ref().map_or(1, |cameras| cameras.len() as u32);
    let (width, height) = (scene.settings.width, scene.settings.height);
    let job = jobs::pick(
        &args.tiles,
        args.sequence.frame(),
        args.sequence.range(total)?,
        (width, height),
        |name| std::env::var(name).ok(),
    )?;
    let (cameras, outputs) = match sequence {
        Some(cameras) => {
            let outputs = frame_paths(&args.output, job.frames.clone())?;
            let range = job.frames.start as usize..job.frames.end as usize;
            (cameras[range].to_vec(), outputs)
        }
        None => (vec![scene.camera], vec![args.output.clone()]),
    };
    if job.window.is_some() && format != OutputFormat::Exr {
        return Err(format!(
            "-o {}: a part (--tile, --crop) is written as .exr, with the linear values and what \
             `raylab merge` needs to know; merge writes the image in any format",
            args.output.display()
        ));
    }
    // A part's film reaches as far around it as the adaptive rounds look (`progressive`), so
    // that its pixels come out as in the whole image.
    let image = Rect::image(width, height);
    let traced = job.window.map_or(image, |(rect, _)| {
        rect.grown(progressive::decision_reach(&scene.settings), &image)
    });
    let pool = super::thread_pool(args.threads)?;
    let pixels = traced.pixels();
    memory::check(
        &if traced == image {
            format!("rendering a {width}×{height} image")
        } else {
            format!(
                "rendering {}×{} pixels (the part and its margin)",
                traced.width(),
                traced.height()
            )
        },
        Film::memory_bytes(traced.width(), traced.height())
            + progressive::memory_bytes(&scene.settings)
            + format.save_bytes(traced.width()),
    )?;

    let mut assembled = pool.install(|| assemble(scene))?;
    let mut backend = Backend::new(Arc::clone(&pool));
    backend.set_device(args.device);
    backend.set_first_hit(args.first_hit);
    let explain = |e: RenderError| super::explain(e, args.view, args.first_hit);
    backend.check(&assembled, args.view).map_err(explain)?;
    if args.device == Device::Gpu {
        let gpu = backend.gpu().map_err(|e| e.to_string())?;
        eprintln!("{}", super::compiling_notice(&gpu));
    }
    backend.prepare(&assembled, args.view).map_err(explain)?;
    let legend = args.view.legend(&assembled.tracer());
    let legend_path = super::legend_path(&outputs[0]);
    if legend.is_some() {
        check_image_path(&legend_path).map_err(|e| e.to_string())?;
    }
    let per_frame = pixels * u64::from(assembled.scene.settings.samples);
    let bar = progress_bar(per_frame * cameras.len() as u64);
    let mut stats = RenderStats::default();
    let mut written = Vec::new();
    for (k, (camera, output)) in cameras.iter().zip(&outputs).enumerate() {
        assembled.scene.camera = *camera;
        let done = per_frame * k as u64;
        let rendered = render_frame(&assembled, args.view, traced, &mut backend, |traced| {
            bar.set_position(done + traced)
        });
        let scene = &assembled.scene;
        let frame = rendered.and_then(|(film, frame_stats)| {
            match job.window {
                Some((rect, tile)) => {
                    let info = PartInfo {
                        width,
                        height,
                        rect,
                        scene: scene_hash(scene),
                        settings: format!("{:#?}\nview = {}", scene.settings, args.view),
                        tile,
                        frame: (total > 1).then_some(job.frames.start + k as u32),
                    };
                    write_part(output, &info, &film.pixels_in(rect)).map_err(|e| e.to_string())
                }
                // Read out of the film and tone mapped on the render's threads.
                None => {
                    let pixel = |x, y| film.get(x, y);
                    pool.install(|| save_toned_pixels(output, width, height, &pixel, tone))
                        .map_err(|e| e.to_string())
                }
            }?;
            written.push(output);
            Ok(frame_stats)
        });
        match frame {
            Ok(frame_stats) => {
                // Adaptive anti-aliasing traces fewer samples than the bar counts on.
                bar.set_position(done + per_frame);
                stats.rays += frame_stats.rays;
                stats.time += frame_stats.time;
                stats.raster_time += frame_stats.raster_time;
            }
            Err(e) => {
                // No partial sequence: the frames written so far go too.
                bar.finish_and_clear();
                for path in written {
                    let _ = std::fs::remove_file(path);
                }
                return Err(e);
            }
        }
    }
    bar.finish_and_clear();

    if let Some(legend) = &legend {
        super::save_legend(legend, &outputs[0])?;
    }
    if stats.rays.over_budget > 0 {
        eprintln!(
            "warning: {} reflected or transmitted rays were not traced: their pixels' ray trees \
             used up the budget of {RAY_BUDGET} rays per eye ray (raise min_weight or lower \
             max_depth)",
            stats.rays.over_budget
        );
    }
    // Printed once every file is written: a closed standard output ends the program.
    super::print_out(|out| {
        if cameras.len() > 1 {
            write!(out, "{} frames of ", cameras.len())?;
        }
        writeln!(
            out,
            "{}",
            summary(
                &assembled.scene.settings,
                &stats,
                assembled.bvh_time,
                backend.label(),
                &args.output
            )
        )?;
        if args.first_hit == FirstHit::Raster {
            write!(
                out,
                "first hits: raster, {} of {} eye rays from the item buffer",
                stats.rays.from_item_buffer, stats.rays.primary,
            )?;
            // The GPU tracer's raster pass is part of its render.
            if stats.raster_time > Duration::ZERO {
                let ms = stats.raster_time.as_secs_f64() * 1e3;
                write!(out, " (raster pass and read-back: {ms:.1} ms)")?;
            }
            writeln!(out)?;
        }
        if let Some(map) = &assembled.caustics {
            writeln!(
                out,
                "caustics: {} photons shot, {} stored, {:.3} s",
                map.shot(),
                map.len(),
                assembled.caustics_time.as_secs_f64()
            )?;
        }
        if let Some(legend) = &legend {
            writeln!(out, "{} → {}", legend.to_text(), legend_path.display())?;
        }
        Ok(())
    })
}

/// Renders the pixels `window` of an image of `assembled`'s scene with `backend`, telling
/// `progress` the pixels traced so far now and then.
fn render_frame(
    assembled: &Assembled,
    view: DebugView,
    window: Rect,
    backend: &mut Backend,
    progress: impl Fn(u64),
) -> Result<(Film, RenderStats), String> {
    let first_hit = backend.first_hit();
    let settings = &assembled.scene.settings;
    let film = Film::window(settings.width, settings.height, window);
    let control = RenderControl::default();
    let stats = std::thread::scope(|s| {
        // Nobody sees the coarse passes: the film is traced in one sweep. The bar moves every
        // 50 ms, and the render's end wakes this thread at once rather than at the next tick.
        let (done, finished) = mpsc::channel();
        let target = (&film, &control);
        let render = s.spawn(move || {
            let stats = backend.render_unwatched(assembled, view, target);
            // Should this thread panic instead, dropping `done` ends the wait too.
            let _ = done.send(());
            stats
        });
        while finished.recv_timeout(Duration::from_millis(50)) == Err(RecvTimeoutError::Timeout) {
            progress(control.pixels_traced());
        }
        render.join()
    })
    .map_err(|_| "the renderer crashed".to_string())?
    .map_err(|e| super::explain(e, view, first_hit))?;
    Ok((film, stats))
}

/// A bar on the terminal (hidden when stderr is not one).
fn progress_bar(total: u64) -> ProgressBar {
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}%")
            .expect("the template is valid"),
    );
    bar
}

/// One line: resolution, time, rays by kind, speed, the device, output.
fn summary(
    settings: &RenderSettings,
    stats: &RenderStats,
    build_time: Duration,
    device: &str,
    output: &Path,
) -> String {
    let r = &stats.rays;
    format!(
        "{}×{}: {:.3} s (BVH {:.1} ms), rays: {} eye ({} hit), {} shadow, {} reflected, {} transmitted; {:.2} Mrays/s ({device}) → {}",
        settings.width,
        settings.height,
        stats.time.as_secs_f64(),
        build_time.as_secs_f64() * 1e3,
        r.primary,
        r.primary_hits,
        r.shadow,
        r.reflected,
        r.transmitted,
        stats.mrays_per_second(),
        output.display()
    )
}
