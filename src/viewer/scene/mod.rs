//! The scene being shown: loading scene files (or the built-in scene) in the background, watching
//! the file for changes, the controls (camera, settings, lights, debug view, materials) the user edits,
//! saving the edited materials and lights back into a TOML scene file, and the bookmarked views
//! (`views`). Where the scene stands is one [`SceneState`]: loading, failed or loaded.

pub mod controls;
pub mod edits;
pub mod source;
pub mod views;
pub mod watch;

use std::borrow::Cow;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use raylab::camera::CameraSpec;
use raylab::formats::SceneFormat;
use raylab::formats::toml::{Looks, save_edits};
use raylab::inspect::DebugView;
use raylab::render::{Device, FirstHit};
use raylab::settings::SettingsOverrides;

use self::controls::Controls;
use self::source::LoadedScene;
use self::views::SceneViews;
use self::watch::SceneWatcher;

/// What the loader and the watcher tell the window, from their own threads.
pub enum SceneNews {
    /// A scene finished loading (or failed to); `generation` tells stale loads apart.
    Loaded {
        generation: u64,
        result: Result<Box<LoadedScene>, String>,
    },
    /// The watched scene file (or its camera file, the path given) changed on disk.
    FileChanged(PathBuf),
}

/// Where the loader and the watcher send their news (and wake the window).
pub type NewsSender = Arc<dyn Fn(SceneNews) + Send + Sync>;

/// A loaded scene and the user's controls over it.
pub struct ShownScene {
    pub scene: Arc<LoadedScene>,
    /// What the user controls: the file's camera and settings with the overrides, then edited.
    pub controls: Controls,
    /// The controls as the scene file gives them (no overrides), to tell which a reloaded file
    /// changed.
    pub file_controls: Controls,
    /// The bookmarked views and their preview.
    pub views: SceneViews,
    /// The observer of the ray-tree figure while the figure is shown: the image renders from it
    /// and navigation moves it, while `controls.camera` stays the scene camera the picked
    /// pixel's tree is traced with.
    pub observer: Option<CameraSpec>,
}

impl ShownScene {
    /// The controls the image renders with: the observer's camera while the figure is shown.
    pub fn rendered_controls(&self) -> Cow<'_, Controls> {
        match self.observer {
            Some(observer) => {
                let mut controls = self.controls.clone();
                controls.camera = observer;
                Cow::Owned(controls)
            }
            None => Cow::Borrowed(&self.controls),
        }
    }
}

/// Where the scene stands.
pub enum SceneState {
    /// The first scene is loading: nothing to show yet.
    Loading,
    /// The last load failed (`file:line:column: message`); the last good scene, if there is one,
    /// stays on screen.
    Failed {
        error: String,
        last_good: Option<ShownScene>,
    },
    /// A scene is shown.
    Loaded(ShownScene),
}

/// The shown scene as the side panel sees it.
pub struct SceneInfo<'a> {
    pub scene: &'a LoadedScene,
    /// Why the last load failed, if it did.
    pub load_error: Option<&'a str>,
    /// The scene files beside the one asked for.
    pub files_beside: &'a [PathBuf],
    /// The bookmarked views.
    pub views: &'a SceneViews,
}

/// The scene, the loads that bring it and the file watched for changes.
pub struct SceneSlot {
    state: SceneState,
    /// The command line's overrides of each scene's settings, and the debug view each scene
    /// starts with. A size or a debug view the user picks later replaces them, so that it stays
    /// for the next scenes.
    overrides: SettingsOverrides,
    debug_view: DebugView,
    /// The tracer the shaded image is rendered with, and where the eye rays find their first
    /// hits, kept for the next scenes as the debug view.
    device: Device,
    first_hit: FirstHit,
    /// The scene file asked for last (watched even while it fails to load); `None` for the
    /// built-in default scene.
    requested: Option<PathBuf>,
    /// The command line's scene file and the format it said to read it in (`--format`),
    /// whenever that file is loaded; other files are read in the format their names say.
    format: Option<(PathBuf, SceneFormat)>,
    /// The scene files beside the requested one, for quick switching.
    files_beside: Vec<PathBuf>,
    watcher: Option<SceneWatcher>,
    /// The number of the latest load; the results of older ones are dropped.
    generation: u64,
    /// A load is under way.
    loading: bool,
    /// Scene loads finished (well or not), for the script's `wait-load`.
    loads: u64,
    /// The scene file and the text the viewer last wrote into it (Save scene), so that the
    /// watcher's news of that write does not reload it.
    written: Option<(PathBuf, String)>,
    /// Where the loader and the watcher send their news.
    news: NewsSender,
}

