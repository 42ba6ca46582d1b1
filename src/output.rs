//! Writing raylab's output files safely (images, generated NFF files, benchmark reports):
//! atomically ([`write_atomically`]): into a temporary file beside the target, then renamed
//! over it, so an interrupted run never leaves half a file. A path can be checked before long
//! work ([`check_writable`]); a symbolic link is written through, and a read-only file is
//! refused, not replaced. The temporary files of writes in progress are known, so that a
//! program stopped by a signal can remove them ([`remove_temporary_files`]).

use std::fs::File;
use std::io::{self, BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// Checks that [`write_atomically`] can write `path` (through a symbolic link, its target):
/// the folder exists and takes new files, and the file, if there is one, is neither a folder
/// nor read-only. For a check before long work; the error says what is wrong, without the path.
pub fn check_writable(path: &Path) -> io::Result<()> {
    let target = link_target(path)?;
    check_target(&target)?;
    // Only creating a file there tells whether the folder takes one (permissions, a read-only
    // file system). The probe is gone before the registry is unlocked, so a signal handler
    // never has to know about it.
    let dir = folder_of(&target);
    let _files = temporary_files();
    temporary_file_builder()
        .tempfile_in(dir)
        .map(drop)
        .map_err(|e| {
            let message = format!("cannot create a file in {}: {e}", dir.display());
            io::Error::new(e.kind(), message)
        })
}

/// Writes the file at `path` atomically: `write` fills a temporary file beside it, which then
/// replaces `path`, so a failed or interrupted write never leaves half a file (and keeps the old
/// one). A symbolic link is written through: its target is replaced and the link stays. A
/// folder or a read-only file at `path` is an error. `io` turns an I/O error into the caller's
/// error.
pub fn write_atomically<E>(
    path: &Path,
    io: impl Fn(io::Error) -> E,
    write: impl FnOnce(&mut BufWriter<&mut File>) -> Result<(), E>,
) -> Result<(), E> {
    let target = link_target(path).map_err(&io)?;
    check_target(&target).map_err(&io)?;
    let mut temp = {
        let mut files = temporary_files();
        let temp = temporary_file_builder()
            .tempfile_in(folder_of(&target))
            .map_err(&io)?;
        files.push(temp.path().to_path_buf());
        temp
    };
    let written = {
        let mut out = BufWriter::new(temp.as_file_mut());
        write(&mut out).and_then(|()| out.flush().map_err(&io))
    };
    // Renamed or removed while the registry is locked, so that a signal handler's
    // `remove_temporary_files` finds the write either in progress or over.
    let mut files = temporary_files();
    files.retain(|f| f != temp.path());
    match written {
        Ok(()) => temp.persist(&target).map(drop).map_err(|e| io(e.error)),
        Err(e) => {
            drop(temp);
            Err(e)
        }
    }
}

/// What writing `target` (no link) needs of it: its folder exists, and it is neither a folder
/// nor a read-only file (refused, as `cp` without `-f` does).
fn check_target(target: &Path) -> io::Result<()> {
    let dir = folder_of(target);
    if !dir.is_dir() {
        let message = if dir.exists() {
            format!("{} is not a folder", dir.display())
        } else {
            format!("the folder {} does not exist", dir.display())
        };
        return Err(io::Error::new(ErrorKind::NotFound, message));
    }
    match std::fs::metadata(target) {
        Ok(m) if m.is_dir() => Err(io::Error::new(ErrorKind::IsADirectory, "is a folder")),
        Ok(m) if m.permissions().readonly() => Err(io::Error::new(
            ErrorKind::PermissionDenied,
            "is read-only (raylab does not replace read-only files)",
        )),
        _ => Ok(()),
    }
}

/// Removes the temporary files of the writes in progress, then runs `then` before any write
/// can start or finish: for a signal handler, whose `then` exits the process. Returns what
/// `then` returns.
pub fn remove_temporary_files<R>(then: impl FnOnce() -> R) -> R {
    let mut files = temporary_files();
    remove_files(&mut files);
    then()
}

/// Removes the files and empties the list.
fn remove_files(files: &mut Vec<PathBuf>) {
    for file in files.drain(..) {
        // A file already gone is what we want.
        let _ = std::fs::remove_file(file);
    }
}

/// The temporary files of the writes in progress.
static TEMPORARY_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn temporary_files() -> MutexGuard<'static, Vec<PathBuf>> {
    // The list stays valid whatever a panicking holder was doing.
    TEMPORARY_FILES
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
}

/// Temporary files `.raylab-*.tmp`, readable by others like any new file (not 0600).
fn temporary_file_builder() -> tempfile::Builder<'static, 'static> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".raylab-").suffix(".tmp");
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o644));
    builder
}

