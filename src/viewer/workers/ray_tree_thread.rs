//! The ray tree thread: it traces the ray tree of a pixel, or the object seen at
//! every pixel, on its own copy of the scene (made at the first request, updated in place after),
//! and finds the object ids on a pool of lowered priority so that the window and the render go
//! first. Requests carry a key; object ids asked for a view that has since changed are skipped.

use std::panic::AssertUnwindSafe;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::time::{Duration, Instant};

use raylab::camera::Camera;
use raylab::inspect::{self, RayTree};

use super::caustics::SharedCaustics;
use super::worker::{low_priority_pool, panic_message};
use super::working_scene::WorkingScene;
use crate::viewer::scene::controls::TraceSetup;
use crate::viewer::scene::source::LoadedScene;

/// A traced ray tree and the view it was traced in.
pub struct TracedTree {
    pub tree: RayTree,
    pub camera: Camera,
    /// The image size.
    pub size: (u32, u32),
    pub time: Duration,
}

/// The object seen at each pixel (row-major, top row first; `u32::MAX` for none).
pub struct ObjectIds {
    /// The picked pixel's key of the view they were traced for.
    pub key: u64,
    pub ids: Vec<u32>,
    pub size: (u32, u32),
    pub time: Duration,
}

/// What the thread is asked: `key` names the scene, controls and pixel it was asked for.
pub struct Request {
    pub key: u64,
    pub scene: Arc<LoadedScene>,
    pub setup: TraceSetup,
    pub pixel: (u32, u32),
    /// Trace the object ids of the view rather than the pixel's tree.
    pub object_ids: bool,
}

/// What the thread traced for the request with that key (or why it could not).
pub enum Answer {
    Tree(u64, Result<TracedTree, String>),
    Ids(u64, Result<ObjectIds, String>),
}

/// The window's end of the thread.
pub struct RayTreeThread {
    requests: Sender<Request>,
    answers: Receiver<Answer>,
    /// The newest request's key.
    latest: Arc<AtomicU64>,
}

impl RayTreeThread {
    /// Starts the thread (with `threads` threads for the object ids, 0: one per core);
    /// `wake` tells the window an answer has come. The thread ends with its `RayTreeThread`.
    /// The trees include the caustics of the render worker's map, borrowed from `caustics`.
    pub fn start(
        threads: usize,
        caustics: SharedCaustics,
        wake: impl Fn() + Send + 'static,
    ) -> Result<Self, String> {
        let pool = low_priority_pool(threads, "ray-tree")?;
        let (requests, inbox) = mpsc::channel();
        let (outbox, answers) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let newest = latest.clone();
        std::thread::Builder::new()
            .name("ray-tree".into())
            .spawn(move || run(&pool, &inbox, &outbox, &newest, &caustics, wake))
            .map_err(|e| format!("cannot start the ray tree thread: {e}"))?;
        Ok(RayTreeThread {
            requests,
            answers,
            latest,
        })
    }

    /// Sends a request; it supersedes the object ids asked before it.
    pub fn ask(&self, request: Request) -> Result<(), String> {
        self.latest.store(request.key, Ordering::Relaxed);
        self.requests
            .send(request)
            .map_err(|_| "the ray tree thread has stopped".to_string())
    }

    /// The next answer that came, if any.
    pub fn answer(&self) -> Option<Answer> {
        self.answers.try_recv().ok()
    }
}

/// The thread's loop: answer each request, skipping object ids asked for a view since changed.
fn run(
    pool: &rayon::ThreadPool,
    inbox: &Receiver<Request>,
    outbox: &Sender<Answer>,
    latest: &AtomicU64,
    caustics: &SharedCaustics,
    wake: impl Fn(),
) {
    let mut working = WorkingScene::default();
    while let Ok(request) = inbox.recv() {
        if request.key < latest.load(Ordering::Relaxed) {
            continue;
        }
        let map = caustics.current(&request.scene, &request.setup);
        let tracer = working
            .assembled(&request.scene, &request.setup, map)
            .tracer();
        let size = (request.setup.settings.width, request.setup.settings.height);
        let start = Instant::now();
        let answer = if request.object_ids {
            let ids = catching(|| pool.install(|| inspect::object_ids(&tracer)));
            Answer::Ids(
                request.key,
                ids.map(|ids| ObjectIds {
                    key: request.key,
                    ids,
                    size,
                    time: start.elapsed(),
                }),
            )
        } else {
            let (x, y) = request.pixel;
            let tree = catching(|| inspect::trace_ray_tree(&tracer, x, y));
            Answer::Tree(
                request.key,
                tree.map(|tree| TracedTree {
                    tree,
                    camera: request.setup.camera,
                    size,
                    time: start.elapsed(),
                }),
            )
        };
        if outbox.send(answer).is_err() {
            return;
        }
        wake();
    }
}

/// `f`'s result, or the message of its panic (a broken scene must not take the viewer down).
fn catching<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(AssertUnwindSafe(f)).map_err(|p| panic_message(p.as_ref()))
}
