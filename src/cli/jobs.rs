//! `raylab render`'s jobs for a scheduler: `--tile K/N` and `--crop X0,Y0,X1,Y1` (a rectangle
//! of the image, written as a part for `raylab merge`), and `auto` for `--tile` and `--frame`,
//! which takes the task's index from the scheduler's environment: Slurm's
//! `SLURM_ARRAY_TASK_ID`, Kubernetes' `JOB_COMPLETION_INDEX` (Indexed Jobs) or GNU parallel's
//! `PARALLEL_SEQ` (which counts from 1; task 0 is its 1). The tiles of `--tile auto` number
//! `--of N`, or Slurm's `SLURM_ARRAY_TASK_COUNT`. With both `--frame auto` and `--tile auto`,
//! task `i` renders tile `i mod N` of frame `i div N`: every tile of the first frame, then of the
//! next.

use std::ops::Range;
use std::str::FromStr;

use clap::Args;
use raylab::tiles::{self, Rect, SplitError};

/// The flags that pick a rectangle of the image.
#[derive(Args, Debug)]
pub struct TileArgs {
    /// Render tile K of N (K from 0 to N−1) as a part for `raylab merge`: the image cut into
    /// a grid of N near-square rectangles (rows × columns = N; a prime N gives bands), numbered
    /// row by row. `auto` takes K from the scheduler (SLURM_ARRAY_TASK_ID,
    /// JOB_COMPLETION_INDEX or PARALLEL_SEQ) and N from --of or SLURM_ARRAY_TASK_COUNT. The
    /// output must be .exr.
    #[arg(long, value_name = "K/N|auto", conflicts_with = "crop")]
    tile: Option<TileArg>,
    /// Render only the pixels X0 ≤ x < X1, Y0 ≤ y < Y1 (half-open, as pbrt's --pixelbounds;
    /// 0,0 is the top-left pixel) as a part for `raylab merge`. The output must be .exr.
    #[arg(long, value_name = "X0,Y0,X1,Y1")]
    crop: Option<Crop>,
    /// How many tiles `--tile auto` cuts the image into (default: SLURM_ARRAY_TASK_COUNT).
    #[arg(long, value_name = "N")]
    of: Option<u32>,
}

/// `--tile`'s value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TileArg {
    Tile { k: u32, n: u32 },
    Auto,
}

impl FromStr for TileArg {
    type Err = String;
    fn from_str(s: &str) -> Result<TileArg, String> {
        if s == "auto" {
            return Ok(TileArg::Auto);
        }
        let bad = || format!("{s:?} is not K/N (tile K of N, such as 3/16) or auto");
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let (k, n): (u32, u32) = (k.parse().map_err(|_| bad())?, n.parse().map_err(|_| bad())?);
        if n == 0 {
            return Err(SplitError::NoTiles.to_string());
        }
        if k >= n {
            return Err(SplitError::TileOutOfRange { k, n }.to_string());
        }
        Ok(TileArg::Tile { k, n })
    }
}

/// `--crop`'s value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop(Rect);

impl FromStr for Crop {
    type Err = String;
    fn from_str(s: &str) -> Result<Crop, String> {
        let bad = || format!("{s:?} is not X0,Y0,X1,Y1 (four whole numbers of pixels)");
        let numbers: Vec<u32> = s
            .split(',')
            .map(|v| v.trim().parse().map_err(|_| bad()))
            .collect::<Result<_, _>>()?;
        let [x0, y0, x1, y1] = numbers[..] else {
            return Err(bad());
        };
        if x0 >= x1 || y0 >= y1 {
            return Err(format!("{s:?} is empty: X0 < X1 and Y0 < Y1 are needed"));
        }
        Ok(Crop(Rect { x0, y0, x1, y1 }))
    }
}

/// `--frame`'s value: a frame number or `auto`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameArg {
    Frame(u32),
    Auto,
}

impl FromStr for FrameArg {
    type Err = String;
    fn from_str(s: &str) -> Result<FrameArg, String> {
        match s {
            "auto" => Ok(FrameArg::Auto),
            _ => s
                .parse()
                .map(FrameArg::Frame)
                .map_err(|_| format!("{s:?} is not a frame number or auto")),
        }
    }
}

/// The part of the work one run does: some frames, and of each, the whole image or one
/// rectangle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Job {
    pub frames: Range<u32>,
    /// The rectangle, and the tile (K, N) when it is one.
    pub window: Option<(Rect, Option<(u32, u32)>)>,
}