impl SceneSlot {
    /// Nothing loaded yet; `first` is the scene to load first (the default scene for `None`),
    /// read in `format` if given.
    pub fn new(
        first: Option<PathBuf>,
        format: Option<SceneFormat>,
        overrides: SettingsOverrides,
        debug_view: DebugView,
        (device, first_hit): (Device, FirstHit),
        news: NewsSender,
    ) -> SceneSlot {
        SceneSlot {
            state: SceneState::Loading,
            overrides,
            debug_view,
            device,
            first_hit,
            format: first.clone().zip(format),
            requested: first,
            files_beside: Vec::new(),
            watcher: None,
            generation: 0,
            loading: false,
            loads: 0,
            written: None,
            news,
        }
    }

    /// The scene file asked for last (`None`: the default scene).
    pub fn requested(&self) -> Option<PathBuf> {
        self.requested.clone()
    }

    /// Starts loading `path` (the default scene for `None`) and watches it. The error says why
    /// the file is not watched; the load goes ahead anyway.
    pub fn start_load(&mut self, path: Option<PathBuf>) -> Result<(), String> {
        self.generation += 1;
        self.loading = true;
        let mut watch_error = Ok(());
        if self.requested != path || (path.is_some() && self.watcher.is_none()) {
            // Only files are watched (not `spd:` names).
            self.watcher = path.as_deref().filter(|p| p.is_file()).and_then(|p| {
                let news = self.news.clone();
                SceneWatcher::new(p, move |changed| {
                    news(SceneNews::FileChanged(changed.to_path_buf()));
                })
                .map_err(|e| watch_error = Err(e))
                .ok()
            });
        }
        self.requested = path.clone();
        self.written = None;
        self.files_beside = source::scene_files_beside(path.as_deref());
        let (news, generation) = (self.news.clone(), self.generation);
        let format = self
            .format
            .as_ref()
            .filter(|(file, _)| path.as_ref() == Some(file))
            .map(|&(_, format)| format);
        source::spawn_load(path, format, move |result| {
            let result = result.map(Box::new);
            news(SceneNews::Loaded { generation, result });
        });
        watch_error
    }

    /// Whether a load's result is of the latest load (older ones are dropped).
    pub fn is_latest(&self, generation: u64) -> bool {
        generation == self.generation
    }

    /// Takes the latest load's result: the new scene is shown, or the error kept beside the last
    /// good scene. A reload of the same file keeps the user's camera and settings unless the
    /// file itself changed them.
    pub fn finish_load(
        &mut self,
        result: Result<Box<LoadedScene>, String>,
    ) -> Result<Arc<LoadedScene>, String> {
        self.loading = false;
        self.loads += 1;
        let last_good = match std::mem::replace(&mut self.state, SceneState::Loading) {
            SceneState::Loading => None,
            SceneState::Failed { last_good, .. } => last_good,
            SceneState::Loaded(shown) => Some(shown),
        };
        // The scene with the overrides applied (they were checked before the window opened, so
        // only a scene's own bad settings can fail here).
        let with_overrides = result.and_then(|loaded| {
            let mut controls =
                Controls::with_overrides(loaded.scene(), &self.overrides, self.debug_view)?;
            controls.device = self.device;
            controls.first_hit = self.first_hit;
            Ok((loaded, controls))
        });
        let (loaded, with_overrides) = match with_overrides {
            Ok(both) => both,
            Err(error) => {
                self.state = SceneState::Failed {
                    error: error.clone(),
                    last_good,
                };
                return Err(error);
            }
        };
        // The file's own controls, to tell on the next reload what the file changed.
        let file_controls = Controls::from_scene(loaded.scene());
        let controls = match last_good {
            Some(old) if old.scene.path == loaded.path => {
                let mut controls = old.controls;
                if old.file_controls.camera != file_controls.camera {
                    controls.camera = with_overrides.camera;
                }
                if old.file_controls.settings != file_controls.settings {
                    controls.settings = with_overrides.settings;
                }
                if old.file_controls.materials != file_controls.materials {
                    controls.materials = with_overrides.materials;
                }
                if old.file_controls.lights != file_controls.lights {
                    controls.lights = with_overrides.lights;
                }
                controls
            }
            _ => with_overrides,
        };
        let views = SceneViews::new(loaded.views.clone(), loaded.path.as_deref());
        let scene: Arc<LoadedScene> = Arc::from(loaded);
        self.state = SceneState::Loaded(ShownScene {
            scene: scene.clone(),
            controls,
            file_controls,
            views,
            observer: None,
        });
        Ok(scene)
    }

