//! The picked pixel: the pixel whose ray tree is shown, that tree and, once a node is hovered,
//! the object seen at every pixel (to highlight that object), on the scene as the controls show
//! it. They are traced on the ray tree thread ([`super::ray_tree_thread`]): the window never
//! waits, it asks and takes the answers when they arrive; a camera or scene change keeps the
//! pixel and traces it again.

use std::sync::Arc;
use std::time::Duration;

use super::caustics::SharedCaustics;
use raylab::camera::Camera;

use super::ray_tree_thread::{
    Answer, Ask, FigureAsk, FigureLayer, ObjectIds, RayTreeThread, Request, TracedTree,
};
use crate::viewer::scene::controls::Controls;
use crate::viewer::scene::controls::TraceSetup;
use crate::viewer::scene::source::LoadedScene;

/// The ray-tree figure of the picked pixel: how much of the tree it shows, and the newest
/// drawing of it.
#[derive(Default)]
pub struct FigureView {
    /// Show the tree up to this generation; `None`: all of it.
    pub generations: Option<u32>,
    /// The node whose lines are drawn wider (clicked in the ray tree panel).
    pub highlight: Option<usize>,
    /// The newest figure drawn (it may be of the observer before while the new one is drawn).
    pub drawn: Option<FigureLayer>,
    /// Counts the figures drawn: a new one has a new serial.
    pub serial: u64,
    /// The node whose line the cursor is over, this frame.
    pub hovered_node: Option<usize>,
    /// The key and figure last asked for.
    asked: Option<(u64, FigureAsk)>,
}

/// The picked pixel and what is known of it.
pub struct PickedPixel {
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
    /// The ray-tree figure, while an observer looks at it.
    pub figure: FigureView,
    /// What `key` stands for: the scene and controls the pixel was last traced with.
    traced_for: Option<(Arc<LoadedScene>, Controls, (u32, u32))>,
    setup: Option<TraceSetup>,
    key: u64,
    tree_key: u64,
    ids_key: Option<u64>,
    ids_asked: Option<u64>,
    thread: RayTreeThread,
}

impl PickedPixel {
    /// Starts the thread (with `threads` threads for the object ids, 0: one per core);
    /// `wake` tells the window an answer has come.
    pub fn start(
        threads: usize,
        caustics: SharedCaustics,
        wake: impl Fn() + Send + 'static,
    ) -> Result<PickedPixel, String> {
        let thread = RayTreeThread::start(threads, caustics, wake)?;
        Ok(PickedPixel {
            pixel: None,
            tree: None,
            error: None,
            object_ids: None,
            show_overlay: true,
            hovered: None,
            figure: FigureView::default(),
            traced_for: None,
            setup: None,
            key: 0,
            tree_key: 0,
            ids_key: None,
            ids_asked: None,
            thread,
        })
    }

    /// Inspects `pixel` from now on.
    pub fn pick(&mut self, pixel: (u32, u32)) {
        self.pixel = Some(pixel);
    }

    pub fn close(&mut self) {
        self.figure.drawn = None;
        self.figure.asked = None;
        self.pixel = None;
        self.tree = None;
        self.error = None;
        self.traced_for = None;
    }

