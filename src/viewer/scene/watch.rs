//! Scene file watching: the file's folder is watched (editors often save by writing a new file and
//! renaming it over the old one, which a watch on the file itself would lose), and every change to
//! the file or to its `NAME.camera.toml` calls back, so the viewer re-renders when either is saved.

use std::path::Path;

use notify::{EventKind, RecursiveMode, Watcher};
use raylab::formats::camera_path;

/// Watches one file while it lives.
pub struct SceneWatcher {
    _watcher: notify::RecommendedWatcher,
}

impl SceneWatcher {
    /// Calls `changed` with the file's path (on the watcher's thread) each time the file at
    /// `path`, or the camera file beside it, is written, created, renamed or removed.
    pub fn new(
        path: &Path,
        changed: impl Fn(&Path) + Send + 'static,
    ) -> Result<SceneWatcher, String> {
        let file = std::path::absolute(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let folder = file.parent().unwrap_or(Path::new("/")).to_path_buf();
        let names =
            [file.clone(), camera_path(&file)].map(|f| f.file_name().map(|n| n.to_os_string()));
        let mut watcher =
            notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
                let Ok(event) = event else { return };
                let relevant = matches!(
                    event.kind,
                    EventKind::Create(_) | EventKind::Modify(_) | EventKind::Remove(_)
                );
                let watched =
                    |p: &std::path::PathBuf| names.iter().any(|n| p.file_name() == n.as_deref());
                if relevant && let Some(path) = event.paths.iter().find(|p| watched(p)) {
                    changed(path);
                }
            })
            .map_err(|e| format!("cannot watch {}: {e}", path.display()))?;
        watcher
            .watch(&folder, RecursiveMode::NonRecursive)
            .map_err(|e| format!("cannot watch {}: {e}", folder.display()))?;
        Ok(SceneWatcher { _watcher: watcher })
    }
}

#[cfg(test)]
mod tests {
    use std::sync::mpsc;
    use std::time::Duration;

    use super::*;

    #[test]
    fn saving_the_file_or_its_camera_file_calls_back_and_other_files_do_not() {
        use std::sync::Arc;
        use std::sync::atomic::{AtomicBool, Ordering::SeqCst};

        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("scene.toml");
        std::fs::write(&scene, "a").unwrap();
        // Each call back says whether the scene file had been touched yet.
        let touched = Arc::new(AtomicBool::new(false));
        let (sender, receiver) = mpsc::channel();
        let seen = touched.clone();
        let _watcher = SceneWatcher::new(&scene, move |_| {
            let _ = sender.send(seen.load(SeqCst));
        })
        .unwrap();
        // Other files first. The watcher's thread takes the folder's changes in order, so a call
        // back for them would come before the scene file's and (unless that thread lags behind
        // all twenty writes) say that the scene file was not touched yet.
        for i in 0..20 {
            std::fs::write(dir.path().join(format!("other-{i}.toml")), "b").unwrap();
        }
        touched.store(true, SeqCst);
        // Written in place, then replaced by a rename as many editors do.
        std::fs::write(&scene, "c").unwrap();
        assert_eq!(receiver.recv_timeout(Duration::from_secs(5)), Ok(true));
        while receiver.try_recv().is_ok() {}
        let temp = dir.path().join(".scene.toml.swp");
        std::fs::write(&temp, "d").unwrap();
        std::fs::rename(&temp, &scene).unwrap();
        assert_eq!(receiver.recv_timeout(Duration::from_secs(5)), Ok(true));
        while receiver.try_recv().is_ok() {}
        std::fs::write(dir.path().join("scene.camera.toml"), "[camera]").unwrap();
        assert_eq!(receiver.recv_timeout(Duration::from_secs(5)), Ok(true));
    }
}