/// Picks the job of this run: of `frames` (the sequence's frames to render, `0..1` for one
/// image), `frame` alone if given, and the tile or crop of `args`, for a `width × height`
/// image, reading the scheduler's variables through `env` for `auto`.
pub fn pick(
    args: &TileArgs,
    frame: Option<FrameArg>,
    frames: Range<u32>,
    (width, height): (u32, u32),
    env: impl Fn(&str) -> Option<String>,
) -> Result<Job, String> {
    if args.of.is_some() && args.tile != Some(TileArg::Auto) {
        return Err("--of N gives the number of tiles of --tile auto".into());
    }
    let task = || task_index(&env);
    // The tile count of `--tile auto`.
    let tile_count = || -> Result<u32, String> {
        let n = match args.of {
            Some(n) => n,
            None if frame == Some(FrameArg::Auto) => {
                return Err("--frame auto with --tile auto needs the number of tiles \
                            per frame: --of N"
                    .into());
            }
            None => count_from(&env)?.ok_or(
                "--tile auto needs the number of tiles: --of N (only Slurm sets it, \
                 as SLURM_ARRAY_TASK_COUNT)",
            )?,
        };
        if n == 0 {
            return Err("--of: the number of tiles must be at least 1".into());
        }
        Ok(n)
    };
    let (frame, tile) = match (frame, args.tile) {
        (Some(FrameArg::Auto), Some(TileArg::Auto)) => {
            let n = tile_count()?;
            let (i, from) = task()?;
            let jobs = u64::from(frames.end - frames.start) * u64::from(n);
            if u64::from(i) >= jobs {
                return Err(out_of_range(i, from, jobs, "frames × tiles"));
            }
            (Some(frames.start + i / n), Some((i % n, n)))
        }
        (Some(FrameArg::Auto), tile) => {
            let (i, from) = task()?;
            let jobs = u64::from(frames.end - frames.start);
            if u64::from(i) >= jobs {
                return Err(out_of_range(i, from, jobs, "frames"));
            }
            let tile = tile.map(|t| match t {
                TileArg::Tile { k, n } => (k, n),
                TileArg::Auto => unreachable!("matched above"),
            });
            (Some(frames.start + i), tile)
        }
        (frame, Some(TileArg::Auto)) => {
            let n = tile_count()?;
            let (i, from) = task()?;
            if i >= n {
                return Err(out_of_range(i, from, n.into(), "tiles"));
            }
            (frame.map(number), Some((i, n)))
        }
        (frame, Some(TileArg::Tile { k, n })) => (frame.map(number), Some((k, n))),
        (frame, None) => (frame.map(number), None),
    };
    let frames = match frame {
        Some(k) if !frames.contains(&k) => {
            return Err(format!(
                "--frame {k}: the sequence's frames are {} to {}",
                frames.start,
                frames.end - 1
            ));
        }
        Some(k) => k..k + 1,
        None => frames,
    };
    let image = Rect::image(width, height);
    let window = match (tile, args.crop) {
        (Some((k, n)), _) => Some((
            tiles::tile(width, height, k, n).map_err(|e| format!("--tile: {e}"))?,
            Some((k, n)),
        )),
        (None, Some(Crop(rect))) if !rect.is_inside(&image) => {
            return Err(format!(
                "--crop {rect} reaches outside the {width}×{height} image (pixels 0,0 to {},{})",
                width - 1,
                height - 1
            ));
        }
        (None, Some(Crop(rect))) => Some((rect, None)),
        (None, None) => None,
    };
    Ok(Job { frames, window })
}

/// The frame number of a `--frame` that is not `auto`.
fn number(frame: FrameArg) -> u32 {
    match frame {
        FrameArg::Frame(k) => k,
        FrameArg::Auto => unreachable!("auto is resolved first"),
    }
}

fn out_of_range(i: u32, from: &str, jobs: u64, what: &str) -> String {
    format!(
        "the task index {i} (from {from}) is out of range: there are {jobs} {what}, tasks 0 to {}",
        jobs.saturating_sub(1)
    )
}

/// The task's index, counted from 0, and the variable it came from.
fn task_index(env: &impl Fn(&str) -> Option<String>) -> Result<(u32, &'static str), String> {
    let read = |name: &'static str| -> Result<Option<u32>, String> {
        env(name)
            .map(|v| {
                v.trim()
                    .parse()
                    .map_err(|_| format!("{name}={v:?} is not a task index"))
            })
            .transpose()
    };
    for name in ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"] {
        if let Some(i) = read(name)? {
            return Ok((i, name));
        }
    }
    match read("PARALLEL_SEQ")? {
        Some(0) => Err("PARALLEL_SEQ=0: GNU parallel counts its jobs from 1".into()),
        Some(seq) => Ok((seq - 1, "PARALLEL_SEQ")),
        None => Err(
            "auto takes the task index from SLURM_ARRAY_TASK_ID (Slurm job arrays), \
             JOB_COMPLETION_INDEX (Kubernetes Indexed Jobs) or PARALLEL_SEQ (GNU parallel), \
             and none is set"
                .into(),
        ),
    }
}

