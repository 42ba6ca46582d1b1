//! The GPU sweep of a progressive render: the same passes as the CPU's ([`super::plan`]), each
//! pass's pixel samples listed band by band of 8 rows of its grid, as the CPU sweeps them, and
//! traced on the GPU ([`crate::gpu::tracer`]) a few bands per dispatch, so that no dispatch
//! runs long enough for an operating system's GPU watchdog. The colours stay on the GPU: they go
//! into the film there ([`GpuFilm`]) as the CPU's go into its film (a block painted for a
//! pixel's first sample, otherwise a sample added to its mean), where a viewer on the same
//! device shows them ([`crate::gpu::film::FilmShow`]); only their ray counts come back. The
//! film on the CPU is a copy read back after each pass, from which the next pass's adaptive
//! rule reads and which is saved. A sample whose work the GPU's driver cut short (a driver may
//! bound the loop iterations of a shader, as Mesa's software Vulkan does) is traced again on
//! the CPU. Between dispatches the render waits while paused and stops when cancelled.

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::coloring::SampleColoring;
use super::control::{Cancelled, PassStats, RenderControl, RenderStats, run_plan};
use super::pass::PassStart;
use super::plan::{Pass, passes, sample_ray, unwatched_passes};
use crate::color::Color;
use crate::film::Film;
use crate::gpu::bvh::NodeLayout;
use crate::gpu::device::{ComputeEntry, GpuDevice};
use crate::gpu::film::GpuFilm;
use crate::gpu::frame::GpuView;
use crate::gpu::item_raster::ItemRaster;
use crate::gpu::prelude::WORKGROUP;
use crate::gpu::scene::GpuScene;
use crate::gpu::tracer::{PixelSample, SampleColor, dispatch_list, pipeline, upload_list};
use crate::item_buffer::ItemBuffer;
use crate::photon_map::PhotonMap;
use crate::render::{Assembled, FirstHit};
use crate::stats::RayCounts;
use crate::whitted::Tracer;

/// Rows of a pass's grid in a band, as the CPU's sweep takes them.
const BAND: u32 = 8;

/// How long one dispatch should take at most, unless told otherwise
/// ([`GpuRenderer::set_dispatch_time`]): well under the two seconds after which operating
/// systems reset a GPU that does not answer, and short enough to stop soon after a cancel.
pub const DISPATCH_TIME: Duration = Duration::from_millis(100);

/// Traces one sample on `gpu` and waits for it. A driver may compile the tracer only when it
/// first runs it (lavapipe: a minute or two, once a device): that time is the renderer's
/// making, not a render's, whose rays per second would count it.
fn warm_up(gpu: &GpuDevice, scene: &GpuScene, trace: &ComputeEntry) -> Result<(), String> {
    let sample = PixelSample {
        x: 0,
        y: 0,
        k: 0,
        item_t: 0.0,
    };
    let list = upload_list(gpu, &[sample], size_of::<SampleColor>() as u64)?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    dispatch_list(gpu, scene, trace, &list, &mut encoder);
    gpu.queue.submit([encoder.finish()]);
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| format!("the GPU did not finish: {e}"))?;
    Ok(())
}

/// A scene's objects, BVH, materials, lights and caustic photons on the GPU, ready to render it
/// from any camera with any of the settings the frame record carries (the switches, depth,
/// weights, sizes).
pub struct GpuRenderer {
    gpu: Arc<GpuDevice>,
    scene: GpuScene,
    trace: Arc<ComputeEntry>,
    /// The raster pass of the item buffer the eye rays start from (none: they search the BVH).
    first_hits: Option<ItemRaster>,
    /// How long one dispatch should take at most.
    dispatch_time: Duration,
}

impl GpuRenderer {
    /// Uploads `assembled` to `gpu`; the error says what the GPU does not trace or hold.
    pub fn new(gpu: Arc<GpuDevice>, assembled: &Assembled) -> Result<GpuRenderer, String> {
        GpuRenderer::with_nodes(gpu, assembled, NodeLayout::default())
    }

