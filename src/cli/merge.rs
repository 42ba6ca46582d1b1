//! `raylab merge`: the parts that `raylab render --tile` or `--crop` wrote (OpenEXR files with
//! the linear values, see [`raylab::formats::part`]) into the image one render of the whole
//! would have written, bit for bit, after checking that they come from the same scene, camera
//! and settings and cover the image exactly once; and `--status`, which lists the parts there
//! are and the tiles missing.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use raylab::color::Color;
use raylab::formats::image::{check_image_path, save_toned_image};
use raylab::formats::part::{PartInfo, read_part, read_part_info};
use raylab::memory;
use raylab::tiles::{CoverError, Rect, check_cover, split};

use super::render::ToneArgs;

#[derive(Args, Debug)]
pub struct MergeArgs {
    /// The parts (.exr files from `raylab render --tile` or `--crop`), or folders of them.
    #[arg(required = true, value_name = "PARTS")]
    parts: Vec<PathBuf>,
    /// The merged image: .png or .ppm (8-bit sRGB), .exr or .hdr (linear floats), written
    /// only when the parts check out, and atomically.
    #[arg(short, long, required_unless_present = "status")]
    output: Option<PathBuf>,
    /// List the parts there are (tile, pixels, frame) and the tiles missing, and write nothing.
    #[arg(long, conflicts_with = "output")]
    status: bool,
    #[command(flatten)]
    tone: ToneArgs,
}

pub fn run(args: MergeArgs) -> Result<(), String> {
    let files = part_files(&args.parts)?;
    let Some(output) = &args.output else {
        return status(&files);
    };
    let format = check_image_path(output).map_err(|e| e.to_string())?;
    let tone = args.tone.tone(format, output)?;
    let infos: Vec<PartInfo> = files
        .iter()
        .map(|file| read_part_info(file).map_err(|e| e.to_string()))
        .collect::<Result<_, _>>()?;
    check_parts(&files, &infos)?;
    let (width, height) = (infos[0].width, infos[0].height);
    let pixels = u64::from(width) * u64::from(height);
    memory::check(
        &format!("merging a {width}×{height} image"),
        pixels * std::mem::size_of::<Color>() as u64 + format.save_bytes(width),
    )?;
    let mut image = vec![Color::ZERO; pixels as usize];
    for (file, info) in files.iter().zip(&infos) {
        let part = read_part(file).map_err(|e| e.to_string())?;
        if part.info != *info {
            return Err(format!("{}: changed while merging", file.display()));
        }
        let rect = info.rect;
        for (y, row) in (rect.y0..rect.y1).zip(part.pixels.chunks(rect.width() as usize)) {
            let start = y as usize * width as usize + rect.x0 as usize;
            image[start..start + row.len()].copy_from_slice(row);
        }
    }
    save_toned_image(output, width, height, &image, tone).map_err(|e| e.to_string())?;
    super::print_out(|out| {
        writeln!(
            out,
            "{} parts → {width}×{height} → {}",
            files.len(),
            output.display()
        )
    })
}

/// The files `paths` name: each file, and the .exr files in each folder, by name.
fn part_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    for path in paths {
        if path.is_dir() {
            let entries =
                std::fs::read_dir(path).map_err(|e| format!("{}: {e}", path.display()))?;
            let mut exr: Vec<PathBuf> = entries
                .filter_map(|entry| Some(entry.ok()?.path()))
                .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")))
                .collect();
            exr.sort();
            files.extend(exr);
        } else {
            files.push(path.clone());
        }
    }
    if files.is_empty() {
        return Err("no parts: the folders hold no .exr files".into());
    }
    Ok(files)
}

/// How a part names itself in messages: its file, and its tile or rectangle.
fn describe(file: &Path, info: &PartInfo) -> String {
    match info.tile {
        Some((k, n)) => format!("{} (tile {k}/{n})", file.display()),
        None => format!("{} (pixels {})", file.display(), info.rect),
    }
}

/// Checks that the parts come from one render (image size, scene, settings, frame) and cover
/// its image exactly once.
fn check_parts(files: &[PathBuf], infos: &[PartInfo]) -> Result<(), String> {
    let parts: Vec<(&Path, &PartInfo)> = files.iter().map(PathBuf::as_path).zip(infos).collect();
    if let Some(why) = not_of_one_render(&parts) {
        return Err(why);
    }
    let image = Rect::image(infos[0].width, infos[0].height);
    let rects: Vec<Rect> = infos.iter().map(|info| info.rect).collect();
    match check_cover(&image, &rects) {
        Ok(()) => Ok(()),
        Err(CoverError::Overlap { first, second }) => Err(format!(
            "{} and {} overlap: each pixel must come from one part",
            describe(&files[first], &infos[first]),
            describe(&files[second], &infos[second])
        )),
        Err(CoverError::Outside { index }) => Err(format!(
            "{} lies outside the image",
            describe(&files[index], &infos[index])
        )),
        Err(CoverError::Gap { x, y }) => match missing_tiles(infos) {
            Some(missing) => Err(format!("missing {missing}")),
            None => Err(format!("no part covers pixel ({x}, {y})")),
        },
    }
}

