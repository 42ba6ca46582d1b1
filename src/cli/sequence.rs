//! `raylab render`'s image sequences: `--turntable FRAMES` and `--path FILE --frames N`, the
//! cameras of their frames (the library's [`raylab::views`]) and the numbered file names that
//! `-o frames/%04d.png` gives them. Frames are numbered from 0; frame 0 is the scene's camera
//! (the turntable) or the first view (the path). A run can render some of the frames, as a job
//! of a scheduler: `--frames A..B` (frames A to B−1) or `--frame K` (see `jobs`); a path's
//! length is then `--path-length N`.

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use clap::Args;
use raylab::camera::{Camera, CameraSpec};
use raylab::formats::toml::load_views;
use raylab::formats::{SceneFormat, load_any};
use raylab::views::{path, turntable};

use super::jobs::FrameArg;

/// The flags of an image sequence.
#[derive(Args, Debug)]
pub struct SequenceArgs {
    /// Render a turntable of FRAMES images: the eye orbits the look-at point once about the
    /// camera's up axis, frame 0 being the scene's camera. -o names the frames with a number
    /// pattern, such as frames/%04d.png (frames 0000.png, 0001.png, …).
    #[arg(long, value_name = "FRAMES", conflicts_with = "path")]
    turntable: Option<u32>,
    /// Render a camera path through the views of a views file (NAME.views.toml, as the viewer
    /// saves them with Ctrl+1…9), or through the cameras of a glTF model (.gltf, .glb), in the
    /// order of their numbers, in --frames images: the first is the first view, the last the
    /// last view. -o as with --turntable.
    #[arg(long, value_name = "FILE")]
    path: Option<PathBuf>,
    /// How many images the --path sequence has (at least 2); or A..B: render only frames A to
    /// B−1 of the --turntable or --path sequence (half-open, as Rust's ranges), each written
    /// under its own number; a path's length then comes from --path-length.
    #[arg(long, value_name = "N|A..B")]
    frames: Option<FramesArg>,
    /// The number of images of the --path sequence, when --frames gives a range or --frame
    /// picks one.
    #[arg(long, value_name = "N", requires = "path")]
    path_length: Option<u32>,
    /// Render only frame K of the --turntable or --path sequence (numbered from 0), or `auto`:
    /// the scheduler's task index, as --tile auto reads it (with --tile auto too, task i is
    /// tile i mod N of frame i div N).
    #[arg(long, value_name = "K|auto")]
    frame: Option<FrameArg>,
}

/// `--frames`' value: a number of frames, or a range of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FramesArg {
    Count(u32),
    Range(u32, u32),
}

impl FromStr for FramesArg {
    type Err = String;
    fn from_str(s: &str) -> Result<FramesArg, String> {
        let bad = || format!("{s:?} is not a number of frames N or a range A..B");
        let Some((a, b)) = s.split_once("..") else {
            return s.parse().map(FramesArg::Count).map_err(|_| bad());
        };
        let (a, b): (u32, u32) = (a.parse().map_err(|_| bad())?, b.parse().map_err(|_| bad())?);
        if a >= b {
            return Err(format!(
                "{s:?} has no frames: A..B renders frames A to B−1, so A < B is needed"
            ));
        }
        Ok(FramesArg::Range(a, b))
    }
}

impl SequenceArgs {
    /// The cameras of all the sequence's frames, `camera` being the scene's; `None` for a single
    /// image.
    pub fn cameras(&self, camera: CameraSpec) -> Result<Option<Vec<Camera>>, String> {
        let range = matches!(self.frames, Some(FramesArg::Range(..)));
        let picks = range || self.frame.is_some();
        if let Some(frames) = self.turntable {
            if let Some(FramesArg::Count(_)) = self.frames {
                return Err("--frames with --turntable takes a range A..B of its frames".into());
            }
            return turntable(&camera, frames)
                .map(Some)
                .map_err(|e| format!("--turntable: {e}"));
        }
        let Some(file) = &self.path else {
            if picks {
                return Err("--frames A..B and --frame pick frames of a --turntable or                             --path sequence, and there is none"
                    .into());
            }
            if self.frames.is_some() {
                return Err("--frames N needs --path FILE".into());
            }
            return Ok(None);
        };
        let length = match (self.frames, self.path_length) {
            (Some(FramesArg::Count(n)), None) => n,
            (Some(FramesArg::Count(_)), Some(_)) => {
                return Err("give the --path's length once: --frames N or --path-length N".into());
            }
            (_, Some(n)) => n,
            (_, None) if picks => {
                return Err("picking frames of a --path needs its length: --path-length N".into());
            }
            (_, None) => return Err("--path FILE needs its number of frames: --frames N".into()),
        };
        let views = if SceneFormat::of(file) == SceneFormat::Gltf {
            let name = file
                .to_str()
                .ok_or("--path: the file's name is not UTF-8")?;
            load_any(name).map_err(|e| e.to_string())?.views
        } else {
            load_views(file, camera).map_err(|e| e.to_string())?
        };
        path(&views.cameras(), length)
            .map(Some)
            .map_err(|e| format!("--path {}: {e}", file.display()))
    }