    /// [`Self::new`] with the BVH's nodes in `nodes` on the GPU.
    pub fn with_nodes(
        gpu: Arc<GpuDevice>,
        assembled: &Assembled,
        nodes: NodeLayout,
    ) -> Result<GpuRenderer, String> {
        let scene = GpuScene::upload_with(&gpu, assembled, nodes)?;
        let trace = pipeline(&gpu, "trace_samples", nodes);
        warm_up(&gpu, &scene, &trace)?;
        Ok(GpuRenderer {
            gpu,
            scene,
            trace,
            first_hits: None,
            dispatch_time: DISPATCH_TIME,
        })
    }

    /// Makes the eye rays find their first hits as `first_hit` says from the next render on:
    /// by searching the BVH, or starting from the item buffer, drawn on the GPU before each
    /// render (its raster pass compiled the first time).
    pub fn set_first_hit(&mut self, first_hit: FirstHit) {
        match first_hit {
            FirstHit::Rays => self.first_hits = None,
            FirstHit::Raster => {
                let nodes = self.scene.node_layout;
                let gpu = &self.gpu;
                self.first_hits
                    .get_or_insert_with(|| ItemRaster::new(gpu, nodes));
            }
        }
    }

    /// Makes each dispatch take about `time` at most (the default is [`DISPATCH_TIME`]): a
    /// window drawn on the same GPU waits for the dispatch in flight before its frame.
    pub fn set_dispatch_time(&mut self, time: Duration) {
        self.dispatch_time = time;
    }

    /// The device it renders on.
    pub fn gpu(&self) -> &GpuDevice {
        &self.gpu
    }

    /// Takes `caustics` as the scene's caustic photon map from now on (none: caustics off),
    /// uploading it unless it is the one the GPU holds; the error says if it does not fit.
    pub fn set_caustics(&mut self, caustics: Option<&Arc<PhotonMap>>) -> Result<(), String> {
        self.scene.set_caustics(&self.gpu, caustics)
    }

    /// Renders `tracer`'s scene (the one uploaded, with its camera and settings now) in `view`
    /// into `film` pass after pass as [`super::render`] does on the CPU, calling `on_pass`
    /// after each. `coloring` is the same view on the CPU, for the samples the driver cuts short.
    /// The error says why the GPU failed.
    pub fn render(
        &self,
        tracer: &Tracer,
        (view, coloring): (GpuView, &dyn SampleColoring),
        film: &Film,
        control: &RenderControl,
        on_pass: impl FnMut(&PassStats),
    ) -> Result<Result<RenderStats, Cancelled>, String> {
        let on_gpu = GpuFilm::new(&self.gpu, film)?;
        self.render_into(tracer, (view, coloring), (film, &on_gpu), control, on_pass)
    }

    /// [`Self::render`] into `on_gpu`, the film on the GPU, which a viewer on the same device
    /// shows as it fills; `film` (of the same size) gets a copy of it after each pass.
    pub fn render_into(
        &self,
        tracer: &Tracer,
        (view, coloring): (GpuView, &dyn SampleColoring),
        (film, on_gpu): (&Film, &GpuFilm),
        control: &RenderControl,
        on_pass: impl FnMut(&PassStats),
    ) -> Result<Result<RenderStats, Cancelled>, String> {
        let settings = &tracer.scene.settings;
        let plan = passes(
            settings.block_size,
            settings.samples,
            settings.aa_threshold > 0.0,
        );
        self.run(
            tracer,
            (view, coloring),
            &plan,
            (film, on_gpu),
            control,
            on_pass,
        )
    }

