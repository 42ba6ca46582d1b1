//! Grading a class: each student's image of each scene of an [`assignment::Assignment`]
//! measured against raylab's render of the scene ([`assignment::Measure`]), a pass or a fail
//! and its points, and the report a browser opens ([`report`]). Nothing a student hands in
//! stops the grading: a missing, unreadable, truncated, wrongly sized or oversized image, or a
//! symbolic link, is a grade of 0 that says why. Each reference is rendered once (per size, when
//! the assignment leaves the size to the students), before the images are measured on all
//! cores; a failed image is checked as `raylab check` does, against raylab's images traced with
//! mistakes that the class's checks share ([`Traces`]).

pub mod assignment;
pub mod report;
pub mod submissions;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use crate::compare::check::{CheckReport, check};
use crate::compare::difference::{Difference, difference};
use crate::compare::traces::Traces;
use crate::render::assemble;
use crate::srgb_image::SrgbImage;
use assignment::{Assignment, Measure};
use submissions::{Student, find_image};

/// FLIP, measured by the program that has its crate: the reference, then the image.
pub type FlipMeasure = dyn Fn(&SrgbImage, &SrgbImage) -> f64 + Sync;

/// What one student's image of one scene earned.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneGrade {
    /// The image graded, once found.
    pub image: Option<PathBuf>,
    /// The measure, once the image could be measured; else why it could not.
    pub measured: Result<Measured, String>,
    pub points: f64,
}

/// An image measured against its reference.
#[derive(Clone, Debug, PartialEq)]
pub struct Measured {
    pub measure: f64,
    pub passed: bool,
    /// The figures `raylab diff` prints, at the assignment's tolerance.
    pub difference: Difference,
    /// Where the image failed, what `raylab check` finds at the assignment's tolerance, or why
    /// it could not look.
    pub check: Option<Result<CheckReport, String>>,
}

/// One student's grades, a scene at a time in the assignment's order.
#[derive(Clone, Debug, PartialEq)]
pub struct StudentGrades {
    pub student: Student,
    pub scenes: Vec<SceneGrade>,
}

impl StudentGrades {
    pub fn total(&self) -> f64 {
        self.scenes.iter().map(|s| s.points).sum()
    }
}

/// A reference: scene `k` of the assignment at size `(w, h)`.
pub type ReferenceKey = (usize, (u32, u32));

/// The references raylab rendered, with the images it traces with mistakes to check a failed
/// image, or why it could not render them.
pub type References = BTreeMap<ReferenceKey, Result<Traces, String>>;

/// The memory the images traced with mistakes that every reference keeps for the class's
/// checks may take, all references together.
pub const KEPT_TRACES_BYTES: u64 = 256 << 20;

/// Where a student's image of a scene is and the size its reference is rendered at, or why it
/// has none.
type Located = Result<(PathBuf, (u32, u32)), String>;

/// Grades `students` on `assignment`; FLIP, when the assignment measures with it, by `flip`.
/// Returns the grades and the references they were measured against.
pub fn grade(
    assignment: &Assignment,
    students: &[Student],
    flip: &FlipMeasure,
) -> (Vec<StudentGrades>, References) {
    // Where each image is and the size its reference is rendered at, or why it has none.
    let found: Vec<Vec<Located>> = students
        .iter()
        .map(|student| {
            let scenes = assignment.scenes.iter();
            scenes.map(|scene| locate(student, scene)).collect()
        })
        .collect();
    let keys: BTreeSet<ReferenceKey> = found
        .iter()
        .flat_map(|row| row.iter().enumerate())
        .filter_map(|(k, located)| located.as_ref().ok().map(|(_, size)| (k, *size)))
        .collect();
    let share = KEPT_TRACES_BYTES / keys.len().max(1) as u64;
    let references: References = keys
        .into_iter()
        .map(|(k, size)| ((k, size), reference(assignment, k, size, share)))
        .collect();
    let mut grades: Vec<StudentGrades> = students
        .par_iter()
        .zip(found.into_par_iter())
        .map(|(student, row)| StudentGrades {
            student: student.clone(),
            scenes: row
                .into_iter()
                .enumerate()
                .map(|(k, located)| scene_grade(assignment, k, located, &references, flip))
                .collect(),
        })
        .collect();
    // The failed images are checked one at a time, each check on all cores, so that the memory
    // the checks hold is one check's.
    for student in &mut grades {
        for (k, scene) in student.scenes.iter_mut().enumerate() {
            if let (Some(path), Ok(measured)) = (&scene.image, &mut scene.measured)
                && !measured.passed
            {
                let size = (measured.difference.width, measured.difference.height);
                if let Some(Ok(traces)) = references.get(&(k, size)) {
                    measured.check = Some(checked(assignment, traces, path));
                }
            }
        }
    }
    (grades, references)
}

