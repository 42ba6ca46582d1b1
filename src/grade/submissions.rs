//! A class's submissions: one folder per student, named by the student's id, holding an image
//! per scene. Nothing a student hands in is trusted: a symbolic link is never followed (it
//! could lead anywhere), names may hold any character, and each image is found by its name and
//! one of the extensions raylab reads, in any case, or its absence is said.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use super::assignment::IMAGE_EXTENSIONS;

/// A student's folder: the id (the folder's name, made text) and where it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Student {
    pub id: String,
    pub folder: PathBuf,
}

/// The students of the class in `folder`, sorted by id: every folder in it. A symbolic link
/// is a student whose folder is not read (their images are then missing, with the reason); any
/// other file is not a student, and is named in the notes returned beside them.
pub fn students(folder: &Path) -> Result<(Vec<Student>, Vec<String>), String> {
    let entries = fs::read_dir(folder)
        .map_err(|e| format!("{}: cannot read the submissions: {e}", folder.display()))?;
    let mut students = Vec::new();
    let mut notes = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", folder.display()))?;
        let id = entry.file_name().to_string_lossy().into_owned();
        let kind = entry
            .file_type()
            .map_err(|e| format!("{}: {e}", entry.path().display()))?;
        if kind.is_dir() || kind.is_symlink() {
            students.push(Student {
                id,
                folder: entry.path(),
            });
        } else {
            notes.push(format!("{id} is a file, not a student's folder: skipped"));
        }
    }
    students.sort_by(|a, b| a.id.cmp(&b.id));
    notes.sort();
    Ok((students, notes))
}

/// How many of the other images in a student's folder the message of a missing one names.
const OTHERS_NAMED: usize = 5;

/// The image `name` (without extension) in `student`'s folder: the file named `name` and one of
/// [`IMAGE_EXTENSIONS`], in any case of ASCII letters (`Spheres.PNG` is `spheres.png`), the
/// first extension of the list where several are there, the exact case first; or why there is
/// none, naming a few of the images the folder does hold.
pub fn find_image(student: &Student, name: &str) -> Result<PathBuf, String> {
    let folder = fs::symlink_metadata(&student.folder)
        .map_err(|e| format!("the folder cannot be read: {e}"))?;
    if folder.file_type().is_symlink() {
        return Err("the student's folder is a symbolic link: not followed".into());
    }
    let entries =
        fs::read_dir(&student.folder).map_err(|e| format!("the folder cannot be read: {e}"))?;
    // The best match as (extension's place in the list, not the exact case, file name).
    let mut best: Option<(usize, bool, String)> = None;
    let mut others = BTreeSet::new();
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some((stem, extension)) = file_name.to_str().and_then(|n| n.rsplit_once('.')) else {
            continue;
        };
        let Some(place) = IMAGE_EXTENSIONS
            .iter()
            .position(|e| e.eq_ignore_ascii_case(extension))
        else {
            continue;
        };
        let text = format!("{stem}.{extension}");
        if stem.eq_ignore_ascii_case(name) {
            let key = (
                place,
                stem != name || extension != IMAGE_EXTENSIONS[place],
                text,
            );
            if best.as_ref().is_none_or(|b| key < *b) {
                best = Some(key);
            }
        } else {
            others.insert(text);
            if others.len() > OTHERS_NAMED {
                others.pop_last();
            }
        }
    }
    let Some((_, _, file)) = best else {
        let mut message = format!(
            "missing: no {name}.{}",
            IMAGE_EXTENSIONS.join(format!(", {name}.").as_str())
        );
        if !others.is_empty() {
            let others: Vec<String> = others.into_iter().collect();
            message += &format!(" (the folder holds {})", others.join(", "));
        }
        return Err(message);
    };
    let path = student.folder.join(&file);
    match fs::symlink_metadata(&path) {
        Ok(meta) if meta.file_type().is_symlink() => {
            Err(format!("{file} is a symbolic link: not followed"))
        }
        Ok(meta) if meta.is_file() => Ok(path),
        Ok(_) => Err(format!("{file} is not a file")),
        Err(e) => Err(format!("{file} cannot be read: {e}")),
    }
}