    /// [`Self::render_into`] for a film nobody looks at before it is finished, as
    /// [`super::render_unwatched`].
    pub fn render_unwatched(
        &self,
        tracer: &Tracer,
        (view, coloring): (GpuView, &dyn SampleColoring),
        (film, on_gpu): (&Film, &GpuFilm),
        control: &RenderControl,
    ) -> Result<Result<RenderStats, Cancelled>, String> {
        let settings = &tracer.scene.settings;
        let plan = unwatched_passes(settings.samples, settings.aa_threshold > 0.0);
        self.run(
            tracer,
            (view, coloring),
            &plan,
            (film, on_gpu),
            control,
            |_| {},
        )
    }

    /// Runs `plan`; a GPU failure ends the render with its message.
    fn run(
        &self,
        tracer: &Tracer,
        (view, coloring): (GpuView, &dyn SampleColoring),
        plan: &[Pass],
        (film, on_gpu): (&Film, &GpuFilm),
        control: &RenderControl,
        on_pass: impl FnMut(&PassStats),
    ) -> Result<Result<RenderStats, Cancelled>, String> {
        let scene = tracer.scene;
        let origin = film.origin();
        self.scene
            .update(&self.gpu, scene, &scene.camera, view, origin)?;
        // The item buffer, read back to give each pixel sample its item's distance.
        let items = match &self.first_hits {
            Some(raster) => {
                let size = (film.width(), film.height());
                let on_gpu = raster.draw(&self.gpu, &self.scene, scene, size)?;
                Some(on_gpu.read_back(&self.gpu, film.image_size(), origin)?)
            }
            None => None,
        };
        let mut shown = Vec::new();
        let mut failure = None;
        let mut batch_bands = 1;
        let stats = run_plan(plan, control, on_pass, |pass| {
            let sweep = Sweep {
                tracer,
                coloring,
                film,
                on_gpu,
                items: items.as_ref(),
                control,
            };
            let result = self.run_pass(&sweep, pass, &mut shown, &mut batch_bands);
            result.map_err(|e| {
                if let Some(message) = e {
                    failure = Some(message);
                    control.cancel();
                }
                Cancelled
            })
        });
        match failure {
            Some(message) => Err(message),
            None => Ok(stats),
        }
    }

    /// One pass over the film, `batch_bands` bands per dispatch (adjusted to the time each
    /// takes). `Err(None)` when cancelled, `Err(Some(message))` when the GPU failed.
    fn run_pass(
        &self,
        sweep: &Sweep,
        pass: Pass,
        shown: &mut Vec<[u8; 3]>,
        batch_bands: &mut u32,
    ) -> Result<PassStats, Option<String>> {
        let Sweep { film, control, .. } = *sweep;
        let settings = &sweep.tracer.scene.settings;
        let setup = (settings.block_size, settings.aa_threshold);
        let start = PassStart::new(pass, film, shown, setup, control);
        let (grid, rows, columns, step) = (&start.grid, start.rows, start.columns, pass.step());
        // At most as many rows a dispatch as their samples fit one dispatch: however fast the
        // GPU, a list stays within its limits.
        let pixel_samples = match pass {
            Pass::Block(_) | Pass::Sample(_) => 1,
            Pass::Refine(n) | Pass::Sweep(n) => n,
        };
        let row_samples = u64::from(columns) * u64::from(pixel_samples.max(1));
        let most_rows = (most_samples(&self.gpu) / row_samples.max(1)).clamp(1, u64::from(rows));
        let mut pixels = 0;
        let mut band_start = 0;
        while band_start < rows {
            control.wait_for_band().map_err(|Cancelled| None)?;
            let batch_rows = (*batch_bands * BAND).min(most_rows as u32);
            let band_end = (band_start + batch_rows).min(rows);
            let mut samples = Vec::new();
            for row in band_start..band_end {
                for column in 0..columns {
                    let (x, y) = (column * step, row * step);
                    let taken = grid.samples_at(x, y);
                    pixels += u64::from(!taken.is_empty());
                    let item_t = sweep
                        .items
                        .and_then(|items| items.at(x, y))
                        .map_or(0.0, |item| item.t);
                    samples.extend(taken.map(|k| PixelSample { x, y, k, item_t }));
                }
            }
            let dispatched = Instant::now();
            let counts = self.trace_batch(sweep, &samples, step).map_err(Some)?;
            *batch_bands = next_batch(*batch_bands, dispatched.elapsed(), self.dispatch_time);
            control.band_done(band_end - band_start, samples.len() as u64, &counts);
            film.touch_rows(band_start * step..band_end * step);
            band_start = band_end;
        }
        sweep.on_gpu.read_into(&self.gpu, film).map_err(Some)?;
        film.touch();
        Ok(start.finish(control, pixels))
    }

