//! The inspector's tracing: the picked pixel, and a background thread that traces its ray tree
//! and, once a node is hovered, the object seen at every pixel (to highlight that object), on the
//! scene as the controls show it. The window never waits: it sends requests and takes the answers
//! when they arrive; a camera or scene change keeps the pixel and traces it again. The thread
//! has its own copy of the scene (made at the first pick) and finds the object ids on a pool of
//! lowered priority, so the window and the render go first.

use std::panic::AssertUnwindSafe;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::time::{Duration, Instant};

use raylab::camera::Camera;
use raylab::inspect::{self, RayTree};

use super::controls::Controls;
use super::scene_source::LoadedScene;
use super::worker::{low_priority_pool, panic_message};
use super::working_scene::{TraceSetup, WorkingScene};

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
    /// The inspection's key of the view they were traced for.
    pub key: u64,
    pub ids: Vec<u32>,
    pub size: (u32, u32),
    pub time: Duration,
}

/// What the thread is asked: `key` names the scene, controls and pixel it was asked for.
struct Request {
    key: u64,
    scene: Arc<LoadedScene>,
    setup: TraceSetup,
    pixel: (u32, u32),
    object_ids: bool,
}

enum Answer {
    Tree(u64, Result<TracedTree, String>),
    Ids(u64, Result<ObjectIds, String>),
}

/// The picked pixel and what is known of it.
pub struct Inspection {
    pub pixel: Option<(u32, u32)>,
    /// The newest tree (it may be of the previous camera while the new one is traced).
    pub tree: Option<TracedTree>,
    pub error: Option<String>,
    /// The object ids of the current view, once asked for and traced.
    pub object_ids: Option<ObjectIds>,
    /// Draw the tree over the image.
    pub show_overlay: bool,
    /// The object whose node the cursor is over, this frame.
    pub hovered: Option<u32>,
    /// What `key` stands for: the scene and controls the pixel was last traced with.
    traced_for: Option<(Arc<LoadedScene>, Controls, (u32, u32))>,
    setup: Option<TraceSetup>,
    key: u64,
    tree_key: u64,
    ids_key: Option<u64>,
    ids_asked: Option<u64>,
    latest: Arc<AtomicU64>,
    requests: Sender<Request>,
    answers: Receiver<Answer>,
}

impl Inspection {
    /// Starts the thread (with `threads` threads for the object ids, 0: one per core);
    /// `wake` tells the window an answer has come.
    pub fn start(threads: usize, wake: impl Fn() + Send + 'static) -> Result<Inspection, String> {
        let pool = low_priority_pool(threads, "inspector")?;
        let (requests, inbox) = mpsc::channel();
        let (outbox, answers) = mpsc::channel();
        let latest = Arc::new(AtomicU64::new(0));
        let newest = latest.clone();
        std::thread::Builder::new()
            .name("inspector".into())
            .spawn(move || run(&pool, &inbox, &outbox, &newest, wake))
            .map_err(|e| format!("cannot start the inspector: {e}"))?;
        Ok(Inspection {
            pixel: None,
            tree: None,
            error: None,
            object_ids: None,
            show_overlay: true,
            hovered: None,
            traced_for: None,
            setup: None,
            key: 0,
            tree_key: 0,
            ids_key: None,
            ids_asked: None,
            latest,
            requests,
            answers,
        })
    }

    /// Inspects `pixel` from now on.
    pub fn pick(&mut self, pixel: (u32, u32)) {
        self.pixel = Some(pixel);
    }

    pub fn close(&mut self) {
        self.pixel = None;
        self.tree = None;
        self.error = None;
        self.traced_for = None;
    }

    /// Takes the answers that came (at the start of a frame, so that the frame shows them);
    /// returns how long each took, in words.
    pub fn receive(&mut self) -> Vec<String> {
        let mut times = Vec::new();
        while let Ok(answer) = self.answers.try_recv() {
            times.extend(self.take(answer));
        }
        times
    }

    /// Traces the pixel again if the scene, the controls or the pixel changed. `setup` is what
    /// `controls` change in the scene, if they are valid. The error says why the pick was
    /// dropped.
    pub fn sync(
        &mut self,
        scene: &Arc<LoadedScene>,
        controls: &Controls,
        setup: Option<TraceSetup>,
    ) -> Result<(), String> {
        let (Some(pixel), Some(setup)) = (self.pixel, setup) else {
            return Ok(());
        };
        let current = self
            .traced_for
            .as_ref()
            .is_some_and(|(s, c, p)| Arc::ptr_eq(s, scene) && c == controls && *p == pixel);
        if current {
            return Ok(());
        }
        let (width, height) = (setup.settings.width, setup.settings.height);
        if pixel.0 >= width || pixel.1 >= height {
            self.close();
            return Err(format!(
                "cannot inspect pixel ({}, {}): it is outside the {width}×{height} image",
                pixel.0, pixel.1
            ));
        }
        // Another pixel of the same view keeps the view's object ids.
        let same_view = self
            .traced_for
            .as_ref()
            .is_some_and(|(s, c, _)| Arc::ptr_eq(s, scene) && c == controls);
        let ids_current = self.ids_key == Some(self.key);
        self.key += 1;
        if same_view && ids_current {
            self.ids_key = Some(self.key);
            if let Some(ids) = &mut self.object_ids {
                ids.key = self.key;
            }
        }
        self.traced_for = Some((scene.clone(), controls.clone(), pixel));
        self.setup = Some(setup);
        self.send(false);
        Ok(())
    }

    /// Asks for the object ids of the current view, unless they are known or coming.
    pub fn want_object_ids(&mut self) {
        if self.ids_key != Some(self.key) && self.ids_asked != Some(self.key) {
            self.ids_asked = Some(self.key);
            self.send(true);
        }
    }