/// Why the parts (file and what it says) are not all parts of one render (image size,
/// settings, frame, scene), naming the first that is not of the first's; `None` when they are.
fn not_of_one_render(parts: &[(&Path, &PartInfo)]) -> Option<String> {
    let (first, reference) = parts[0];
    parts.iter().skip(1).find_map(|&(file, info)| {
        let (a, b) = (first.display(), file.display());
        if (info.width, info.height) != (reference.width, reference.height) {
            Some(format!(
                "{a} is a part of a {}×{} image, {b} of a {}×{}",
                reference.width, reference.height, info.width, info.height
            ))
        } else if info.settings != reference.settings {
            Some(format!(
                "{a} and {b} were rendered with different settings{}",
                setting_that_differs(&reference.settings, &info.settings)
            ))
        } else if info.frame != reference.frame {
            Some(format!("{a} and {b} are parts of different frames"))
        } else if info.scene != reference.scene {
            Some(format!(
                "{a} and {b} come from different scenes or cameras (scene hash {} and {})",
                reference.scene, info.scene
            ))
        } else {
            None
        }
    })
}

/// The first setting that differs between the settings texts `a` and `b` (as parts hold them:
/// `name: value` a line, a value over several lines after its name), as `: NAME (A and B)`.
fn setting_that_differs(a: &str, b: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    let Some(i) = (0..a.len().min(b.len())).find(|&i| a[i] != b[i]) else {
        return String::new();
    };
    let name = a[..=i]
        .iter()
        .rev()
        .find_map(|line| line.split_once(": ").or_else(|| line.split_once(" = ")))
        .map_or("", |(name, _)| name.trim());
    let value = |line: &str| {
        let line = line.trim().trim_end_matches(',');
        line.strip_prefix(&format!("{name}: "))
            .or_else(|| line.strip_prefix(&format!("{name} = ")))
            .unwrap_or(line)
            .to_string()
    };
    format!(": {name} ({} and {})", value(a[i]), value(b[i]))
}

/// When every part is a tile of the same N: the tiles of N not among them, as `tile K/N (pixels
/// X0,Y0,X1,Y1)`, joined.
fn missing_tiles(infos: &[PartInfo]) -> Option<String> {
    let (_, n) = infos[0].tile?;
    if infos
        .iter()
        .any(|info| info.tile.map(|(_, m)| m) != Some(n))
    {
        return None;
    }
    let tiles = split(infos[0].width, infos[0].height, n).ok()?;
    let missing: Vec<String> = tiles
        .iter()
        .enumerate()
        .filter(|(_, rect)| infos.iter().all(|info| info.rect != **rect))
        .map(|(k, rect)| format!("tile {k}/{n} (pixels {rect})"))
        .collect();
    Some(missing.join(", "))
}

/// `--status`: each part's file, tile or rectangle and frame; then, for each frame, the tiles
/// missing, or how many pixels the parts cover; or, when a frame's parts are not of one render,
/// which do not belong together (an error).
fn status(files: &[PathBuf]) -> Result<(), String> {
    let mut frames: BTreeMap<Option<u32>, Vec<(&Path, PartInfo)>> = BTreeMap::new();
    let mut apart = Vec::new();
    super::print_out(|out| {
        for file in files {
            match read_part_info(file) {
                Ok(info) => {
                    let frame = info.frame.map_or(String::new(), |f| format!(", frame {f}"));
                    writeln!(out, "{}{frame}", describe(file, &info))?;
                    frames.entry(info.frame).or_default().push((file, info));
                }
                Err(e) => writeln!(out, "{e}")?,
            }
        }
        for (frame, parts) in &frames {
            let frame = frame.map_or(String::new(), |f| format!("frame {f}: "));
            let named: Vec<(&Path, &PartInfo)> = parts.iter().map(|(f, i)| (*f, i)).collect();
            if let Some(why) = not_of_one_render(&named) {
                writeln!(out, "{frame}these parts do not belong together: {why}")?;
                apart.push(why);
                continue;
            }
            let infos: Vec<PartInfo> = parts.iter().map(|(_, info)| info.clone()).collect();
            let infos = &infos;
            let covered: u64 = infos.iter().map(|info| info.rect.pixels()).sum();
            let all = u64::from(infos[0].width) * u64::from(infos[0].height);
            match missing_tiles(infos) {
                Some(missing) if missing.is_empty() => {
                    writeln!(out, "{frame}no tile missing ({} parts)", infos.len())?
                }
                Some(missing) => writeln!(out, "{frame}missing {missing}")?,
                None => writeln!(out, "{frame}{covered} of {all} pixels in parts")?,
            }
        }
        Ok(())
    })?;
    match apart.first() {
        Some(why) => Err(format!("the parts are not of one render: {why}")),
        None => Ok(()),
    }
}
