//! Writing images: PNG and PPM (8-bit sRGB) and OpenEXR and Radiance HDR (linear floats), chosen
//! by the file's extension. Files are written atomically ([`write_atomically`], also used for
//! other files raylab writes): into a temporary file beside the target, then renamed over it, so
//! an interrupted run never leaves half an image. A path can be checked before long work
//! ([`check_writable`], [`check_image_path`]); a symbolic link is written through, and a
//! read-only file is refused, not replaced. The temporary files of writes in progress are
//! known, so that a program stopped by a signal can remove them ([`remove_temporary_files`]).

use std::fs::File;
use std::io::{self, BufWriter, ErrorKind, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use image::codecs::pnm::{PnmEncoder, PnmSubtype, SampleEncoding};
use image::{DynamicImage, ImageFormat, Rgb32FImage, RgbImage};

use crate::color::{Color, to_srgb8};

/// The image formats raylab writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputFormat {
    Png,
    Ppm,
    Exr,
    Hdr,
}

impl OutputFormat {
    pub const EXTENSIONS: &'static str = "png, ppm, exr, hdr";

    /// Memory that saving an image of `pixels` pixels takes, at most: the linear pixels handed
    /// to [`save_image`], the encoder's input and what the encoder keeps while it writes.
    pub fn save_bytes(self, pixels: u64) -> u64 {
        let per_pixel = match self {
            OutputFormat::Png | OutputFormat::Ppm => 12 + 3 + 3,
            OutputFormat::Exr | OutputFormat::Hdr => 12 + 12 + 12,
        };
        pixels * per_pixel
    }

    /// The format a file name's extension asks for.
    pub fn from_path(path: &Path) -> Option<OutputFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(OutputFormat::Png),
            "ppm" => Some(OutputFormat::Ppm),
            "exr" => Some(OutputFormat::Exr),
            "hdr" => Some(OutputFormat::Hdr),
            _ => None,
        }
    }
}

/// Why an image could not be written.
#[derive(Debug)]
pub enum OutputError {
    UnknownFormat(PathBuf),
    Io(PathBuf, std::io::Error),
    Encode(PathBuf, image::ImageError),
    /// The pixel buffer does not hold `width × height` pixels.
    PixelCount {
        expected: usize,
        got: usize,
    },
}

impl std::fmt::Display for OutputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OutputError::UnknownFormat(p) => write!(
                f,
                "{}: unknown image format (use one of: {})",
                p.display(),
                OutputFormat::EXTENSIONS
            ),
            OutputError::Io(p, e) => write!(f, "{}: {e}", p.display()),
            OutputError::Encode(p, e) => write!(f, "{}: {e}", p.display()),
            OutputError::PixelCount { expected, got } => {
                write!(f, "image needs {expected} pixels, got {got}")
            }
        }
    }
}

impl std::error::Error for OutputError {}

/// Checks, before the long work that makes it, that an image can be saved at `path`: its
/// extension names a format raylab writes, and [`check_writable`] passes.
pub fn check_image_path(path: &Path) -> Result<OutputFormat, OutputError> {
    let format =
        OutputFormat::from_path(path).ok_or_else(|| OutputError::UnknownFormat(path.into()))?;
    check_writable(path).map_err(|e| OutputError::Io(path.into(), e))?;
    Ok(format)
}