    /// Takes the answers that came (at the start of a frame, so that the frame shows them);
    /// returns how long each took, in words.
    pub fn receive(&mut self) -> Vec<String> {
        let mut times = Vec::new();
        while let Some(answer) = self.thread.answer() {
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
        self.send(Ask::Tree);
        Ok(())
    }

    /// Asks for the object ids of the current view, unless they are known or coming.
    pub fn want_object_ids(&mut self) {
        if self.ids_key != Some(self.key) && self.ids_asked != Some(self.key) {
            self.ids_asked = Some(self.key);
            self.send(Ask::ObjectIds);
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

    /// Asks for the figure as `observer` sees it, once the tree of the current pick is traced,
    /// unless that figure is drawn or coming; `None` forgets the figure.
    pub fn sync_figure(&mut self, observer: Option<Camera>) {
        let Some(observer) = observer.filter(|_| self.pixel.is_some()) else {
            self.figure.drawn = None;
            self.figure.asked = None;
            return;
        };
        if self.busy() {
            return;
        }
        let ask = FigureAsk {
            observer,
            generations: self.figure.generations.unwrap_or(u32::MAX),
            highlight: self.figure.highlight,
        };
        if self.figure.asked != Some((self.key, ask)) {
            self.figure.asked = Some((self.key, ask));
            self.send(Ask::Figure(ask));
        }
    }

    /// The figure asked for is not drawn yet.
    pub fn figure_busy(&self) -> bool {
        let drawn = self.figure.drawn.as_ref().map(|d| (self.key, d.ask));
        self.figure.asked.is_some() && self.figure.asked != drawn
    }

    fn send(&mut self, ask: Ask) {
        let (Some((scene, _, pixel)), Some(setup)) = (&self.traced_for, &self.setup) else {
            return;
        };
        let request = Request {
            key: self.key,
            scene: scene.clone(),
            setup: setup.clone(),
            pixel: *pixel,
            ask,
        };
        if let Err(e) = self.thread.ask(request) {
            self.error = Some(e);
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
            // A figure of an observer since moved is shown until the newest comes.
            Answer::Figure(key, Ok(drawn)) if key == self.key && self.figure.asked.is_some() => {
                let time = format!("ray-tree figure in {:.1} ms", ms(drawn.time));
                self.figure.drawn = Some(drawn);
                self.figure.serial += 1;
                return Some(time);
            }
            Answer::Figure(_, Err(e)) => self.error = Some(e),
            _ => {}
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use std::time::Instant;

    use glam::Vec3;
    use raylab::inspect;
    use raylab::whitted::Tracer;

    use super::*;
    use crate::viewer::scene::source;

    /// Syncs until the ray tree thread has answered.
    fn settle(picked: &mut PickedPixel, scene: &Arc<LoadedScene>, controls: &Controls) {
        let start = Instant::now();
        loop {
            picked.receive();
            picked
                .sync(scene, controls, controls.setup(4096).ok())
                .unwrap();
            if !picked.busy() {
                return;
            }
            assert!(start.elapsed() < Duration::from_secs(60), "no answer");
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    #[test]
    fn a_pick_is_traced_again_when_the_camera_moves_and_dropped_outside_the_image() {
        let scene = Arc::new(source::load(None, None).unwrap());
        let mut controls = Controls::from_scene(scene.scene());
        (controls.settings.width, controls.settings.height) = (32, 32);
        let mut picked = PickedPixel::start(1, SharedCaustics::default(), || {}).unwrap();
        picked.pick((5, 7));
        for eye_shift in [Vec3::ZERO, Vec3::X] {
            controls.camera.eye += eye_shift;
            settle(&mut picked, &scene, &controls);
            let traced = picked.tree.as_ref().expect("a tree");
            assert_eq!(traced.camera.spec, controls.camera);
            // The same tree as the library's for that pixel of that view.
            let mut expected = scene.scene().clone();
            expected.settings = controls.settings.clone();
            expected.camera = traced.camera;
            let tracer = Tracer::new(&expected, &scene.assembled.bvh);
            assert_eq!(traced.tree, inspect::trace_ray_tree(&tracer, 5, 7));
        }
        picked.want_object_ids();
        let start = Instant::now();
        while picked.current_object_ids().is_none() {
            settle(&mut picked, &scene, &controls);
            std::thread::sleep(Duration::from_millis(1));
            assert!(start.elapsed() < Duration::from_secs(60), "no ids");
        }
        let ids = picked.current_object_ids().unwrap();
        assert_eq!(ids.ids.len(), 32 * 32);
        let eye_ray = &picked.tree.as_ref().unwrap().tree.nodes[0];
        let seen = eye_ray.hit.as_ref().map_or(u32::MAX, |h| h.object);
        assert_eq!(ids.ids[7 * 32 + 5], seen);
        // Another pixel of the same view keeps the ids; another view needs its own.
        picked.pick((6, 7));
        settle(&mut picked, &scene, &controls);
        assert!(picked.current_object_ids().is_some());
        controls.camera.eye += Vec3::Y;
        settle(&mut picked, &scene, &controls);
        assert!(picked.current_object_ids().is_none());
        controls.settings.width = 4;
        let dropped = picked.sync(&scene, &controls, controls.setup(4096).ok());
        assert!(dropped.unwrap_err().contains("outside the 4×32 image"));
        assert_eq!(picked.pixel, None);
    }
}
