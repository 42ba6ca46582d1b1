//! The render worker: one background thread that runs the library's progressive renderer on its
//! own pool of tracing threads, or on the GPU when a job asks for it. The window sends it jobs; a
//! new job cancels the one running (through its [`RenderControl`]) and starts from the coarse
//! block size. Between jobs the thread sleeps on its channel, so an idle viewer uses no CPU.

use std::panic::AssertUnwindSafe;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use raylab::backend::{Backend, RenderError};
use raylab::film::Film;
use raylab::gpu::device::GpuDevice;
use raylab::gpu::film::GpuFilm;
use raylab::inspect::Legend;
use raylab::progressive::{PassStats, RenderControl};

use super::caustics::{JobMap, SharedCaustics, Shot};
use super::working_scene::WorkingScene;
use crate::viewer::scene::controls::TraceSetup;
use crate::viewer::scene::source::LoadedScene;

/// One render: a scene seen with a camera and settings, into a film.
pub struct Job {
    pub scene: Arc<LoadedScene>,
    pub setup: TraceSetup,
    pub film: Arc<Film>,
    pub control: Arc<RenderControl>,
    pub report: Arc<JobReport>,
}

/// How a job ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    Finished,
    Cancelled,
    /// The tracer failed (panicked); the message says how.
    Failed(String),
}

/// What the worker tells the window about a job, readable while it runs.
#[derive(Debug)]
pub struct JobReport {
    pub started: Instant,
    passes: Mutex<Vec<PassStats>>,
    outcome: Mutex<Option<Outcome>>,
    /// What the colours of the job's debug view mean, for the heat maps.
    legend: Mutex<Option<Legend>>,
    /// The caustic photons the job shot, if it shot any.
    caustics: Mutex<Option<Shot>>,
    /// Photons in the caustic map the job traces with (0: caustics off).
    photons: AtomicU32,
    /// What traces the job: `cpu: N threads` or `gpu: ADAPTER (BACKEND)`, and why not the GPU
    /// where it was asked for and cannot.
    device: Mutex<String>,
    /// The film on the GPU the job renders into, when it renders on the GPU.
    film_on_gpu: Mutex<Option<Arc<GpuFilm>>>,
}

impl JobReport {
    pub fn new() -> JobReport {
        JobReport {
            started: Instant::now(),
            passes: Mutex::new(Vec::new()),
            outcome: Mutex::new(None),
            legend: Mutex::new(None),
            caustics: Mutex::new(None),
            photons: AtomicU32::new(0),
            device: Mutex::new(String::new()),
            film_on_gpu: Mutex::new(None),
        }
    }

    /// The film on the GPU the job renders into, if it renders on the GPU.
    pub fn film_on_gpu(&self) -> Option<Arc<GpuFilm>> {
        self.film_on_gpu.lock().ok().and_then(|f| f.clone())
    }

    /// What traces the job (empty until it starts).
    pub fn device(&self) -> String {
        self.device.lock().map(|d| d.clone()).unwrap_or_default()
    }

    fn set_device(&self, device: String) {
        if let Ok(mut d) = self.device.lock() {
            *d = device;
        }
    }

    /// The caustic photons the job shot (taken: each shot is heard once).
    pub fn take_shot(&self) -> Option<Shot> {
        self.caustics.lock().ok().and_then(|mut s| s.take())
    }

    /// Photons shot for the caustic map the job traces with (0: caustics off).
    pub fn photons(&self) -> u32 {
        self.photons.load(Ordering::Relaxed)
    }

    /// The passes finished so far.
    pub fn passes(&self) -> Vec<PassStats> {
        self.passes.lock().map(|p| p.clone()).unwrap_or_default()
    }

    /// The colour bar of the job's view, once the job has started (`None` for views that are
    /// not a scale).
    pub fn legend(&self) -> Option<Legend> {
        self.legend.lock().ok().and_then(|l| l.clone())
    }