    /// The frames to render of a sequence of `total` (before `--frame`, which `jobs` applies).
    pub fn range(&self, total: u32) -> Result<Range<u32>, String> {
        match self.frames {
            Some(FramesArg::Range(a, b)) if b > total => Err(format!(
                "--frames {a}..{b}: the sequence has frames 0 to {}",
                total.saturating_sub(1)
            )),
            Some(FramesArg::Range(a, b)) => {
                if self.frame.is_some() {
                    return Err("give --frames A..B or --frame K, not both".into());
                }
                Ok(a..b)
            }
            _ => Ok(0..total),
        }
    }

    /// `--frame`, if given.
    pub fn frame(&self) -> Option<FrameArg> {
        self.frame
    }
}

/// The file names of a sequence of `frames` images: `output` with its frame number pattern
/// (`%d`, or `%0Nd` for N digits with leading zeros, as in printf; `%%` is a `%`) replaced by
/// each frame's number in `numbers`. A single frame may go to a name without a pattern.
pub fn frame_paths(output: &Path, numbers: Range<u32>) -> Result<Vec<PathBuf>, String> {
    let frames = numbers.len();
    let text = output.to_str().ok_or_else(|| {
        format!(
            "-o {}: the name of a sequence's frames must be UTF-8",
            output.display()
        )
    })?;
    let Some((before, width, after)) =
        split_pattern(text).map_err(|e| format!("-o {text}: {e}"))?
    else {
        if frames == 1 {
            return Ok(vec![output.to_path_buf()]);
        }
        return Err(format!(
            "-o {text} names one file, but the sequence has {frames} images: put the frame \
             number in the name, such as -o frames/%04d.png"
        ));
    };
    Ok(numbers
        .map(|k| PathBuf::from(format!("{before}{k:0width$}{after}")))
        .collect())
}

/// The most digits `%0Nd` may ask for.
const MAX_DIGITS: usize = 10;

/// Splits `text` at its frame number pattern: the text before and after it (each `%%` made a
/// `%`) and the digits it asks for (0 for `%d`); `None` if it has none.
fn split_pattern(text: &str) -> Result<Option<(String, usize, String)>, String> {
    let bad = "a frame number pattern is %d or %0Nd (such as %04d), and %% is a percent sign";
    let mut before = String::new();
    let mut after = String::new();
    let mut width = None;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        let part = if width.is_some() {
            &mut after
        } else {
            &mut before
        };
        if c != '%' {
            part.push(c);
        } else if chars.next_if_eq(&'%').is_some() {
            part.push('%');
        } else {
            let mut digits = String::new();
            while let Some(d) = chars.next_if(char::is_ascii_digit) {
                digits.push(d);
            }
            if chars.next() != Some('d') || !(digits.is_empty() || digits.starts_with('0')) {
                return Err(bad.into());
            }
            if width.is_some() {
                return Err("more than one frame number pattern (%d or %0Nd)".into());
            }
            let digits: usize = digits.parse().unwrap_or(0);
            if digits > MAX_DIGITS {
                return Err(format!("at most {MAX_DIGITS} digits, got %0{digits}d"));
            }
            width = Some(digits);
        }
    }
    Ok(width.map(|width| (before, width, after)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paths(output: &str, frames: u32) -> Result<Vec<String>, String> {
        let paths = frame_paths(Path::new(output), 0..frames)?;
        Ok(paths.iter().map(|p| p.display().to_string()).collect())
    }

    #[test]
    fn frames_are_numbered_from_0_as_printf_writes_them() {
        assert_eq!(
            paths("frames/%04d.png", 3).unwrap(),
            ["frames/0000.png", "frames/0001.png", "frames/0002.png"]
        );
        assert_eq!(paths("f%d.png", 11).unwrap()[10], "f10.png");
        assert_eq!(paths("%02d%%.png", 101).unwrap()[100], "100%.png");
        assert_eq!(paths("one.png", 1).unwrap(), ["one.png"]);
        let some = frame_paths(Path::new("f%03d.png"), 7..9).unwrap();
        assert_eq!(some, [Path::new("f007.png"), Path::new("f008.png")]);
    }

    #[test]
    fn frame_ranges_are_checked() {
        assert_eq!("3..5".parse(), Ok(FramesArg::Range(3, 5)));
        assert_eq!("12".parse(), Ok(FramesArg::Count(12)));
        for (value, expected) in [
            ("5..5", "A < B is needed"),
            ("6..2", "A < B is needed"),
            ("1..", "is not a number of frames N or a range A..B"),
            ("x", "is not a number of frames N or a range A..B"),
        ] {
            let err = value.parse::<FramesArg>().unwrap_err();
            assert!(err.contains(expected), "{value}: {err}");
        }
    }

    #[test]
    fn bad_patterns_are_errors() {
        for (output, expected) in [
            (
                "out.png",
                "-o out.png names one file, but the sequence has 2 images",
            ),
            ("%s.png", "a frame number pattern is %d or %0Nd"),
            ("%4d.png", "a frame number pattern is %d or %0Nd"),
            ("%0", "a frame number pattern is %d or %0Nd"),
            ("%d-%d.png", "more than one frame number pattern"),
            ("%011d.png", "at most 10 digits"),
        ] {
            let error = paths(output, 2).unwrap_err();
            assert!(error.contains(expected), "{output}: {error}");
        }
    }
}
