//! A class's submissions: one folder per student, named by the student's id, holding an image
//! per scene. Nothing a student hands in is trusted: a symbolic link is never followed (it
//! could lead anywhere), names may hold any character, and each image is found by its name and
//! one of the extensions raylab reads, or its absence is said.

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

/// The image `name` (without extension) in `student`'s folder: the first of
/// [`IMAGE_EXTENSIONS`] that is a regular file, or why there is none.
pub fn find_image(student: &Student, name: &str) -> Result<PathBuf, String> {
    let folder = fs::symlink_metadata(&student.folder)
        .map_err(|e| format!("the folder cannot be read: {e}"))?;
    if folder.file_type().is_symlink() {
        return Err("the student's folder is a symbolic link: not followed".into());
    }
    for extension in IMAGE_EXTENSIONS {
        let path = student.folder.join(format!("{name}.{extension}"));
        match fs::symlink_metadata(&path) {
            Ok(meta) if meta.file_type().is_symlink() => {
                return Err(format!(
                    "{name}.{extension} is a symbolic link: not followed"
                ));
            }
            Ok(meta) if meta.is_file() => return Ok(path),
            Ok(_) => return Err(format!("{name}.{extension} is not a file")),
            Err(_) => continue,
        }
    }
    Err(format!(
        "missing: no {name}.{}",
        IMAGE_EXTENSIONS.join(format!(", {name}.").as_str())
    ))
}