    /// `None` while the job waits or runs.
    pub fn outcome(&self) -> Option<Outcome> {
        self.outcome.lock().ok().and_then(|o| o.clone())
    }

    fn push_pass(&self, pass: &PassStats) {
        if let Ok(mut passes) = self.passes.lock() {
            passes.push(*pass);
        }
    }

    fn finish(&self, outcome: Outcome) {
        if let Ok(mut o) = self.outcome.lock() {
            *o = Some(outcome);
        }
    }
}

/// The worker thread and the way to give it jobs.
pub struct Worker {
    jobs: Option<Sender<Job>>,
    thread: Option<JoinHandle<()>>,
}

impl Worker {
    /// Starts the worker with `threads` tracing threads (0: one per core), keeping its caustic
    /// map in `caustics`, rendering on `gpu` the jobs that ask for the GPU (opened at the first
    /// such job when `None`).
    pub fn start(
        threads: usize,
        caustics: SharedCaustics,
        gpu: Option<Arc<GpuDevice>>,
    ) -> Result<Worker, String> {
        let pool = low_priority_pool(threads, "tracer")?;
        let (jobs, inbox) = mpsc::channel();
        let thread = std::thread::Builder::new()
            .name("render worker".into())
            .spawn(move || run(pool, &inbox, &caustics, gpu))
            .map_err(|e| format!("cannot start the render worker: {e}"))?;
        Ok(Worker {
            jobs: Some(jobs),
            thread: Some(thread),
        })
    }

