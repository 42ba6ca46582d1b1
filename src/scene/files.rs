//! Where a scene's texture and OBJ files come from: a folder on disk (relative to the scene
//! file), or files held in memory (those built into the binary for the built-in scenes).

use std::borrow::Cow;
use std::path::{Path, PathBuf};

/// The source of the files a scene names.
#[derive(Clone, Copy, Debug)]
pub enum SceneFiles<'a> {
    /// Files on disk; names are relative to this folder.
    Folder(&'a Path),
    /// Files held in memory (compiled into the binary for the built-in scenes), by the name
    /// the scene uses.
    Builtin(&'a [(&'a str, &'a [u8])]),
}

impl<'a> SceneFiles<'a> {
    /// The path that `name` stands for, for messages and for finding files next to it.
    pub fn path(&self, name: &str) -> PathBuf {
        match self {
            SceneFiles::Folder(folder) => folder.join(name),
            SceneFiles::Builtin(_) => PathBuf::from(name),
        }
    }

    /// The bytes of the file at `path` (as returned by [`Self::path`] or a path beside it).
    pub fn read(&self, path: &Path) -> Result<Cow<'a, [u8]>, String> {
        match self {
            SceneFiles::Folder(_) => std::fs::read(path)
                .map(Cow::Owned)
                .map_err(|e| e.to_string()),
            SceneFiles::Builtin(files) => files
                .iter()
                .find(|(name, _)| Path::new(name) == path)
                .map(|(_, bytes)| Cow::Borrowed(*bytes))
                .ok_or_else(|| "no such built-in file".to_string()),
        }
    }
}
