//! The one place where a render's device is chosen. A [`Backend`] runs a plan's passes on the
//! CPU's threads ([`crate::progressive::cpu`]) or on the GPU ([`crate::progressive::gpu`]), its eye rays finding their
//! first hits by searching the BVH or starting from the item buffer, and says why a render did
//! not finish in one error type, [`RenderError`]. `raylab render`, `bench` and `inspect`, the
//! viewer's render worker and the examples all render through it; none of them chooses between
//! the tracers itself.
//!
//! It opens the GPU the first time a render asks for it, and uploads a scene once however many
//! cameras, settings and edited materials render it: the upload is kept for as long as the
//! renders' [`Assembled`] share its BVH (a new scene has a new BVH). A backend may fall back
//! ([`Backend::set_fallback`]): where the GPU cannot render (none, a view it does not draw, a
//! scene it does not hold), the CPU renders, and [`Backend::label`] says why.

use std::fmt;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::film::Film;
use crate::inspect::DebugView;
use crate::item_buffer::ItemBuffer;
use crate::progressive::{Cancelled, PassStats, RenderControl, RenderStats, cpu};
use crate::render::{Assembled, Device, FirstHit};

#[cfg(feature = "gpu")]
use on_gpu::OnGpu;
#[cfg(not(feature = "gpu"))]
use without_gpu::OnGpu;

/// Why a render (or the item buffer a render starts from) did not come.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum RenderError {
    /// Another thread cancelled it through its [`RenderControl`].
    Cancelled,
    /// The GPU does not draw this debug view: it is traced on the CPU only.
    ViewOnCpuOnly(DebugView),
    /// No GPU could be opened for what needs one; `why` is the adapter's (or wgpu's) words and
    /// what to install.
    NoGpu { needed_for: GpuUse, why: String },
    /// The GPU does not hold the scene (or the film): `why` says what does not fit.
    NotOnGpu { needed_for: GpuUse, why: String },
    /// The GPU failed while it rendered.
    GpuFailed(String),
}

/// What a render needs a GPU for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GpuUse {
    /// The GPU tracer.
    Tracer,
    /// The item buffer the CPU tracer's eye rays start from (or its debug view shows).
    ItemBuffer,
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self {
            RenderError::Cancelled => write!(f, "the render was cancelled"),
            RenderError::NoGpu {
                needed_for: GpuUse::Tracer,
                why,
            } => write!(f, "{why}"),
            RenderError::NoGpu {
                needed_for: GpuUse::ItemBuffer,
                why,
            } => write!(f, "the item buffer is drawn on the GPU: {why}"),
            RenderError::ViewOnCpuOnly(view) => {
                write!(f, "the {view} view is drawn on the CPU only")
            }
            RenderError::NotOnGpu { why, .. } => write!(f, "{why}"),
            RenderError::GpuFailed(why) => write!(f, "the GPU failed: {why}"),
        }
    }
}

impl std::error::Error for RenderError {}

impl From<Cancelled> for RenderError {
    fn from(Cancelled: Cancelled) -> RenderError {
        RenderError::Cancelled
    }
}

/// Renders on the device and with the first-hit search it is set to; see the module's
/// documentation.
pub struct Backend {
    pool: Arc<rayon::ThreadPool>,
    device: Device,
    first_hit: FirstHit,
    fallback: bool,
    /// The device [`Self::prepare`] chose (the one asked for, or the CPU in a fallback).
    chosen: Device,
    /// What renders, and why not what was asked.
    label: String,
    gpu: OnGpu,
}

/// Who watches a render.
struct Watch<'a> {
    /// Told after each pass; `None`: nobody looks before the film is finished, and the render
    /// takes no coarse passes.
    on_pass: Option<&'a mut (dyn FnMut(&PassStats) + Send)>,
    /// Given the film on the GPU before the GPU renders into it.
    #[cfg(feature = "gpu")]
    show: Option<&'a mut dyn FnMut(Arc<crate::gpu::film::GpuFilm>)>,
}

impl Backend {
    /// Renders on the CPU on `pool`'s threads, first hits from the rays, until told otherwise.
    pub fn new(pool: Arc<rayon::ThreadPool>) -> Backend {
        Backend {
            label: cpu_label(&pool),
            pool,
            device: Device::Cpu,
            first_hit: FirstHit::Rays,
            fallback: false,
            chosen: Device::Cpu,
            gpu: OnGpu::default(),
        }
    }