    /// Queues a job; the caller cancels the one before (so the worker gets to this one).
    pub fn submit(&self, job: Job) -> Result<(), String> {
        self.jobs
            .as_ref()
            .and_then(|jobs| jobs.send(job).ok())
            .ok_or_else(|| "the render worker has stopped".to_string())
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        // Closing the channel ends the worker's loop once its job (cancelled by the app) returns.
        self.jobs = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

/// How long one of the GPU tracer's dispatches takes at most in the viewer: the window draws on
/// the same GPU, and its frame waits for the dispatch in flight, so a dispatch takes about a
/// frame's share at 60 frames a second.
const FRAME_SHARE: Duration = Duration::from_millis(12);

/// The worker's loop: take the newest job, make or grow its caustic map, render it, repeat; end
/// when the channel closes. Jobs that ask for the GPU render on `gpu` (the window's), or on one
/// opened at the first such job; where the GPU cannot, on the CPU, the job's device saying why.
fn run(
    pool: rayon::ThreadPool,
    inbox: &Receiver<Job>,
    caustics: &SharedCaustics,
    gpu: Option<Arc<GpuDevice>>,
) {
    let mut backend = Backend::new(Arc::new(pool));
    backend.set_fallback(true);
    backend.set_dispatch_time(FRAME_SHARE);
    if let Some(gpu) = gpu {
        backend.set_gpu(gpu);
    }
    let mut working = WorkingScene::default();
    while let Ok(mut job) = inbox.recv() {
        // Jobs queued behind this one supersede it.
        while let Ok(newer) = inbox.try_recv() {
            job.report.finish(Outcome::Cancelled);
            job = newer;
        }
        if job.control.is_cancelled() {
            job.report.finish(Outcome::Cancelled);
            continue;
        }
        let tracer = working.assembled(&job.scene, &job.setup, None).tracer();
        let grown = std::panic::catch_unwind(AssertUnwindSafe(|| {
            backend
                .pool()
                .install(|| caustics.grow(&job.scene, &job.setup, &tracer))
        }));
        let map = match grown {
            Ok(Ok(grown)) => grown.map(|JobMap { map, shot }| {
                job.report
                    .photons
                    .store(map.shot() as u32, Ordering::Relaxed);
                if let Ok(mut s) = job.report.caustics.lock() {
                    *s = shot;
                }
                map
            }),
            Ok(Err(e)) => {
                job.report.finish(Outcome::Failed(e));
                continue;
            }
            Err(panic) => {
                job.report
                    .finish(Outcome::Failed(panic_message(panic.as_ref())));
                continue;
            }
        };
        let assembled = working.assembled(&job.scene, &job.setup, map);
        let view = job.setup.debug_view;
        if let Ok(mut legend) = job.report.legend.lock() {
            *legend = view.legend(&assembled.tracer());
        }
        backend.set_device(job.setup.device);
        backend.set_first_hit(job.setup.first_hit);
        let report = &job.report;
        let rendered = std::panic::catch_unwind(AssertUnwindSafe(|| {
            backend.prepare(assembled, view)?;
            report.set_device(backend.label().to_string());
            let target = (job.film.as_ref(), job.control.as_ref());
            let on_pass = |pass: &PassStats| report.push_pass(pass);
            backend.render_shown(assembled, view, target, on_pass, |film| {
                if let Ok(mut shown) = report.film_on_gpu.lock() {
                    *shown = Some(film);
                }
            })
        }));
        report.finish(match rendered {
            Ok(Ok(_)) => Outcome::Finished,
            Ok(Err(RenderError::Cancelled)) => Outcome::Cancelled,
            Ok(Err(e)) => Outcome::Failed(e.to_string()),
            Err(panic) => Outcome::Failed(panic_message(panic.as_ref())),
        });
    }
}

/// A pool of `threads` threads (0: one per core) named `name` and of lowered priority.
pub(super) fn low_priority_pool(
    threads: usize,
    name: &'static str,
) -> Result<rayon::ThreadPool, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(move |i| format!("{name} {i}"))
        .start_handler(|_| lower_priority())
        .build()
        .map_err(|e| format!("cannot start the {name} threads: {e}"))
}

/// How much lower the tracing threads' priority is than the window's (a `nice` value): the
/// window keeps its frame rate while the tracer still gets most of the cores (BENCHMARKS.md,
/// the viewer's latency, has the trade measured).
#[cfg(target_os = "linux")]
const TRACER_NICENESS: libc::c_int = 4;

/// Lowers the calling thread's priority, so that on a busy machine the window (and the GPU
/// driver's threads, which draw it) go before the tracer and the UI stays fluid.
#[cfg(target_os = "linux")]
fn lower_priority() {
    // SAFETY: plain system calls on the calling thread; Linux's setpriority takes a thread id
    // for PRIO_PROCESS and changes only that thread. Failing leaves the priority as it was.
    unsafe {
        let thread = libc::gettid() as libc::id_t;
        libc::setpriority(libc::PRIO_PROCESS, thread, TRACER_NICENESS);
    }
}

#[cfg(not(target_os = "linux"))]
fn lower_priority() {}

pub(super) fn panic_message(panic: &(dyn std::any::Any + Send)) -> String {
    let text = panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown error".to_string());
    format!("the tracer failed: {text}")
}

#[cfg(test)]
mod tests {
    use raylab::render::FirstHit;

    use super::*;
    use crate::viewer::scene::source;

    fn job(scene: &Arc<LoadedScene>, size: u32) -> Job {
        let mut settings = scene.scene().settings.clone();
        settings.width = size;
        settings.height = size;
        settings.block_size = 8;
        Job {
            scene: scene.clone(),
            setup: TraceSetup {
                camera: scene.scene().camera,
                settings,
                light_scale: 1.0,
                debug_view: Default::default(),
                materials: scene.scene().materials.clone(),
                lights: scene.scene().lights.clone(),
                caustic_round: 0,
                device: Default::default(),
                first_hit: Default::default(),
            },
            film: Arc::new(Film::new(size, size)),
            control: Arc::new(RenderControl::default()),
            report: Arc::new(JobReport::new()),
        }
    }

    fn wait_for(report: &JobReport) -> Outcome {
        wait_at_most(report, Duration::from_secs(60))
    }