/// Writes `pixels` (linear RGB, row 0 at the top) to `path` in the format its extension names.
pub fn save_image(
    path: &Path,
    width: u32,
    height: u32,
    pixels: &[Color],
) -> Result<(), OutputError> {
    let format = check_image_path(path)?;
    let expected = width as usize * height as usize;
    if pixels.len() != expected {
        return Err(OutputError::PixelCount {
            expected,
            got: pixels.len(),
        });
    }
    let io = |e| OutputError::Io(path.into(), e);
    let encode = |e| OutputError::Encode(path.into(), e);
    write_atomically(path, io, |out| {
        match format {
            OutputFormat::Png | OutputFormat::Ppm => {
                let srgb = RgbImage::from_raw(width, height, to_srgb8(pixels)).ok_or(
                    OutputError::PixelCount {
                        expected,
                        got: pixels.len(),
                    },
                )?;
                if format == OutputFormat::Png {
                    srgb.write_to(out, ImageFormat::Png).map_err(encode)?;
                } else {
                    let encoder = PnmEncoder::new(out)
                        .with_subtype(PnmSubtype::Pixmap(SampleEncoding::Binary));
                    srgb.write_with_encoder(encoder).map_err(encode)?;
                }
            }
            OutputFormat::Exr | OutputFormat::Hdr => {
                let floats: Vec<f32> = pixels.iter().flat_map(|c| c.to_array()).collect();
                let linear = Rgb32FImage::from_raw(width, height, floats).ok_or(
                    OutputError::PixelCount {
                        expected,
                        got: pixels.len(),
                    },
                )?;
                let image_format = if format == OutputFormat::Exr {
                    ImageFormat::OpenExr
                } else {
                    ImageFormat::Hdr
                };
                DynamicImage::ImageRgb32F(linear)
                    .write_to(out, image_format)
                    .map_err(encode)?;
            }
        }
        Ok(())
    })
}

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
    use crate::color::linear_to_srgb;

    fn gradient(w: u32, h: u32) -> Vec<Color> {
        (0..w * h)
            .map(|i| Color::new((i % w) as f32 / w as f32, (i / w) as f32 / h as f32, 0.5))
            .collect()
    }

    #[test]
    fn every_format_round_trips() {
        let dir = tempfile::tempdir().unwrap();
        let pixels = gradient(7, 5);
        for ext in ["png", "ppm", "exr", "hdr"] {
            let path = dir.path().join(format!("out.{ext}"));
            save_image(&path, 7, 5, &pixels).unwrap();
            let back = image::open(&path).unwrap().to_rgb32f();
            assert_eq!((back.width(), back.height()), (7, 5), "{ext}");
            let back: Vec<f32> = back.into_raw();
            let linear = matches!(ext, "exr" | "hdr");
            for (i, c) in pixels.iter().enumerate() {
                for ch in 0..3 {
                    let expected = if linear { c[ch] } else { linear_to_srgb(c[ch]) };
                    let got = back[i * 3 + ch];
                    assert!(
                        (got - expected).abs() < 0.02,
                        "{ext} pixel {i}: {got} vs {expected}"
                    );
                }
            }
        }
        let leftovers = std::fs::read_dir(dir.path())
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .ends_with(".tmp")
            })
            .count();
        assert_eq!(leftovers, 0, "no temporary files left behind");
    }

    #[cfg(unix)]
    #[test]
    fn images_are_readable_by_others_like_any_new_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("shared.png");
        save_image(&path, 1, 1, &[Color::ONE]).unwrap();
        let mode = std::fs::metadata(&path).unwrap().permissions().mode();
        assert_eq!(mode & 0o044, 0o044, "mode {mode:o}");
    }

    #[test]
    fn ppm_is_binary_p6() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("x.ppm");
        save_image(&path, 2, 1, &[Color::ONE, Color::ZERO]).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert!(bytes.starts_with(b"P6"));
        assert!(bytes.ends_with(&[255, 255, 255, 0, 0, 0]));
    }

    #[test]
    fn unknown_extensions_and_missing_folders_are_errors() {
        let err = save_image(Path::new("out.gif"), 1, 1, &[Color::ONE]).unwrap_err();
        assert!(err.to_string().contains("unknown image format"), "{err}");
        let err = save_image(Path::new("/no/such/dir/out.png"), 1, 1, &[Color::ONE]).unwrap_err();
        assert!(matches!(err, OutputError::Io(..)), "{err}");
    }

    #[test]
    fn a_failed_write_keeps_the_old_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("keep.png");
        std::fs::write(&path, b"old").unwrap();
        // Too few pixels cannot be encoded; the old file must survive.
        let err = save_image(&path, 4, 4, &[Color::ONE]).unwrap_err();
        assert!(matches!(
            err,
            OutputError::PixelCount {
                expected: 16,
                got: 1
            }
        ));
        assert_eq!(std::fs::read(&path).unwrap(), b"old");
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
        let err = check_image_path(&dir.path().join("x.gif")).unwrap_err();
        assert!(matches!(err, OutputError::UnknownFormat(_)), "{err}");
        assert_eq!(
            check_image_path(&dir.path().join("x.EXR")).unwrap(),
            OutputFormat::Exr
        );
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
        // At the save too (the file may have become read-only during the work).
        let err = save_image(&path, 1, 1, &[Color::ONE]).unwrap_err();
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
            save_image(path, 1, 1, &[Color::ONE]).unwrap();
            let kind = std::fs::symlink_metadata(path).unwrap().file_type();
            assert!(kind.is_symlink(), "{} stays a link", path.display());
        }
        for target in ["real/target.png", "real/new.png"] {
            let image = image::open(dir.path().join(target)).unwrap();
            assert_eq!(image.width(), 1, "{target}");
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
