//! `raylab render`'s image sequences: `--turntable FRAMES` and `--path FILE --frames N`, the
//! cameras of their frames (the library's [`raylab::views`]) and the numbered file names that
//! `-o frames/%04d.png` gives them. Frames are numbered from 0; frame 0 is the scene's camera
//! (the turntable) or the first view (the path).

use std::path::{Path, PathBuf};

use clap::Args;
use raylab::camera::{Camera, CameraSpec};
use raylab::formats::toml::load_views;
use raylab::views::{path, turntable};

/// The flags of an image sequence.
#[derive(Args, Debug)]
pub struct SequenceArgs {
    /// Render a turntable of FRAMES images: the eye orbits the look-at point once about the
    /// camera's up axis, frame 0 being the scene's camera. -o names the frames with a number
    /// pattern, such as frames/%04d.png (frames 0000.png, 0001.png, …).
    #[arg(long, value_name = "FRAMES", conflicts_with = "path")]
    turntable: Option<u32>,
    /// Render a camera path through the views of a views file (NAME.views.toml, as the viewer
    /// saves them with Ctrl+1…9) in the order of their numbers, in --frames images: the first
    /// is the first view, the last the last view. -o as with --turntable.
    #[arg(long, value_name = "FILE", requires = "frames")]
    path: Option<PathBuf>,
    /// How many images the --path sequence has (at least 2).
    #[arg(long, value_name = "N", requires = "path")]
    frames: Option<u32>,
}

impl SequenceArgs {
    /// The cameras of the sequence's frames, `camera` being the scene's; `None` for a single
    /// image.
    pub fn cameras(&self, camera: CameraSpec) -> Result<Option<Vec<Camera>>, String> {
        if let Some(frames) = self.turntable {
            return turntable(&camera, frames)
                .map(Some)
                .map_err(|e| format!("--turntable: {e}"));
        }
        match (&self.path, self.frames) {
            (Some(file), Some(frames)) => {
                let views = load_views(file, camera).map_err(|e| e.to_string())?;
                path(&views.cameras(), frames)
                    .map(Some)
                    .map_err(|e| format!("--path {}: {e}", file.display()))
            }
            _ => Ok(None),
        }
    }
}

/// The file names of a sequence of `frames` images: `output` with its frame number pattern
/// (`%d`, or `%0Nd` for N digits with leading zeros, as in printf; `%%` is a `%`) replaced by
/// each frame's number from 0. A single frame may go to a name without a pattern.
pub fn frame_paths(output: &Path, frames: usize) -> Result<Vec<PathBuf>, String> {
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
    Ok((0..frames)
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

    fn paths(output: &str, frames: usize) -> Result<Vec<String>, String> {
        let paths = frame_paths(Path::new(output), frames)?;
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