    /// The scene on screen (the last good one after a failed load), if any.
    pub fn shown(&self) -> Option<&ShownScene> {
        match &self.state {
            SceneState::Loaded(shown)
            | SceneState::Failed {
                last_good: Some(shown),
                ..
            } => Some(shown),
            _ => None,
        }
    }

    pub fn shown_mut(&mut self) -> Option<&mut ShownScene> {
        match &mut self.state {
            SceneState::Loaded(shown)
            | SceneState::Failed {
                last_good: Some(shown),
                ..
            } => Some(shown),
            _ => None,
        }
    }

    /// Why the last load failed, if it did.
    pub fn load_error(&self) -> Option<&str> {
        match &self.state {
            SceneState::Failed { error, .. } => Some(error),
            _ => None,
        }
    }

    /// What the side panel shows of the scene, and the controls it edits; `None` while no scene
    /// is shown.
    pub fn for_panel(&mut self) -> Option<(SceneInfo<'_>, &mut Controls)> {
        let (shown, load_error) = match &mut self.state {
            SceneState::Loaded(shown) => (shown, None),
            SceneState::Failed {
                error,
                last_good: Some(shown),
            } => (shown, Some(error.as_str())),
            _ => return None,
        };
        let info = SceneInfo {
            scene: &shown.scene,
            load_error,
            files_beside: &self.files_beside,
            views: &shown.views,
        };
        Some((info, &mut shown.controls))
    }

    /// Writes the edited materials and lights into the shown scene's TOML file, atomically, and
    /// remembers the text written (see [`SceneSlot::wrote_it`]); returns a line saying what was
    /// saved. The error says why nothing was saved.
    pub fn save_edits(&mut self) -> Result<String, String> {
        let Some(shown) = self.shown_mut() else {
            return Err("no scene is shown".into());
        };
        let path = match &shown.scene.path {
            Some(path) if shown.scene.toml_file => path.clone(),
            _ => return Err(cannot_save(&shown.scene)),
        };
        shown.controls.check_edits()?;
        let names = &shown.scene.scene().material_names;
        let saved = save_edits(
            &path,
            looks(names, &shown.file_controls),
            looks(names, &shown.controls),
        )?;
        // The file has the edits now: a reload compares with them.
        shown.file_controls.materials = shown.controls.materials.clone();
        shown.file_controls.lights = shown.controls.lights.clone();
        let mut message = format!(
            "saved the scene's materials and lights in {}",
            path.display()
        );
        for line in saved.unsaved {
            message += &format!("\n{line}");
        }
        self.written = Some((path, saved.text));
        Ok(message)
    }

    /// Whether the file at `changed` holds what Save scene last wrote into it: the watcher's news
    /// of the viewer's own write, which needs no reload.
    pub fn wrote_it(&self, changed: &Path) -> bool {
        self.written.as_ref().is_some_and(|(path, text)| {
            path.file_name() == changed.file_name()
                && std::fs::read_to_string(changed).is_ok_and(|now| now == *text)
        })
    }

    /// A load is under way.
    pub fn loading(&self) -> bool {
        self.loading
    }

    /// Scene loads finished so far, well or not.
    pub fn loads(&self) -> u64 {
        self.loads
    }

    /// The shown controls are being rendered: a size the user chose (not the one the scene
    /// started with), the debug view and the device, stay for the next scenes.
    pub fn keep_choices(&mut self) {
        let Some(shown) = self.shown() else { return };
        let settings = &shown.controls.settings;
        let file = &shown.file_controls.settings;
        let started = (
            self.overrides.width.unwrap_or(file.width),
            self.overrides.height.unwrap_or(file.height),
        );
        let size = (settings.width, settings.height);
        let (debug_view, device) = (shown.controls.debug_view, shown.controls.device);
        self.first_hit = shown.controls.first_hit;
        if size != started {
            (self.overrides.width, self.overrides.height) = (Some(size.0), Some(size.1));
        }
        self.debug_view = debug_view;
        self.device = device;
    }
}

/// The materials (called `names`) and lights of `controls`.
fn looks<'a>(names: &'a [String], controls: &'a Controls) -> Looks<'a> {
    Looks {
        names,
        materials: &controls.materials,
        lights: &controls.lights,
    }
}

/// Why the scene `loaded` cannot be saved: it is not a TOML scene file.
pub fn cannot_save(loaded: &LoadedScene) -> String {
    match &loaded.path {
        None => "the built-in scene has no file to save into; open a TOML scene file".into(),
        Some(path) => format!(
            "only TOML scene files can be saved (with their comments kept); {} is not one",
            path.display()
        ),
    }
}