/// The folder a file is in (`.` for a bare file name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Where writing `path` ends up: `path` itself, or the file its chain of symbolic links points
/// to (which need not exist yet).
fn link_target(path: &Path) -> io::Result<PathBuf> {
    /// As many links as Linux follows before giving up (ELOOP).
    const MOST_LINKS: usize = 40;
    let mut path = path.to_path_buf();
    for _ in 0..MOST_LINKS {
        match std::fs::symlink_metadata(&path) {
            Ok(m) if m.file_type().is_symlink() => {
                // A relative link is relative to its own folder.
                let link = std::fs::read_link(&path)?;
                path = folder_of(&path).join(link);
            }
            _ => return Ok(path),
        }
    }
    Err(io::Error::new(
        ErrorKind::InvalidInput,
        "too many levels of symbolic links",
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes `text` to `path` with [`write_atomically`].
    fn write_text(path: &Path, text: &str) -> io::Result<()> {
        write_atomically(path, |e| e, |out| out.write_all(text.as_bytes()))
    }

    #[test]
    fn bad_paths_are_found_before_any_work() {
        let dir = tempfile::tempdir().unwrap();
        let reason = |path: &Path| check_writable(path).unwrap_err().to_string();
        assert!(reason(&dir.path().join("no/x.png")).contains("does not exist"));
        assert!(reason(dir.path()).contains("is a folder"));
        let file = dir.path().join("file");
        std::fs::write(&file, b"").unwrap();
        assert!(reason(&file.join("x.png")).contains("is not a folder"));
        check_writable(&dir.path().join("new.png")).unwrap();
        check_writable(&file).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn files_are_readable_by_others_like_any_new_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("shared.png");
        write_text(&path, "x").unwrap();
        let mode = std::fs::metadata(&path).unwrap().permissions().mode();
        assert_eq!(mode & 0o044, 0o044, "mode {mode:o}");
    }

    #[test]
    fn a_read_only_file_is_refused_and_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("keep.png");
        std::fs::write(&path, b"old").unwrap();
        let mut permissions = std::fs::metadata(&path).unwrap().permissions();
        permissions.set_readonly(true);
        std::fs::set_permissions(&path, permissions).unwrap();
        let err = check_writable(&path).unwrap_err();
        assert!(err.to_string().contains("read-only"), "{err}");
        // At the write too (the file may have become read-only during the work).
        let err = write_text(&path, "new").unwrap_err();
        assert!(err.to_string().contains("read-only"), "{err}");
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
    }

    #[cfg(unix)]
    #[test]
    fn a_symbolic_link_is_written_through() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("real")).unwrap();
        std::fs::write(dir.path().join("real/target.png"), b"old").unwrap();
        // Relative links: each is relative to its own folder.
        let link = dir.path().join("link.png");
        std::os::unix::fs::symlink("real/target.png", &link).unwrap();
        let dangling = dir.path().join("real/dangling.png");
        std::os::unix::fs::symlink("new.png", &dangling).unwrap();
        for path in [&link, &dangling] {
            write_text(path, "new").unwrap();
            let kind = std::fs::symlink_metadata(path).unwrap().file_type();
            assert!(kind.is_symlink(), "{} stays a link", path.display());
        }
        for target in ["real/target.png", "real/new.png"] {
            let text = std::fs::read_to_string(dir.path().join(target)).unwrap();
            assert_eq!(text, "new", "{target}");
        }
    }

    #[test]
    fn writes_in_progress_register_their_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let mine = || -> Vec<PathBuf> {
            let files = temporary_files();
            files
                .iter()
                .filter(|f| f.starts_with(dir.path()))
                .cloned()
                .collect()
        };
        let mut during = Vec::new();
        write_atomically(
            &dir.path().join("x.txt"),
            |e| e,
            |out| {
                during = mine();
                out.write_all(b"x")
            },
        )
        .unwrap();
        assert_eq!(during.len(), 1, "{during:?}");
        assert!(
            during[0]
                .file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with(".raylab-")
        );
        assert!(!during[0].exists(), "renamed");
        assert!(mine().is_empty(), "unregistered once written");

        // A failed write unregisters and removes its file too.
        let failed: io::Result<()> = write_atomically(
            &dir.path().join("y.txt"),
            |e| e,
            |_| Err(io::Error::other("no")),
        );
        assert!(failed.is_err());
        assert!(mine().is_empty());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "x.txt alone"
        );
    }

    #[test]
    fn the_cleanup_removes_the_files_it_is_given() {
        let dir = tempfile::tempdir().unwrap();
        let (left, gone) = (
            dir.path().join(".raylab-1.tmp"),
            dir.path().join("gone.tmp"),
        );
        std::fs::write(&left, b"half an image").unwrap();
        let mut files = vec![left.clone(), gone];
        remove_files(&mut files);
        assert!(!left.exists());
        assert!(files.is_empty());
    }
}