/// The image of scene `scene` in `student`'s folder and the size its reference is rendered at:
/// the assignment's (which the image must have), or the image's own.
fn locate(student: &Student, scene: &assignment::AssignedScene) -> Located {
    let path = find_image(student, &scene.image)?;
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let (size, _) =
        SrgbImage::probe(&path).map_err(|e| format!("{name} cannot be read: {}", after(&e)))?;
    let pixels = |(w, h): (u32, u32)| u64::from(w) * u64::from(h);
    let own = (scene.scene.settings.width, scene.scene.settings.height);
    match scene.size {
        Some(wanted) if wanted != size => Err(format!(
            "{name} is {}×{}; the assignment asks for {}×{}",
            size.0, size.1, wanted.0, wanted.1
        )),
        None if pixels(size) > LARGEST_SHARE * pixels(own) => Err(format!(
            "{name} is {}×{}: larger than raylab renders for grading (at most {LARGEST_SHARE} \
             times the scene's {}×{} pixels; the assignment can set `size`)",
            size.0, size.1, own.0, own.1
        )),
        _ => Ok((path, size)),
    }
}

/// Where the assignment leaves the size to the students, raylab renders its image at a
/// student's size up to this many times the scene file's own pixels.
pub const LARGEST_SHARE: u64 = 4;

/// An error message without the path it starts with (the report names the file itself).
fn after(message: &str) -> &str {
    message.split_once(": ").map_or(message, |(_, rest)| rest)
}

/// raylab's image of scene `k` at `size`, rendered as `raylab check` renders it, keeping as
/// many images traced with mistakes as `kept_bytes` holds.
fn reference(
    assignment: &Assignment,
    k: usize,
    size: (u32, u32),
    kept_bytes: u64,
) -> Result<Traces, String> {
    let mut scene = assignment.scenes[k].scene.clone();
    (scene.settings.width, scene.settings.height) = size;
    scene.settings.validate()?;
    let pixels = u64::from(size.0) * u64::from(size.1);
    let film_bytes = crate::film::Film::memory_bytes(size.0, size.1);
    let most_kept = kept_bytes / film_bytes.max(1);
    crate::memory::check(
        &format!(
            "raylab's {}×{} image of {}",
            size.0, size.1, assignment.scenes[k]
        ),
        pixels * 3 + crate::compare::check::memory_bytes(&scene.settings) + most_kept * film_bytes,
    )?;
    Ok(Traces::new(assemble(scene)?, most_kept as usize))
}

/// The grade of one located image of scene `k`.
fn scene_grade(
    assignment: &Assignment,
    k: usize,
    located: Located,
    references: &References,
    flip: &FlipMeasure,
) -> SceneGrade {
    let (path, size) = match located {
        Ok(found) => found,
        Err(problem) => {
            return SceneGrade {
                image: None,
                measured: Err(problem),
                points: 0.0,
            };
        }
    };
    let measured = match &references[&(k, size)] {
        Ok(traces) => measure(assignment, traces, &path, flip),
        Err(problem) => Err(format!("raylab's image cannot be made: {problem}")),
    };
    let points = match &measured {
        Ok(m) if m.passed => assignment.scenes[k].points,
        _ => 0.0,
    };
    SceneGrade {
        image: Some(path),
        measured,
        points,
    }
}

/// The image at `path` measured against `traces`' reference, of its size.
fn measure(
    assignment: &Assignment,
    traces: &Traces,
    path: &Path,
    flip: &FlipMeasure,
) -> Result<Measured, String> {
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let image =
        SrgbImage::read(path).map_err(|e| format!("{name} cannot be read: {}", after(&e)))?;
    let reference = &traces.reference;
    let figures = difference(reference, &image, assignment.tolerance)?;
    let value = match assignment.measure {
        Measure::Mean => figures.mean_absolute,
        Measure::Neighbour => neighbour_mean(reference, &image),
        Measure::Flip => flip(reference, &image),
    };
    Ok(Measured {
        measure: value,
        passed: value <= assignment.pass,
        difference: figures,
        check: None,
    })
}

/// What `raylab check` finds in the image at `path` against `traces`, at the assignment's
/// tolerance.
fn checked(assignment: &Assignment, traces: &Traces, path: &Path) -> Result<CheckReport, String> {
    let image = SrgbImage::read(path)?;
    check(traces, &image, assignment.tolerance, &mut |_| {})
}

/// The mean absolute difference, in levels, with each pixel of `image` measured against the
/// pixel of `reference`'s 3×3 window around it that it is closest to (its channels' mean).
pub fn neighbour_mean(reference: &SrgbImage, image: &SrgbImage) -> f64 {
    let (width, height) = (image.width, image.height);
    let closest = |x: u32, y: u32| {
        let pixel = image.at(x, y);
        let mut best = u32::MAX;
        for ny in y.saturating_sub(1)..=(y + 1).min(height - 1) {
            for nx in x.saturating_sub(1)..=(x + 1).min(width - 1) {
                let other = reference.at(nx, ny);
                let apart: u32 = (0..3).map(|c| u32::from(pixel[c].abs_diff(other[c]))).sum();
                best = best.min(apart);
            }
        }
        u64::from(best)
    };
    let sum: u64 = (0..height)
        .into_par_iter()
        .map(|y| (0..width).map(|x| closest(x, y)).sum::<u64>())
        .sum();
    sum as f64 / (3.0 * f64::from(width) * f64::from(height))
}
