//! The assignment file `raylab grade` reads: the scenes a class renders, the image each student
//! hands in for each (its name, size and points), the tolerance and the pass mark, and how an
//! image is measured against raylab's ([`Measure`]). Every error is at `file:line:column`.

use std::fmt;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use crate::formats::{SceneError, Source, load_any, utf8_text};
use crate::limits::check_image_size;
use crate::scene::Scene;
use crate::settings::SettingsOverrides;

/// How an image is measured against raylab's, in `[grading] measure`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, strum::Display)]
#[serde(rename_all = "lowercase")]
#[strum(serialize_all = "lowercase")]
pub enum Measure {
    /// The mean absolute difference over every channel of every pixel, in 8-bit levels.
    #[default]
    Mean,
    /// The same mean with each pixel forgiven by its best neighbour in the reference's 3×3
    /// window around it: for tracers whose pixel centres lie half a pixel from raylab's.
    Neighbour,
    /// FLIP, NVIDIA's perceptual difference, from 0 (the same) to 1.
    Flip,
}

/// An assignment, read and checked, its scenes loaded.
#[derive(Debug)]
pub struct Assignment {
    pub name: String,
    /// A pixel differs when one of its channels is more than this many levels off.
    pub tolerance: u8,
    /// A scene passes when its measure is at most this.
    pub pass: f64,
    pub measure: Measure,
    pub scenes: Vec<AssignedScene>,
}

/// One scene of an assignment.
#[derive(Debug)]
pub struct AssignedScene {
    /// The scene file, as the assignment names it, and the scene, its overrides applied.
    pub file: String,
    pub scene: Scene,
    /// The name of the image each student hands in, without its extension.
    pub image: String,
    /// The size the image must have; `None`: any, the reference rendered at the image's.
    pub size: Option<(u32, u32)>,
    /// What a pass earns.
    pub points: f64,
}

/// The extensions a student's image may have, in the order they are looked for.
pub const IMAGE_EXTENSIONS: [&str; 7] = ["png", "ppm", "bmp", "jpg", "jpeg", "exr", "hdr"];

/// A pass mark when the assignment gives none: a mean difference of 2 levels.
pub const DEFAULT_PASS: f64 = 2.0;
/// A tolerance when the assignment gives none (wider than `raylab diff`'s: students' tracers
/// round differently).
pub const GRADING_TOLERANCE: u8 = 8;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AssignmentFile {
    assignment: HeaderFile,
    #[serde(default)]
    grading: GradingFile,
    scene: Spanned<Vec<SceneFile>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct HeaderFile {
    name: String,
    tolerance: Option<u8>,
    pass: Option<Spanned<f64>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct GradingFile {
    measure: Option<Measure>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    file: Spanned<String>,
    image: Spanned<String>,
    size: Option<Spanned<[u32; 2]>>,
    points: Option<Spanned<f64>>,
    samples: Option<u32>,
    max_depth: Option<u32>,
    min_weight: Option<f32>,
    aa_threshold: Option<f32>,
    fog_steps: Option<u32>,
    caustic_photons: Option<u32>,
    caustic_gather: Option<u32>,
}

/// Reads the assignment at `path` ([`parse_assignment`]).
pub fn read_assignment(path: &Path) -> Result<Assignment, SceneError> {
    let bytes = std::fs::read(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read it: {e}")))?;
    parse_assignment(&bytes, path)
}

/// Reads the assignment `bytes`, the file at `path`, and loads its scene files, relative to
/// its folder. A scene file's own error is that file's; every other is at its place in the
/// assignment.
pub fn parse_assignment(bytes: &[u8], path: &Path) -> Result<Assignment, SceneError> {
    let text = utf8_text(bytes, path)?;
    let source = Source { origin: path, text };
    let file: AssignmentFile = toml::from_str(text).map_err(|e| source.toml_error(&e))?;
    let pass = match file.assignment.pass {
        Some(pass) if !(pass.get_ref().is_finite() && *pass.get_ref() >= 0.0) => {
            return Err(source.error(pass.span(), "the pass mark must be a number of 0 or more"));
        }
        Some(pass) => pass.into_inner(),
        None => DEFAULT_PASS,
    };
    if file.scene.get_ref().is_empty() {
        return Err(source.error(file.scene.span(), "an assignment needs a [[scene]]"));
    }
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut scenes: Vec<AssignedScene> = Vec::new();
    for entry in file.scene.into_inner() {
        let scene = assigned_scene(entry, folder, source)?;
        scenes.push(scene);
    }
    Ok(Assignment {
        name: file.assignment.name,
        tolerance: file.assignment.tolerance.unwrap_or(GRADING_TOLERANCE),
        pass,
        measure: file.grading.measure.unwrap_or_default(),
        scenes,
    })
}

/// One `[[scene]]`, checked, its file (relative to `folder`) loaded.
fn assigned_scene(
    entry: SceneFile,
    folder: &Path,
    source: Source,
) -> Result<AssignedScene, SceneError> {
    let image = entry.image.get_ref();
    if image.is_empty() || image.contains(['/', '\\', '.']) {
        return Err(source.error(
            entry.image.span(),
            "`image` is a file name without a folder or an extension (`spheres` for \
             spheres.png, .ppm, …)",
        ));
    }
    let size = match &entry.size {
        Some(size) => {
            let [width, height] = *size.get_ref();
            check_image_size(width, height).map_err(|e| source.error(size.span(), e))?;
            Some((width, height))
        }
        None => None,
    };
    let points = match &entry.points {
        Some(points) if !(points.get_ref().is_finite() && *points.get_ref() >= 0.0) => {
            return Err(source.error(points.span(), "points must be a number of 0 or more"));
        }
        Some(points) => *points.get_ref(),
        None => 1.0,
    };
    let scene_path: PathBuf = folder.join(entry.file.get_ref());
    if !scene_path.is_file() {
        return Err(source.error(
            entry.file.span(),
            format!("no scene file {}", scene_path.display()),
        ));
    }
    let mut scene = load_any(&scene_path.to_string_lossy())?;
    let overrides = SettingsOverrides {
        samples: entry.samples,
        max_depth: entry.max_depth,
        min_weight: entry.min_weight,
        aa_threshold: entry.aa_threshold,
        fog_steps: entry.fog_steps,
        caustic_photons: entry.caustic_photons,
        caustic_gather: entry.caustic_gather,
        ..SettingsOverrides::default()
    };
    overrides
        .apply(&mut scene.settings)
        .map_err(|e| source.error(entry.file.span(), e))?;
    Ok(AssignedScene {
        file: entry.file.into_inner(),
        scene,
        image: entry.image.into_inner(),
        size,
        points,
    })
}

impl fmt::Display for AssignedScene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({})", self.image, self.file)
    }
}