    /// [`Self::new`] on a pool of one thread per core.
    pub fn on_all_cores() -> Result<Backend, String> {
        let pool = rayon::ThreadPoolBuilder::new()
            .build()
            .map_err(|e| format!("cannot start the tracing threads: {e}"))?;
        Ok(Backend::new(Arc::new(pool)))
    }

    /// Renders on `device` from the next render on.
    pub fn set_device(&mut self, device: Device) {
        self.device = device;
    }

    /// The device asked for.
    pub fn device(&self) -> Device {
        self.device
    }

    /// Finds the eye rays' first hits as `first_hit` says from the next render on.
    pub fn set_first_hit(&mut self, first_hit: FirstHit) {
        self.first_hit = first_hit;
    }

    /// The first-hit search asked for.
    pub fn first_hit(&self) -> FirstHit {
        self.first_hit
    }

    /// With `fallback`, what the GPU cannot do the CPU does: a render asked of the GPU renders
    /// on the CPU, and first hits asked of the item buffer come from the rays, where the GPU is
    /// missing, does not draw the view or does not hold the scene; [`Self::label`] says why.
    /// Without (the default), those are errors.
    pub fn set_fallback(&mut self, fallback: bool) {
        self.fallback = fallback;
    }

    /// The CPU's threads, which render on the CPU (and trace what the GPU's driver cuts short).
    pub fn pool(&self) -> &Arc<rayon::ThreadPool> {
        &self.pool
    }

    /// What renders, as a summary names it: `cpu: N threads` or `gpu: ADAPTER (BACKEND)`, and
    /// with a fallback why not what was asked. It is known once [`Self::prepare`] (or a render)
    /// has chosen.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// Renders on `gpu` (a window's, so that it can show the GPU's film) when a render asks for
    /// the GPU, rather than opening one.
    #[cfg(feature = "gpu")]
    pub fn set_gpu(&mut self, gpu: Arc<crate::gpu::device::GpuDevice>) {
        self.gpu.set_device(gpu);
    }

    /// The GPU the GPU tracer renders on, opened now if it is not yet.
    #[cfg(feature = "gpu")]
    pub fn gpu(&mut self) -> Result<Arc<crate::gpu::device::GpuDevice>, RenderError> {
        self.gpu.device(GpuUse::Tracer)
    }

    /// Lays out the BVH's nodes on the GPU as `nodes` from the next upload on.
    #[cfg(feature = "gpu")]
    pub fn set_gpu_nodes(&mut self, nodes: crate::gpu::bvh::NodeLayout) {
        if self.gpu.nodes != nodes {
            self.gpu.nodes = nodes;
            self.gpu.forget_scene();
        }
    }

    /// Makes each of the GPU's dispatches take about `time` at most
    /// ([`crate::progressive::gpu::DISPATCH_TIME`] unless told): a window drawn on the same GPU waits for the
    /// dispatch in flight before its frame.
    #[cfg(feature = "gpu")]
    pub fn set_dispatch_time(&mut self, time: std::time::Duration) {
        self.gpu.dispatch_time = time;
        self.gpu.forget_scene();
    }

    /// Refuses, before anything is opened, uploaded or compiled, what [`Self::prepare`] would
    /// refuse for `view`: a view the GPU does not draw, asked of the GPU without a fallback.
    pub fn check(&self, assembled: &Assembled, view: DebugView) -> Result<(), RenderError> {
        match self.device {
            Device::Gpu if !self.fallback => OnGpu::draws(assembled, view),
            _ => Ok(()),
        }
    }

    /// Gets everything ready for rendering `assembled` in `view` as the backend is set: opens
    /// the GPU, uploads the scene and compiles its programs (a minute or two the first time on a
    /// software adapter), so that the renders that follow time only their rays. A render
    /// prepares itself too; this lets a program fail before it starts, or say what it will use.
    pub fn prepare(&mut self, assembled: &Assembled, view: DebugView) -> Result<(), RenderError> {
        self.label = cpu_label(&self.pool);
        self.chosen = Device::Cpu;
        if self.device == Device::Gpu {
            match self.gpu.tracer(assembled, view, self.first_hit) {
                Ok(name) => {
                    self.label = format!("gpu: {name}");
                    self.chosen = Device::Gpu;
                    return Ok(());
                }
                Err(e) if self.fallback => self.label += &format!(" (not the GPU: {e})"),
                Err(e) => return Err(e),
            }
        }
        if self.cpu_needs_items(view) {
            match self.gpu.items(assembled) {
                Ok(_) => {}
                Err(e) if self.fallback => {
                    self.label += &format!(" (first hits from the rays: {e})")
                }
                Err(e) => return Err(e),
            }
        }
        Ok(())
    }

