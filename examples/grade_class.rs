//! A class for `raylab grade` to grade: an assignment of four shipped scenes and a folder per
//! student, each image either raylab's own or one with a mistake `raylab check` names (made
//! with the library, as the tests make them), some as PNG and some as PPM, and the answer key
//! (`key.csv`: each image's mistake and what `check` says of it). What BENCHMARKS.md's
//! grading figures are measured on, and a class to try the report with.
//!
//! ```sh
//! cargo run --release --example grade_class -- /tmp/class 40 640x480
//! raylab grade /tmp/class/assignment.toml /tmp/class/students -o /tmp/class/report
//! ```
//!
//! Student `i`'s image of scene `k` has mistake `(i + k) mod 21` of the seventeen, or none for
//! the other four: about a fifth to a quarter of the images are raylab's.

use std::path::Path;

use raylab::formats::load_any;

#[path = "../tests/common/students.rs"]
mod students;

/// The scenes of the assignment, from `assets/scenes`.
const SCENES: [&str; 4] = ["default", "glass", "mirrors", "shadows"];
/// How many of every sixteen images are raylab's own.
const EXACT: usize = 4;

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: grade_class FOLDER [STUDENTS] [WIDTHxHEIGHT]";
    let folder = Path::new(args.first().ok_or(usage)?);
    let count: usize = match args.get(1) {
        Some(n) => n.parse().map_err(|_| usage)?,
        None => 40,
    };
    let size = match args.get(2) {
        Some(text) => {
            let (w, h) = text.split_once('x').ok_or(usage)?;
            (w.parse().map_err(|_| usage)?, h.parse().map_err(|_| usage)?)
        }
        None => (640u32, 480u32),
    };
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut assignment =
        String::from("[assignment]\nname = \"Ray tracer, part 1\"\ntolerance = 8\npass = 1.0\n");
    let mut images = Vec::new();
    for name in SCENES {
        let file = scenes.join(format!("{name}.toml"));
        let mut scene = load_any(&file.to_string_lossy()).map_err(|e| e.to_string())?;
        (scene.settings.width, scene.settings.height) = size;
        assignment += &format!(
            "\n[[scene]]\nfile = {:?}\nimage = \"{name}\"\nsize = [{}, {}]\npoints = 10\n",
            file.display().to_string(),
            size.0,
            size.1
        );
        let exact = students::levels(&students::rendered(&scene));
        let mistaken = students::mistaken(&scene);
        images.push((exact, mistaken));
    }
    std::fs::create_dir_all(folder).map_err(|e| e.to_string())?;
    std::fs::write(folder.join("assignment.toml"), assignment).map_err(|e| e.to_string())?;
    // The answer key: what each image was made with, and what `check` says of it.
    let mut key = String::from("student,scene,mistake,check says\n");
    for i in 0..count {
        let student = folder.join(format!("students/student{:02}", i + 1));
        std::fs::create_dir_all(&student).map_err(|e| e.to_string())?;
        for (k, (name, (exact, mistaken))) in SCENES.iter().zip(&images).enumerate() {
            let which = (i + k) % (mistaken.len() + EXACT);
            let pixels = match mistaken.get(which) {
                Some(m) => {
                    key += &format!("student{:02},{name},{},{}\n", i + 1, m.name, m.says);
                    &m.pixels
                }
                None => exact,
            };
            let extension = if i % 3 == 2 { "ppm" } else { "png" };
            let bytes = pixels.iter().flatten().copied().collect();
            image::RgbImage::from_raw(size.0, size.1, bytes)
                .ok_or("the image's size")?
                .save(student.join(format!("{name}.{extension}")))
                .map_err(|e| e.to_string())?;
        }
    }
    std::fs::write(folder.join("key.csv"), key).map_err(|e| e.to_string())?;
    println!(
        "{count} students × {} scenes at {}×{}: {}",
        SCENES.len(),
        size.0,
        size.1,
        folder.display()
    );
    Ok(())
}