/// The number of tasks Slurm says the array has, if it does.
fn count_from(env: &impl Fn(&str) -> Option<String>) -> Result<Option<u32>, String> {
    let name = "SLURM_ARRAY_TASK_COUNT";
    env(name)
        .map(|v| {
            v.trim()
                .parse()
                .map_err(|_| format!("{name}={v:?} is not a number"))
        })
        .transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(tile: Option<&str>, crop: Option<&str>, of: Option<u32>) -> TileArgs {
        TileArgs {
            tile: tile.map(|t| t.parse().unwrap()),
            crop: crop.map(|c| c.parse().unwrap()),
            of,
        }
    }

    fn env(vars: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let vars: Vec<(String, String)> = vars
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |name| vars.iter().find(|(k, _)| k == name).map(|(_, v)| v.clone())
    }

    #[test]
    fn bad_values_are_clear_errors() {
        for (value, expected) in [
            ("3/3", "tile 3 of 3 does not exist"),
            ("0/0", "the number of tiles must be at least 1"),
            ("3", "is not K/N"),
            ("a/4", "is not K/N"),
            ("-1/4", "is not K/N"),
        ] {
            let err = value.parse::<TileArg>().unwrap_err();
            assert!(err.contains(expected), "{value}: {err}");
        }
        for (value, expected) in [
            ("1,2,3", "is not X0,Y0,X1,Y1"),
            ("4,0,4,5", "is empty"),
            ("1,2,x,4", "is not X0,Y0,X1,Y1"),
        ] {
            let err = value.parse::<Crop>().unwrap_err();
            assert!(err.contains(expected), "{value}: {err}");
        }
        let err = pick(
            &args(None, Some("0,0,40,5"), None),
            None,
            0..1,
            (37, 23),
            env(&[]),
        )
        .unwrap_err();
        assert!(err.contains("reaches outside the 37×23 image"), "{err}");
        let err = pick(
            &args(Some("0/999"), None, None),
            None,
            0..1,
            (37, 23),
            env(&[]),
        )
        .unwrap_err();
        assert!(err.contains("without an empty one"), "{err}");
    }

    #[test]
    fn auto_reads_each_scheduler_s_index() {
        let auto = args(Some("auto"), None, Some(4));
        let tile_of = |vars: &[(&str, &str)]| {
            pick(&auto, None, 0..1, (40, 40), env(vars)).map(|job| job.window.unwrap().1)
        };
        assert_eq!(tile_of(&[("SLURM_ARRAY_TASK_ID", "2")]), Ok(Some((2, 4))));
        assert_eq!(tile_of(&[("JOB_COMPLETION_INDEX", "0")]), Ok(Some((0, 4))));
        assert_eq!(
            tile_of(&[("PARALLEL_SEQ", "4")]),
            Ok(Some((3, 4))),
            "GNU parallel counts from 1"
        );
        let err = tile_of(&[("PARALLEL_SEQ", "5")]).unwrap_err();
        assert!(
            err.contains("task index 4 (from PARALLEL_SEQ) is out of range"),
            "{err}"
        );
        let err = tile_of(&[]).unwrap_err();
        assert!(err.contains("none is set"), "{err}");
        // Slurm gives the count too; the others need --of.
        let slurm = env(&[
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]);
        let job = pick(&args(Some("auto"), None, None), None, 0..1, (40, 40), slurm).unwrap();
        assert_eq!(job.window.unwrap().1, Some((1, 3)));
        let k8s = env(&[("JOB_COMPLETION_INDEX", "1")]);
        let err = pick(&args(Some("auto"), None, None), None, 0..1, (40, 40), k8s).unwrap_err();
        assert!(err.contains("--of N"), "{err}");
    }

    #[test]
    fn frames_and_tiles_combine() {
        let both = args(Some("auto"), None, Some(4));
        let job = pick(
            &both,
            Some(FrameArg::Auto),
            10..13,
            (40, 40),
            env(&[("SLURM_ARRAY_TASK_ID", "9")]),
        )
        .unwrap();
        assert_eq!(job.frames, 12..13, "task 9 of 3 frames × 4 tiles");
        assert_eq!(job.window.unwrap().1, Some((1, 4)));
        let err = pick(
            &both,
            Some(FrameArg::Auto),
            10..13,
            (40, 40),
            env(&[("SLURM_ARRAY_TASK_ID", "12")]),
        )
        .unwrap_err();
        assert!(err.contains("there are 12 frames × tiles"), "{err}");
        let job = pick(
            &args(Some("1/2"), None, None),
            Some(FrameArg::Frame(5)),
            0..8,
            (40, 40),
            env(&[]),
        )
        .unwrap();
        assert_eq!(job.frames, 5..6);
        let err = pick(
            &args(None, None, None),
            Some(FrameArg::Frame(8)),
            0..8,
            (4, 4),
            env(&[]),
        )
        .unwrap_err();
        assert!(err.contains("frames are 0 to 7"), "{err}");
    }
}