    /// Renders `assembled`'s scene (with its camera and settings now) as `view` shows it into
    /// `film` pass after pass, coarse blocks first, calling `on_pass` after each.
    pub fn render(
        &mut self,
        assembled: &Assembled,
        view: DebugView,
        (film, control): (&Film, &RenderControl),
        mut on_pass: impl FnMut(&PassStats) + Send,
    ) -> Result<RenderStats, RenderError> {
        let watch = Watch {
            on_pass: Some(&mut on_pass),
            #[cfg(feature = "gpu")]
            show: None,
        };
        self.run(assembled, view, (film, control), watch)
    }

    /// [`Self::render`] for a film nobody looks at before it is finished (a render to a file):
    /// no coarse passes, the same film in the end.
    pub fn render_unwatched(
        &mut self,
        assembled: &Assembled,
        view: DebugView,
        (film, control): (&Film, &RenderControl),
    ) -> Result<RenderStats, RenderError> {
        let watch = Watch {
            on_pass: None,
            #[cfg(feature = "gpu")]
            show: None,
        };
        self.run(assembled, view, (film, control), watch)
    }

    /// The whole image of `assembled`'s scene, shaded, as [`Self::render_unwatched`] renders it.
    pub fn render_image(
        &mut self,
        assembled: &Assembled,
    ) -> Result<(Film, RenderStats), RenderError> {
        let settings = &assembled.scene.settings;
        let film = Film::new(settings.width, settings.height);
        let control = RenderControl::default();
        let stats = self.render_unwatched(assembled, DebugView::Shaded, (&film, &control))?;
        Ok((film, stats))
    }

    /// [`Self::render`], handing `show` the film on the GPU before the GPU renders into it, for a
    /// window on the same device to show as it fills (on the CPU, `show` is not called).
    #[cfg(feature = "gpu")]
    pub fn render_shown(
        &mut self,
        assembled: &Assembled,
        view: DebugView,
        (film, control): (&Film, &RenderControl),
        mut on_pass: impl FnMut(&PassStats) + Send,
        mut show: impl FnMut(Arc<crate::gpu::film::GpuFilm>),
    ) -> Result<RenderStats, RenderError> {
        let watch = Watch {
            on_pass: Some(&mut on_pass),
            show: Some(&mut show),
        };
        self.run(assembled, view, (film, control), watch)
    }

    /// The item buffer the CPU tracer's eye rays start from for a film of `size` at `origin` of
    /// `assembled`'s image, drawn on the GPU; `None` with first hits from the rays (or, with a
    /// fallback, when the GPU cannot draw it).
    pub fn item_buffer(
        &mut self,
        assembled: &Assembled,
        window: ((u32, u32), (u32, u32)),
    ) -> Result<Option<ItemBuffer>, RenderError> {
        match self.first_hit {
            FirstHit::Rays => Ok(None),
            FirstHit::Raster => self.draw_items(assembled, window),
        }
    }

    /// The item buffer, drawn; `None` when the GPU cannot and the backend falls back.
    fn draw_items(
        &mut self,
        assembled: &Assembled,
        window: ((u32, u32), (u32, u32)),
    ) -> Result<Option<ItemBuffer>, RenderError> {
        let drawn = self.gpu.items(assembled).and_then(|items| {
            items
                .draw(&assembled.scene, window)
                .map_err(|why| RenderError::NotOnGpu {
                    needed_for: GpuUse::ItemBuffer,
                    why,
                })
        });
        match drawn {
            Ok(items) => Ok(Some(items)),
            Err(_) if self.fallback => Ok(None),
            Err(e) => Err(e),
        }
    }

    /// Whether a render on the CPU in `view` starts from the item buffer (or shows it).
    fn cpu_needs_items(&self, view: DebugView) -> bool {
        self.first_hit == FirstHit::Raster || view == DebugView::ItemBuffer
    }