    fn wait_at_most(report: &JobReport, limit: Duration) -> Outcome {
        let start = Instant::now();
        loop {
            if let Some(outcome) = report.outcome() {
                return outcome;
            }
            assert!(start.elapsed() < limit, "the job never ended");
            std::thread::sleep(Duration::from_millis(2));
        }
    }

    #[test]
    fn a_job_from_the_item_buffer_renders_the_rays_film() {
        let scene = Arc::new(source::load(None, None).unwrap());
        let worker = Worker::start(2, SharedCaustics::default(), None).unwrap();
        let mut films = Vec::new();
        for first_hit in [FirstHit::Rays, FirstHit::Raster] {
            let mut j = job(&scene, 32);
            j.setup.first_hit = first_hit;
            let (film, report) = (j.film.clone(), j.report.clone());
            worker.submit(j).unwrap();
            // Mesa's software GPU may first compile the raster pass for minutes.
            let outcome = wait_at_most(&report, Duration::from_secs(600));
            assert_eq!(outcome, Outcome::Finished, "{first_hit}");
            let from_items: u64 = report
                .passes()
                .iter()
                .map(|p| p.rays.from_item_buffer)
                .sum();
            assert_eq!(from_items > 0, first_hit == FirstHit::Raster, "{first_hit}");
            assert!(
                !report.device().contains("first hits from the rays"),
                "{}",
                report.device()
            );
            films.push(film.pixels());
        }
        assert!(films[0] == films[1], "the films differ");
    }

    #[test]
    fn a_job_renders_every_pass_into_its_film() {
        let scene = Arc::new(source::load(None, None).unwrap());
        let worker = Worker::start(2, SharedCaustics::default(), None).unwrap();
        let j = job(&scene, 32);
        let (film, report, control) = (j.film.clone(), j.report.clone(), j.control.clone());
        worker.submit(j).unwrap();
        assert_eq!(wait_for(&report), Outcome::Finished);
        assert!(control.progress().finished);
        assert_eq!(report.passes().len(), 4, "block sizes 8, 4, 2, 1");
        assert!(
            film.pixels()
                .iter()
                .any(|c| *c != raylab::color::Color::ZERO)
        );
    }

    #[test]
    fn a_cancelled_job_stops_and_the_next_one_runs() {
        let scene = Arc::new(source::load(None, None).unwrap());
        let worker = Worker::start(1, SharedCaustics::default(), None).unwrap();
        let first = job(&scene, 1024);
        let (first_control, first_report) = (first.control.clone(), first.report.clone());
        worker.submit(first).unwrap();
        first_control.cancel();
        let second = job(&scene, 16);
        let second_report = second.report.clone();
        worker.submit(second).unwrap();
        assert_eq!(wait_for(&first_report), Outcome::Cancelled);
        assert_eq!(wait_for(&second_report), Outcome::Finished);
    }

    #[test]
    fn a_failing_tracer_is_reported_and_the_worker_goes_on() {
        let good = Arc::new(source::load(None, None).unwrap());
        let mut broken = source::load(None, None).unwrap();
        // An object whose material does not exist makes the tracer index out of bounds.
        for object in &mut broken.assembled.scene.geometry.objects {
            object.material = 9999;
        }
        let broken = Arc::new(broken);
        let worker = Worker::start(1, SharedCaustics::default(), None).unwrap();
        let failing = job(&broken, 16);
        let report = failing.report.clone();
        worker.submit(failing).unwrap();
        match wait_for(&report) {
            Outcome::Failed(message) => assert!(message.contains("the tracer failed"), "{message}"),
            other => panic!("expected a failure, got {other:?}"),
        }
        let next = job(&good, 16);
        let next_report = next.report.clone();
        worker.submit(next).unwrap();
        assert_eq!(wait_for(&next_report), Outcome::Finished);
    }
}