    /// The object ids, if they are of the current view.
    pub fn current_object_ids(&self) -> Option<&ObjectIds> {
        self.object_ids
            .as_ref()
            .filter(|_| self.ids_key == Some(self.key))
    }

    /// A tree is being traced (or is yet to be asked for) for the current pick.
    pub fn busy(&self) -> bool {
        let asked = self.traced_for.as_ref().map(|(_, _, pixel)| *pixel);
        self.pixel.is_some() && (self.tree_key != self.key || asked != self.pixel)
    }

    fn send(&mut self, object_ids: bool) {
        let (Some((scene, _, pixel)), Some(setup)) = (&self.traced_for, &self.setup) else {
            return;
        };
        self.latest.store(self.key, Ordering::Relaxed);
        let request = Request {
            key: self.key,
            scene: scene.clone(),
            setup: setup.clone(),
            pixel: *pixel,
            object_ids,
        };
        if self.requests.send(request).is_err() {
            self.error = Some("the inspector has stopped".into());
        }
    }

    fn take(&mut self, answer: Answer) -> Option<String> {
        let ms = |t: Duration| t.as_secs_f64() * 1e3;
        match answer {
            Answer::Tree(key, result) if key == self.key && self.pixel.is_some() => {
                self.tree_key = key;
                match result {
                    Ok(traced) => {
                        let (x, y) = traced.tree.pixel;
                        let time = format!(
                            "ray tree of pixel ({x}, {y}): {} rays in {:.3} ms",
                            traced.tree.nodes.len(),
                            ms(traced.time)
                        );
                        self.tree = Some(traced);
                        self.error = None;
                        return Some(time);
                    }
                    Err(e) => {
                        self.tree = None;
                        self.error = Some(e);
                    }
                }
            }
            Answer::Ids(key, Ok(ids)) if key == self.key => {
                let (w, h) = ids.size;
                let time = format!("object ids of the {w}×{h} image in {:.1} ms", ms(ids.time));
                self.ids_key = Some(key);
                self.object_ids = Some(ids);
                return Some(time);
            }
            Answer::Ids(_, Err(e)) => self.error = Some(e),
            _ => {}
        }
        None
    }
}

/// The thread's loop: answer each request, skipping object ids asked for a view since changed.
fn run(
    pool: &rayon::ThreadPool,
    inbox: &Receiver<Request>,
    outbox: &Sender<Answer>,
    latest: &AtomicU64,
    wake: impl Fn(),
) {
    let mut working = WorkingScene::default();
    while let Ok(request) = inbox.recv() {
        if request.key < latest.load(Ordering::Relaxed) {
            continue;
        }
        let tracer = working.tracer(&request.scene, &request.setup);
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

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use raylab::whitted::Tracer;

    use super::*;
    use crate::viewer::scene_source;

    /// Syncs until the inspector has answered.
    fn settle(inspection: &mut Inspection, scene: &Arc<LoadedScene>, controls: &Controls) {
        let start = Instant::now();
        loop {
            inspection.receive();
            inspection
                .sync(scene, controls, controls.setup(4096).ok())
                .unwrap();
            if !inspection.busy() {
                return;
            }
            assert!(start.elapsed() < Duration::from_secs(60), "no answer");
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    #[test]
    fn a_pick_is_traced_again_when_the_camera_moves_and_dropped_outside_the_image() {
        let scene = Arc::new(scene_source::load(None).unwrap());
        let mut controls = Controls::from_scene(&scene.scene);
        (controls.settings.width, controls.settings.height) = (32, 32);
        let mut inspection = Inspection::start(1, || {}).unwrap();
        inspection.pick((5, 7));
        for eye_shift in [Vec3::ZERO, Vec3::X] {
            controls.camera.eye += eye_shift;
            settle(&mut inspection, &scene, &controls);
            let traced = inspection.tree.as_ref().expect("a tree");
            assert_eq!(traced.camera.spec, controls.camera);
            // The same tree as the library's for that pixel of that view.
            let mut expected = scene.scene.clone();
            expected.settings = controls.settings.clone();
            expected.camera = traced.camera;
            let tracer = Tracer::new(&expected, &scene.bvh);
            assert_eq!(traced.tree, inspect::trace_ray_tree(&tracer, 5, 7));
        }
        inspection.want_object_ids();
        let start = Instant::now();
        while inspection.current_object_ids().is_none() {
            settle(&mut inspection, &scene, &controls);
            std::thread::sleep(Duration::from_millis(1));
            assert!(start.elapsed() < Duration::from_secs(60), "no ids");
        }
        let ids = inspection.current_object_ids().unwrap();
        assert_eq!(ids.ids.len(), 32 * 32);
        let eye_ray = &inspection.tree.as_ref().unwrap().tree.nodes[0];
        let seen = eye_ray.hit.as_ref().map_or(u32::MAX, |h| h.object);
        assert_eq!(ids.ids[7 * 32 + 5], seen);
        // Another pixel of the same view keeps the ids; another view needs its own.
        inspection.pick((6, 7));
        settle(&mut inspection, &scene, &controls);
        assert!(inspection.current_object_ids().is_some());
        controls.camera.eye += Vec3::Y;
        settle(&mut inspection, &scene, &controls);
        assert!(inspection.current_object_ids().is_none());
        controls.settings.width = 4;
        let dropped = inspection.sync(&scene, &controls, controls.setup(4096).ok());
        assert!(dropped.unwrap_err().contains("outside the 4×32 image"));
        assert_eq!(inspection.pixel, None);
    }
}