    /// Traces `samples` (of a pass of block side `step`) on the GPU into the GPU's film, those
    /// the driver cuts short again on the CPU; returns their rays.
    fn trace_batch(
        &self,
        sweep: &Sweep,
        samples: &[PixelSample],
        step: u32,
    ) -> Result<RayCounts, String> {
        if samples.is_empty() {
            return Ok(RayCounts::default());
        }
        let gpu = &self.gpu;
        let colors_bytes = samples.len() * size_of::<SampleColor>();
        let list = upload_list(gpu, samples, colors_bytes as u64)?;
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        dispatch_list(gpu, &self.scene, &self.trace, &list, &mut encoder);
        let (tally, cut) = sweep.on_gpu.add(gpu, encoder, &list, step)?;
        let mut counts = tally.counts();
        if !cut.is_empty() {
            let again: Vec<PixelSample> = cut.iter().map(|&i| samples[i as usize]).collect();
            let colors: Vec<Color> = again
                .iter()
                .map(|s| sweep.trace_on_cpu(s, &mut counts))
                .collect();
            sweep.on_gpu.put(gpu, &again, &colors, step)?;
        }
        Ok(counts)
    }
}

/// What a pass sweeps: the tracer and the CPU's colouring of the view (for the samples the GPU's
/// driver cuts short), the film on the GPU and its copy, the item buffer the eye rays start
/// from, and the control.
struct Sweep<'a> {
    tracer: &'a Tracer<'a>,
    coloring: &'a dyn SampleColoring,
    film: &'a Film,
    on_gpu: &'a GpuFilm,
    items: Option<&'a ItemBuffer>,
    control: &'a RenderControl,
}

impl Sweep<'_> {
    /// The colour of sample `s` traced on the CPU, as the CPU sweep traces it, counting its
    /// rays into `counts`.
    fn trace_on_cpu(&self, s: &PixelSample, counts: &mut RayCounts) -> Color {
        let ray = sample_ray(&self.tracer.scene.camera, self.film, (s.x, s.y), s.k);
        let mut color = [Color::ZERO];
        let item = self.items.and_then(|items| items.at(s.x, s.y));
        self.coloring
            .shade(self.tracer, &[ray], &[item], &mut color, counts);
        color[0]
    }
}

/// The most samples one dispatch takes: as many as the GPU runs workgroups for in one dispatch,
/// and as many as one storage buffer holds the colours of.
fn most_samples(gpu: &GpuDevice) -> u64 {
    let limits = gpu.device.limits();
    let invocations = u64::from(limits.max_compute_workgroups_per_dimension) * u64::from(WORKGROUP);
    let buffer = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    invocations.min(buffer / size_of::<SampleColor>() as u64)
}

/// The bands the next dispatch takes, after one of `bands` took `took`: as many as fit in
/// `budget`, at most twice as many as before.
fn next_batch(bands: u32, took: Duration, budget: Duration) -> u32 {
    let per_band = took.as_secs_f64() / f64::from(bands);
    let fit = (budget.as_secs_f64() / per_band.max(1e-9)) as u32;
    fit.clamp(1, bands.saturating_mul(2).max(1))
}
