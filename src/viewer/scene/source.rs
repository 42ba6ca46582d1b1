//! Where the viewer's scenes come from: a scene file or the built-in default scene, read and given
//! its BVH on a background thread so the window never waits, and the scene files beside the
//! current one for quick switching.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use raylab::aabb::Aabb;
use raylab::formats::nff::NffLighting;
use raylab::formats::toml::load_views;
use raylab::formats::toml::{default_scene, load_scene};
use raylab::formats::{SCENE_EXTENSIONS, SceneFormat, load_any_as, views_path};
use raylab::render::Assembled;
use raylab::scene::Scene;
use raylab::views::Views;

/// A scene ready to trace, with where it came from.
pub struct LoadedScene {
    /// The scene and its BVH; the viewer shoots the caustic photons for each render itself.
    pub assembled: Assembled,
    /// The scene file; `None` for the built-in default scene.
    pub path: Option<PathBuf>,
    /// The scene was read from a TOML file, which "Save scene" can write edits back into.
    pub toml_file: bool,
    /// Bounds of everything bounded (planes are not), for framing and flying speed.
    pub bounds: Aabb,
    /// Time to read the file and build the BVH.
    pub load_time: Duration,
    /// The views of the `NAME.views.toml` beside the file, as read.
    pub views: Views,
}

impl LoadedScene {
    pub fn scene(&self) -> &Scene {
        &self.assembled.scene
    }

    /// A name for the window title and messages.
    pub fn name(&self) -> String {
        match &self.path {
            Some(path) => path.display().to_string(),
            None => "built-in default scene".to_string(),
        }
    }
}

/// Reads the scene at `path` (a TOML, NFF, SDL or OBJ file, or an `spd:NAME[:SIZE]` name; the
/// default scene for `None`) in `format`, or the one its name says, with the views file beside
/// it, and builds its BVH. The error is the loader's message (`file:line:column: message`).
pub fn load(path: Option<&Path>, format: Option<SceneFormat>) -> Result<LoadedScene, String> {
    let start = Instant::now();
    let scene = match path {
        Some(path) => match path.to_str() {
            Some(name) => load_any_as(name, NffLighting::default(), format),
            None => load_scene(path),
        },
        None => default_scene(),
    }
    .map_err(|e| e.to_string())?;
    let views = match path.map(views_path).filter(|file| file.is_file()) {
        Some(file) => load_views(&file, scene.camera.spec).map_err(|e| e.to_string())?,
        None => scene.views.clone(),
    };
    let assembled = Assembled::without_caustics(scene);
    let bounds = assembled.bvh.bounds().unwrap_or(Aabb::EMPTY);
    let toml_file = path.is_some_and(|p| {
        p.is_file() && format.unwrap_or_else(|| SceneFormat::of(p)) == SceneFormat::Toml
    });
    Ok(LoadedScene {
        assembled,
        path: path.map(Path::to_path_buf),
        toml_file,
        bounds,
        load_time: start.elapsed(),
        views,
    })
}

/// Loads on a new thread and hands the result to `done` there.
pub fn spawn_load(
    path: Option<PathBuf>,
    format: Option<SceneFormat>,
    done: impl FnOnce(Result<LoadedScene, String>) + Send + 'static,
) {
    let spawned = std::thread::Builder::new()
        .name("scene loader".into())
        .spawn(move || done(load(path.as_deref(), format)));
    if let Err(e) = spawned {
        eprintln!("error: cannot start the scene loader thread: {e}");
    }
}

/// The scene files (`*.toml`, `*.nff`, SDL's `*.dat` and `*.sdl`, and `*.obj` models, sorted
/// by name, leaving out the cameras and views saved beside scenes, `NAME.camera.toml` and
/// `NAME.views.toml`) in the folder of `path`; for the built-in scene (`None`), those in
/// `assets/scenes` under the current folder, if there is one.
pub fn scene_files_beside(path: Option<&Path>) -> Vec<PathBuf> {
    let folder = match path {
        Some(p) => p.parent().map(Path::to_path_buf).unwrap_or_default(),
        None => PathBuf::from("assets/scenes"),
    };
    let folder = if folder.as_os_str().is_empty() {
        PathBuf::from(".")
    } else {
        folder
    };
    let Ok(entries) = std::fs::read_dir(&folder) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let ext = p.extension().and_then(|x| x.to_str());
            let known = |ext: &str| {
                SCENE_EXTENSIONS
                    .iter()
                    .any(|(name, _)| ext.eq_ignore_ascii_case(name))
            };
            p.is_file() && ext.is_some_and(known)
        })
        .filter(|p| {
            p.file_name().and_then(|n| n.to_str()).is_some_and(|n| {
                n != "Cargo.toml" && !n.ends_with(".camera.toml") && !n.ends_with(".views.toml")
            })
        })
        .collect();
    files.sort();
    files
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_scene_loads_with_finite_bounds() {
        let loaded = load(None, None).unwrap();
        assert!(loaded.path.is_none());
        assert!(loaded.bounds.min.is_finite() && loaded.bounds.max.is_finite());
        assert!(!loaded.scene().lights.is_empty());
    }

    #[test]
    fn spd_names_load_too() {
        let loaded = load(Some(Path::new("spd:balls:1")), None).unwrap();
        assert!(!loaded.scene().geometry.objects.is_empty());
    }

    #[test]
    fn a_missing_file_is_an_error_naming_it() {
        let err = load(Some(Path::new("/no/such/scene.toml")), None)
            .err()
            .unwrap();
        assert!(err.contains("/no/such/scene.toml"), "{err}");
    }

    #[test]
    fn scene_files_are_listed_sorted_without_other_files() {
        let dir = tempfile::tempdir().unwrap();
        for name in [
            "b.toml",
            "a.toml",
            "notes.txt",
            "Cargo.toml",
            "c.NFF",
            "d.dat",
            "a.camera.toml",
            "d.views.toml",
        ] {
            std::fs::write(dir.path().join(name), "").unwrap();
        }
        let files = scene_files_beside(Some(&dir.path().join("a.toml")));
        let names: Vec<_> = files
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, ["a.toml", "b.toml", "c.NFF", "d.dat"]);
    }
}
