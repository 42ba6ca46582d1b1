//! The scene's bookmarked views and their previews: `Ctrl+1…9` stores the camera as a view and
//! `1…9` recalls it; the views live in the `NAME.views.toml` beside the scene file (written,
//! atomically, at each store; read with the scene, see [`super::source::load`]). A preview of a
//! turntable or of the path through the views moves the camera one frame at a time, each time
//! the frame before has reached the screen (at the coarse block size the render starts with).

use std::io::Write;
use std::path::{Path, PathBuf};

use raylab::camera::{Camera, CameraSpec};
use raylab::formats::toml::views_text;
use raylab::formats::views_path;
use raylab::output::write_atomically;
use raylab::views::{Views, path, turntable};

/// Frames of the turntable the `T` key and the panel's button preview: 5° a frame.
pub const TURNTABLE_FRAMES: u32 = 72;
/// Frames per stretch between two views of the path the `P` key and the panel's button preview.
pub const PATH_FRAMES_PER_VIEW: u32 = 30;

/// A scene's views, the file they are kept in, and the preview playing, if any.
pub struct SceneViews {
    pub views: Views,
    /// `NAME.views.toml` beside the scene file; `None` for a built-in scene, whose views last
    /// as long as the viewer.
    file: Option<PathBuf>,
    preview: Option<Preview>,
}

/// The cameras of a preview still to show.
struct Preview {
    cameras: std::vec::IntoIter<CameraSpec>,
}

impl SceneViews {
    /// The views read with the scene at `scene_file` (`None`: a built-in scene).
    pub fn new(views: Views, scene_file: Option<&Path>) -> SceneViews {
        SceneViews {
            views,
            file: scene_file.map(views_path),
            preview: None,
        }
    }

    /// Stores `camera` as view `number` and writes the views file; returns what was done.
    pub fn store(&mut self, number: u8, camera: CameraSpec) -> Result<String, String> {
        self.views.set(number, camera)?;
        let Some(file) = &self.file else {
            return Ok(format!(
                "view {number} stored (until the viewer closes: a built-in scene has no file to \
                 keep views beside)"
            ));
        };
        let text = views_text(&self.views);
        write_atomically(
            file,
            |e| format!("cannot store view {number}: {}: {e}", file.display()),
            |out| out.write_all(text.as_bytes()).map_err(|e| e.to_string()),
        )?;
        Ok(format!("view {number} stored in {}", file.display()))
    }

    /// Starts a turntable of `frames` frames around `camera`, ending back on it; or stops the
    /// preview playing.
    pub fn toggle_turntable(&mut self, camera: CameraSpec, frames: u32) -> Result<String, String> {
        if self.preview.take().is_some() {
            return Ok("preview stopped".into());
        }
        let mut cameras = specs(turntable(&camera, frames)?);
        cameras.push(camera);
        self.preview = Some(Preview {
            cameras: cameras.into_iter(),
        });
        Ok(format!("turntable of {frames} frames"))
    }

    /// Starts the path through the views in `frames` frames (by default
    /// [`PATH_FRAMES_PER_VIEW`] a stretch); or stops the preview playing.
    pub fn toggle_path(&mut self, frames: Option<u32>) -> Result<String, String> {
        if self.preview.take().is_some() {
            return Ok("preview stopped".into());
        }
        let stops = self.views.cameras();
        let frames = frames.unwrap_or(PATH_FRAMES_PER_VIEW * (stops.len().max(2) as u32 - 1));
        let cameras = specs(
            path(&stops, frames)
                .map_err(|e| format!("{e} (Ctrl+1…9 stores the camera as a view)"))?,
        );
        self.preview = Some(Preview {
            cameras: cameras.into_iter(),
        });
        Ok(format!(
            "path through {} views in {frames} frames",
            stops.len()
        ))
    }

    /// A preview is playing.
    pub fn previewing(&self) -> bool {
        self.preview.is_some()
    }

    /// The preview's next camera (the preview ends after its last).
    pub fn next_frame(&mut self) -> Option<CameraSpec> {
        let preview = self.preview.as_mut()?;
        let next = preview.cameras.next();
        if preview.cameras.len() == 0 {
            self.preview = None;
        }
        next
    }
}

fn specs(cameras: Vec<Camera>) -> Vec<CameraSpec> {
    cameras.into_iter().map(|c| c.spec).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storing_writes_the_views_file_beside_the_scene() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("room.toml");
        let mut views = SceneViews::new(Views::default(), Some(&scene));
        let message = views.store(2, CameraSpec::default()).unwrap();
        assert!(message.contains("room.views.toml"), "{message}");
        let text = std::fs::read_to_string(dir.path().join("room.views.toml")).unwrap();
        assert!(text.contains("[view.2]"), "{text}");
        assert!(views.store(0, CameraSpec::default()).is_err());
        let mut builtin = SceneViews::new(Views::default(), None);
        assert!(builtin.store(1, CameraSpec::default()).is_ok());
        assert_eq!(builtin.views.get(1), Some(CameraSpec::default()));
    }

    #[test]
    fn a_turntable_preview_plays_its_frames_and_ends_on_the_camera() {
        let mut views = SceneViews::new(Views::default(), None);
        let camera = CameraSpec::default();
        views.toggle_turntable(camera, 4).unwrap();
        let played: Vec<_> = std::iter::from_fn(|| views.next_frame()).collect();
        assert_eq!(played.len(), 5);
        assert_eq!((played[0], played[4]), (camera, camera));
        assert_ne!(played[2], camera);
        assert!(!views.previewing());
        // The key stops a preview that plays.
        views.toggle_turntable(camera, 4).unwrap();
        assert!(views.previewing());
        views.toggle_turntable(camera, 4).unwrap();
        assert!(!views.previewing());
    }

    #[test]
    fn a_path_preview_needs_two_views() {
        let mut views = SceneViews::new(Views::default(), None);
        let error = views.toggle_path(None).unwrap_err();
        assert!(error.contains("at least 2 views, got 0"), "{error}");
        views.store(1, CameraSpec::default()).unwrap();
        let mut other = CameraSpec::default();
        other.eye.x = 3.0;
        views.store(4, other).unwrap();
        views.toggle_path(Some(3)).unwrap();
        let played: Vec<_> = std::iter::from_fn(|| views.next_frame()).collect();
        assert_eq!(played.len(), 3);
        assert_eq!((played[0], played[2]), (CameraSpec::default(), other));
    }
}