    /// Renders on the device [`Self::prepare`] chooses, with the plan `watch` asks for.
    fn run(
        &mut self,
        assembled: &Assembled,
        view: DebugView,
        (film, control): (&Film, &RenderControl),
        watch: Watch,
    ) -> Result<RenderStats, RenderError> {
        self.prepare(assembled, view)?;
        if self.chosen == Device::Gpu {
            return self.gpu.render(assembled, view, (film, control), watch);
        }
        let window = (film.origin(), (film.width(), film.height()));
        let started = Instant::now();
        let items = match self.cpu_needs_items(view) {
            true => self.draw_items(assembled, window)?,
            false => None,
        };
        let raster_time = items.as_ref().map_or(Duration::ZERO, |_| started.elapsed());
        let tracer = assembled.tracer().with_item_buffer(items.as_ref());
        let rendered = self.pool.install(|| match watch.on_pass {
            Some(on_pass) => cpu::render(&tracer, &view, film, control, on_pass),
            None => cpu::render_unwatched(&tracer, &view, film, control),
        });
        Ok(RenderStats {
            raster_time,
            ..rendered?
        })
    }
}

/// The CPU as a label names it.
fn cpu_label(pool: &rayon::ThreadPool) -> String {
    format!("cpu: {} threads", pool.current_num_threads())
}

/// What the backend holds on the GPU: the device, and the scene uploaded for the GPU tracer or
/// for the CPU tracer's item buffers.
#[cfg(feature = "gpu")]
mod on_gpu {
    use std::sync::Arc;
    use std::time::Duration;

    use super::{GpuUse, RenderError, Watch};
    use crate::bvh::Bvh;
    use crate::film::Film;
    use crate::gpu::bvh::NodeLayout;
    use crate::gpu::device::GpuDevice;
    use crate::gpu::film::GpuFilm;
    use crate::gpu::item_raster::CpuItems;
    use crate::inspect::DebugView;
    use crate::progressive::control::{RenderControl, RenderStats};
    use crate::progressive::gpu::{DISPATCH_TIME, GpuRenderer};
    use crate::render::{Assembled, FirstHit};

    /// The GPU, opened when first asked for, and what is uploaded to it.
    pub struct OnGpu {
        device: Option<Result<Arc<GpuDevice>, String>>,
        /// The BVH of the scene uploaded, held so that no other scene's takes its address.
        scene: Option<Arc<Bvh>>,
        renderer: Option<Result<GpuRenderer, String>>,
        items: Option<Result<CpuItems, String>>,
        pub nodes: NodeLayout,
        pub dispatch_time: Duration,
    }

    impl Default for OnGpu {
        fn default() -> OnGpu {
            OnGpu {
                device: None,
                scene: None,
                renderer: None,
                items: None,
                nodes: NodeLayout::default(),
                dispatch_time: DISPATCH_TIME,
            }
        }
    }

    impl OnGpu {
        /// Renders on `gpu` rather than opening one.
        pub fn set_device(&mut self, gpu: Arc<GpuDevice>) {
            self.device = Some(Ok(gpu));
            self.forget_scene();
        }

        /// Uploads again at the next use.
        pub fn forget_scene(&mut self) {
            self.scene = None;
            self.renderer = None;
            self.items = None;
        }

        /// The GPU, opened the first time.
        pub fn device(&mut self, needed_for: GpuUse) -> Result<Arc<GpuDevice>, RenderError> {
            self.device
                .get_or_insert_with(|| GpuDevice::new().map(Arc::new))
                .clone()
                .map_err(|why| RenderError::NoGpu { needed_for, why })
        }

        /// Forgets what is uploaded when `assembled` is another scene than it.
        fn follow(&mut self, assembled: &Assembled) {
            let same = self
                .scene
                .as_ref()
                .is_some_and(|bvh| Arc::ptr_eq(bvh, &assembled.bvh));
            if !same {
                self.forget_scene();
                self.scene = Some(Arc::clone(&assembled.bvh));
            }
        }

        /// Whether the GPU tracer draws `view` of `assembled`.
        pub fn draws(assembled: &Assembled, view: DebugView) -> Result<(), RenderError> {
            match view.on_gpu(&assembled.tracer()) {
                Ok(_) => Ok(()),
                Err(_) => Err(RenderError::ViewOnCpuOnly(view)),
            }
        }

