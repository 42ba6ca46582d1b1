//! The ray tree thread: it traces the ray tree of a pixel, the object seen at every pixel, or
//! the pixel's ray-tree figure seen by an observer, on its own copy of the scene (made at the
//! first request, updated in place after), and finds the object ids and the figure on a pool of
//! lowered priority so that the window and the render go first. Requests carry a key; object ids
//! asked for a view that has since changed are skipped, and so is a figure asked for before a
//! newer one.

use std::panic::AssertUnwindSafe;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::time::{Duration, Instant};

use raylab::camera::{Camera, PIXEL_CENTRE};
use raylab::figure::{FigureStyle, Layer, RayFigure, draw_layer, observer_depths};
use raylab::inspect::{self, RayTree};
use raylab::render::Assembled;
use raylab::srgb_image::SrgbImage;
use raylab::stats::RayCounts;
use rayon::prelude::*;

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

/// The pixel's ray-tree figure as an observer sees it, over the render from that observer.
pub struct FigureLayer {
    pub ask: FigureAsk,
    pub figure: RayFigure,
    pub layer: Layer,
    pub time: Duration,
}

/// How the figure is asked for: who sees it, and how much of the tree.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FigureAsk {
    pub observer: Camera,
    pub generations: u32,
    /// The node whose lines are drawn wider.
    pub highlight: Option<usize>,
}

/// What the thread is asked to trace.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ask {
    Tree,
    /// The object ids of the view.
    ObjectIds,
    Figure(FigureAsk),
}

/// What the thread is asked: `key` names the scene, controls and pixel it was asked for.
pub struct Request {
    pub key: u64,
    pub scene: Arc<LoadedScene>,
    pub setup: TraceSetup,
    pub pixel: (u32, u32),
    pub ask: Ask,
}

/// What the thread traced for the request with that key (or why it could not).
pub enum Answer {
    Tree(u64, Result<TracedTree, String>),
    Ids(u64, Result<ObjectIds, String>),
    Figure(u64, Result<FigureLayer, String>),
}

/// The longest side of the scene camera's image on the figure's image plane.
const PLANE_IMAGE_SIDE: u32 = 256;

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
    while let Ok(first) = inbox.recv() {
        // A figure asked for before a newer one is not drawn.
        let batch: Vec<Request> = std::iter::once(first).chain(inbox.try_iter()).collect();
        let newest_figure = batch.iter().rposition(|r| matches!(r.ask, Ask::Figure(_)));
        let batch = batch.into_iter().enumerate().filter_map(|(i, r)| {
            let superseded = matches!(r.ask, Ask::Figure(_)) && Some(i) != newest_figure;
            (!superseded).then_some(r)
        });
        for request in batch {
            if request.key < latest.load(Ordering::Relaxed) {
                continue;
            }
            let map = caustics.current(&request.scene, &request.setup);
            let assembled = working.assembled(&request.scene, &request.setup, map);
            if outbox.send(answer(pool, assembled, &request)).is_err() {
                return;
            }
            wake();
        }
    }
}

/// Traces what `request` asks of `assembled`, its scene as the request's setup shows it.
fn answer(pool: &rayon::ThreadPool, assembled: &Assembled, request: &Request) -> Answer {
    let tracer = assembled.tracer();
    let size = (request.setup.settings.width, request.setup.settings.height);
    let (x, y) = request.pixel;
    let start = Instant::now();
    match request.ask {
        Ask::ObjectIds => {
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
        }
        Ask::Tree => {
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
        }
        Ask::Figure(ask) => {
            let drawn = catching(|| {
                pool.install(|| {
                    let tree = inspect::trace_ray_tree(&tracer, x, y);
                    let scene = (&assembled.scene, &request.setup.camera);
                    let figure = RayFigure::new(&tree, scene, size, ask.generations);
                    let plane = plane_image(assembled, size);
                    let depths = observer_depths(&tracer, &ask.observer, size);
                    let style = FigureStyle {
                        xray: false,
                        highlight: ask.highlight,
                        legend: None,
                    };
                    let layer = draw_layer(&figure, &ask.observer, size, &depths, &plane, &style);
                    (figure, layer)
                })
            });
            Answer::Figure(
                request.key,
                drawn.map(|(figure, layer)| FigureLayer {
                    ask,
                    figure,
                    layer,
                    time: start.elapsed(),
                }),
            )
        }
    }
}

/// The scene camera's image of `assembled`, one eye ray through each pixel's centre, at most
/// [`PLANE_IMAGE_SIDE`] a side with the aspect of a `width × height` image: what the figure
/// shows on the image plane.
fn plane_image(assembled: &Assembled, (width, height): (u32, u32)) -> SrgbImage {
    let scale = (PLANE_IMAGE_SIDE as f32 / width.max(height) as f32).min(1.0);
    let side = |v: u32| ((v as f32 * scale).round() as u32).max(1);
    let size = (side(width), side(height));
    let tracer = assembled.tracer();
    let camera = assembled.scene.camera;
    let mut pixels = vec![raylab::color::Color::ZERO; (size.0 * size.1) as usize];
    pixels
        .par_chunks_mut(size.0 as usize)
        .enumerate()
        .for_each(|(y, row)| {
            let mut counts = RayCounts::default();
            for (x, pixel) in row.iter_mut().enumerate() {
                let ray = camera.eye_ray((x as u32, y as u32), PIXEL_CENTRE, size);
                *pixel = tracer.trace_eye(&ray, &mut counts);
            }
        });
    SrgbImage::from_linear(size.0, size.1, &pixels)
}

/// `f`'s result, or the message of its panic (a broken scene must not take the viewer down).
fn catching<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(AssertUnwindSafe(f)).map_err(|p| panic_message(p.as_ref()))
}