        /// Readies the GPU tracer for `assembled` in `view`: the scene uploaded (once a scene),
        /// its caustic photon map and the first-hit search set. Gives the adapter's name.
        pub fn tracer(
            &mut self,
            assembled: &Assembled,
            view: DebugView,
            first_hit: FirstHit,
        ) -> Result<String, RenderError> {
            OnGpu::draws(assembled, view)?;
            let gpu = self.device(GpuUse::Tracer)?;
            self.follow(assembled);
            let (nodes, dispatch_time) = (self.nodes, self.dispatch_time);
            let renderer = self
                .renderer
                .get_or_insert_with(|| {
                    let mut renderer = GpuRenderer::with_nodes(gpu, assembled, nodes)?;
                    renderer.set_dispatch_time(dispatch_time);
                    Ok(renderer)
                })
                .as_mut()
                .map_err(|e| not_on_gpu(GpuUse::Tracer, e.clone()))?;
            renderer
                .set_caustics(assembled.caustics.as_ref())
                .map_err(|e| not_on_gpu(GpuUse::Tracer, e))?;
            renderer.set_first_hit(first_hit);
            Ok(renderer.gpu().name())
        }

        /// Renders on the GPU tracer [`Self::tracer`] readied.
        pub fn render(
            &mut self,
            assembled: &Assembled,
            view: DebugView,
            (film, control): (&Film, &RenderControl),
            watch: Watch,
        ) -> Result<RenderStats, RenderError> {
            let tracer = assembled.tracer();
            let on_gpu = view
                .on_gpu(&tracer)
                .map_err(|_| RenderError::ViewOnCpuOnly(view))?;
            let Some(Ok(renderer)) = &self.renderer else {
                let why = "no scene on the GPU".to_string();
                return Err(not_on_gpu(GpuUse::Tracer, why));
            };
            let film_on_gpu = GpuFilm::new(renderer.gpu(), film)
                .map(Arc::new)
                .map_err(|e| not_on_gpu(GpuUse::Tracer, e))?;
            if let Some(show) = watch.show {
                show(Arc::clone(&film_on_gpu));
            }
            let target = (film, film_on_gpu.as_ref());
            let views = (on_gpu, &view as &dyn crate::progressive::SampleColoring);
            let rendered = match watch.on_pass {
                Some(on_pass) => renderer.render_into(&tracer, views, target, control, on_pass),
                None => renderer.render_unwatched(&tracer, views, target, control),
            };
            Ok(rendered.map_err(RenderError::GpuFailed)??)
        }

        /// `assembled`'s scene uploaded (once a scene) for the CPU tracer's item buffers.
        pub fn items(&mut self, assembled: &Assembled) -> Result<&CpuItems, RenderError> {
            let gpu = self.device(GpuUse::ItemBuffer)?;
            self.follow(assembled);
            self.items
                .get_or_insert_with(|| CpuItems::new(gpu, assembled))
                .as_ref()
                .map_err(|e| not_on_gpu(GpuUse::ItemBuffer, e.clone()))
        }
    }

    fn not_on_gpu(needed_for: GpuUse, why: String) -> RenderError {
        RenderError::NotOnGpu { needed_for, why }
    }
}

/// A library built without the GPU: what needs one is refused, saying so.
#[cfg(not(feature = "gpu"))]
mod without_gpu {
    use super::{GpuUse, RenderError, Watch};
    use crate::film::Film;
    use crate::inspect::DebugView;
    use crate::item_buffer::ItemBuffer;
    use crate::progressive::control::{RenderControl, RenderStats};
    use crate::render::{Assembled, FirstHit};
    use crate::scene::Scene;

    #[derive(Default)]
    pub struct OnGpu {}

    /// Item buffers that cannot be: there is no GPU to draw them.
    pub enum NoItems {}

    impl NoItems {
        pub fn draw(&self, _: &Scene, _: ((u32, u32), (u32, u32))) -> Result<ItemBuffer, String> {
            match *self {}
        }
    }

    fn refused(needed_for: GpuUse) -> RenderError {
        let why = "this raylab was built without its `gpu` feature".to_string();
        RenderError::NoGpu { needed_for, why }
    }

    impl OnGpu {
        pub fn draws(_: &Assembled, _: DebugView) -> Result<(), RenderError> {
            Err(refused(GpuUse::Tracer))
        }

        pub fn tracer(
            &mut self,
            _: &Assembled,
            _: DebugView,
            _: FirstHit,
        ) -> Result<String, RenderError> {
            Err(refused(GpuUse::Tracer))
        }

        pub fn render(
            &mut self,
            _: &Assembled,
            _: DebugView,
            _: (&Film, &RenderControl),
            _: Watch,
        ) -> Result<RenderStats, RenderError> {
            Err(refused(GpuUse::Tracer))
        }

        pub fn items(&mut self, _: &Assembled) -> Result<&NoItems, RenderError> {
            Err(refused(GpuUse::ItemBuffer))
        }
    }
}
