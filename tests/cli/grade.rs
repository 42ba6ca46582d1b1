//! `raylab grade`: a class made here with the library (not with `grade`'s code): a student
//! whose images are exact, one without shadows, one who handed in nothing, one whose file names
//! are in capitals or mistyped, one with a truncated PNG, one with an image far too large, one
//! with a 1×1 image, one whose folder is a symbolic link out of the class, one whose id has a
//! space and accents, and one whose id is HTML; and a class whose every student made one of the
//! mistakes `raylab check` knows. Each is graded as expected, the CSV's means are `raylab
//! diff`'s, each mistake is named on its student's page with crops of the worst pixels, nothing
//! from a name reaches the HTML unescaped, and a wrong assignment or command line exits 1 or 2.

use std::path::Path;

use raylab::color::srgb8;
use raylab::formats::load_any;
use raylab::progressive::render_image;
use raylab::render::assemble;

use crate::common::run::{raylab, stderr};
use crate::common::students::mistaken;
use raylab::grade::report::html_escape;

const SIZE: (u32, u32) = (80, 60);
/// A folder name with a space and letters beyond ASCII.
pub(crate) const ACCENTED: &str = "Zoë Ñúñez";
/// A folder name that is HTML (a name cannot hold the `/` of `</script>`).
pub(crate) const HOSTILE: &str = "<img src=x onerror=alert(1)>";

fn shipped(name: &str) -> String {
    format!("{}/assets/scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// The image of the shipped scene `name` at [`SIZE`], with shadows or without, as 8-bit
/// levels; the mirrors at the assignment's depth of 4.
fn rendered(name: &str, shadows: bool) -> Vec<u8> {
    let mut scene = load_any(&shipped(name)).unwrap();
    (scene.settings.width, scene.settings.height) = SIZE;
    scene.settings.shadows = shadows;
    if name == "mirrors.toml" {
        scene.settings.max_depth = 4;
    }
    let assembled = assemble(scene).unwrap();
    let colors = render_image(&assembled.tracer()).0;
    colors
        .iter()
        .flat_map(|c| c.to_array().map(srgb8))
        .collect()
}

fn save_png(path: &Path, (width, height): (u32, u32), levels: Vec<u8>) {
    image::RgbImage::from_raw(width, height, levels)
        .unwrap()
        .save(path)
        .unwrap();
}

/// The assignment: two scenes, the first at a set size, the second at the student's.
pub(crate) fn assignment(dir: &Path) -> String {
    let text = format!(
        "[assignment]\nname = \"Ray tracer, part 1\"\ntolerance = 8\npass = 0.5\n\n\
         [[scene]]\nfile = \"{}\"\nimage = \"shadows\"\nsize = [{}, {}]\npoints = 10\n\n\
         [[scene]]\nfile = \"{}\"\nimage = \"mirrors\"\npoints = 5\nmax_depth = 4\n",
        shipped("shadows.toml"),
        SIZE.0,
        SIZE.1,
        shipped("mirrors.toml"),
    );
    let path = dir.join("assignment.toml");
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// The start of a PNG of `side × side` pixels: its header and a first chunk of pixel data
/// (64 zero bytes, stored uncompressed), far from all its pixels.
fn header_only_png(side: u32) -> Vec<u8> {
    let chunk = |kind: &[u8], data: &[u8]| {
        let mut bytes = (data.len() as u32).to_be_bytes().to_vec();
        let body = [kind, data].concat();
        bytes.extend(&body);
        bytes.extend(crc32(&body).to_be_bytes());
        bytes
    };
    let mut header = side.to_be_bytes().to_vec();
    header.extend(side.to_be_bytes());
    header.extend([8, 2, 0, 0, 0]);
    // A zlib stream of one stored block of 64 zeros: its header, the block's length and that
    // length's complement, the bytes, and their Adler-32.
    let mut zlib = vec![0x78, 0x01, 0x01, 64, 0, !64u8, 0xff];
    zlib.extend([0; 64]);
    zlib.extend(0x0040_0001u32.to_be_bytes());
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(chunk(b"IHDR", &header));
    png.extend(chunk(b"IDAT", &zlib));
    png
}

fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xedb8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// Writes the class into `dir/class` and returns its folder.
pub(crate) fn class(dir: &Path) -> std::path::PathBuf {
    let class = dir.join("class");
    // Each image rendered once, however many students hand it in.
    let shadows = rendered("shadows.toml", true);
    let shadowless = rendered("shadows.toml", false);
    let mirrors = rendered("mirrors.toml", true);
    // A student's folder, with each (file, image) of `images` in it.
    let student = |id: &str, images: &[(&str, &Vec<u8>)]| {
        let folder = class.join(id);
        std::fs::create_dir_all(&folder).unwrap();
        for (file, levels) in images {
            save_png(&folder.join(file), SIZE, levels.to_vec());
        }
        folder
    };
    student(
        "alice",
        &[("shadows.png", &shadows), ("mirrors.png", &mirrors)],
    );
    student(
        "bob",
        &[("shadows.png", &shadowless), ("mirrors.png", &mirrors)],
    );
    student("carol", &[]);
    let truncated = student("dave", &[]);
    let mut png = Vec::new();
    let image = image::RgbImage::from_raw(SIZE.0, SIZE.1, shadows.clone());
    image
        .unwrap()
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    std::fs::write(truncated.join("shadows.png"), &png[..png.len() / 2]).unwrap();
    let huge = student("erin", &[]);
    std::fs::write(huge.join("shadows.png"), header_only_png(16384)).unwrap();
    std::fs::write(huge.join("mirrors.png"), header_only_png(16384)).unwrap();
    let tiny = student("frank", &[]);
    save_png(&tiny.join("shadows.ppm"), (1, 1), vec![0, 0, 0]);
    // Handed in with the extension in capitals, and the second image under a mistyped name.
    student(
        "grace",
        &[("Shadows.PNG", &shadows), ("mirror.png", &mirrors)],
    );
    student(ACCENTED, &[("shadows.png", &shadows)]);
    student(HOSTILE, &[("shadows.png", &shadows)]);
    let outside = dir.join("outside");
    std::fs::create_dir_all(&outside).unwrap();
    save_png(&outside.join("shadows.png"), SIZE, shadows);
    std::os::unix::fs::symlink(&outside, class.join("mallory")).unwrap();
    class
}

/// The CSV row of `student`, split at its commas.
pub(crate) fn row(csv: &str, student: &str) -> Vec<String> {
    let line = csv
        .lines()
        .find(|line| line.starts_with(student))
        .unwrap_or_else(|| panic!("no row for {student} in\n{csv}"));
    line.split(',').map(String::from).collect()
}

#[test]
fn a_class_is_graded_each_problem_a_zero_that_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let assignment = assignment(dir);
    let class = class(dir);
    let out = raylab(&["grade", &assignment, "class", "-o", "report"], dir);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let report = dir.join("report");
    let csv = std::fs::read_to_string(report.join("grades.csv")).unwrap();
    assert_eq!(
        csv.lines().next(),
        Some("student,shadows mean,shadows points,mirrors mean,mirrors points,total")
    );
    assert_eq!(
        row(&csv, "alice"),
        ["alice", "0.0000", "10", "0.0000", "5", "15"]
    );
    let bob = row(&csv, "bob");
    assert_eq!(
        (bob[2].as_str(), bob[4].as_str(), bob[5].as_str()),
        ("0", "5", "5")
    );
    // The mean is `raylab diff`'s.
    let reference = report.join(format!("references/0-{}x{}.png", SIZE.0, SIZE.1));
    let diff = raylab(
        &[
            "diff",
            &reference.to_string_lossy(),
            &class.join("bob/shadows.png").to_string_lossy(),
        ],
        dir,
    );
    let printed = String::from_utf8_lossy(&diff.stdout);
    assert!(
        printed.contains(&format!("mean absolute difference: {} levels", bob[1])),
        "{printed} against {bob:?}"
    );
    assert_eq!(
        row(&csv, ACCENTED),
        [ACCENTED, "0.0000", "10", "", "0", "10"]
    );
    for nothing in ["carol", "dave", "erin", "frank", "mallory"] {
        let r = row(&csv, nothing);
        assert_eq!(r.last().map(String::as_str), Some("0"), "{r:?}");
        assert_eq!((r[1].as_str(), r[2].as_str()), ("", "0"), "{r:?}");
    }

    let index = std::fs::read_to_string(report.join("index.html")).unwrap();
    let dave = std::fs::read_to_string(report.join("dave.html")).unwrap();
    for (page, says) in [
        (&index, "missing: no shadows.png"),
        (&index, "is 16384×16384; the assignment asks for 80×60"),
        (&index, "is 1×1; the assignment asks for 80×60"),
        (&index, "symbolic link: not followed"),
        (
            &index,
            "mirrors.hdr (the folder holds Shadows.PNG, mirror.png)",
        ),
        (&index, "&lt;img src=x onerror=alert(1)&gt;"),
        (&index, ACCENTED),
        (&dave, "shadows.png cannot be read"),
    ] {
        assert!(page.contains(says), "the page does not say {says:?}");
    }
    assert!(
        !index.contains(HOSTILE),
        "the hostile name reached the HTML as it is"
    );
    assert!(
        index.contains("is 16384×16384: larger than raylab renders for grading"),
        "the size left to the students is bounded"
    );
    assert_images_in(&report);
}

/// Checks that every image a page of `report` shows is in the report.
fn assert_images_in(report: &Path) {
    for page in std::fs::read_dir(report).unwrap() {
        let page = page.unwrap().path();
        if page.extension().is_some_and(|e| e == "html") {
            let text = std::fs::read_to_string(&page).unwrap();
            for source in text.split("src=\"").skip(1) {
                let file = source.split('"').next().unwrap();
                assert!(report.join(file).is_file(), "{}: {file}", page.display());
            }
        }
    }
}

/// The mean `raylab diff` prints for `image` against `reference`.
fn diff_mean(reference: &Path, image: &Path, dir: &Path) -> String {
    let out = raylab(
        &[
            "diff",
            &reference.to_string_lossy(),
            &image.to_string_lossy(),
        ],
        dir,
    );
    let printed = String::from_utf8_lossy(&out.stdout).into_owned();
    let after = printed
        .split("mean absolute difference: ")
        .nth(1)
        .unwrap_or_else(|| panic!("no mean in {printed}"));
    after.split(' ').next().unwrap().to_string()
}

#[test]
fn each_students_mistake_is_named_on_their_page_with_crops_of_the_worst_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let size = (160, 120);
    let mut scene = load_any(&shipped("default.toml")).unwrap();
    (scene.settings.width, scene.settings.height) = size;
    let students = mistaken(&scene);
    for student in &students {
        let folder = dir.join("class").join(student.name);
        std::fs::create_dir_all(&folder).unwrap();
        let levels = student.pixels.iter().flatten().copied().collect();
        save_png(&folder.join("default.png"), size, levels);
    }
    let text = format!(
        "[assignment]\nname = \"Mistakes\"\npass = 0.0\n\n[[scene]]\nfile = \"{}\"\n\
         image = \"default\"\nsize = [{}, {}]\npoints = 1\n",
        shipped("default.toml"),
        size.0,
        size.1
    );
    std::fs::write(dir.join("assignment.toml"), text).unwrap();
    let out = raylab(&["grade", "assignment.toml", "class", "-o", "report"], dir);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let report = dir.join("report");
    let csv = std::fs::read_to_string(report.join("grades.csv")).unwrap();
    let reference = report.join(format!("references/0-{}x{}.png", size.0, size.1));
    for student in &students {
        let r = row(&csv, student.name);
        assert_eq!((r[2].as_str(), r[3].as_str()), ("0", "0"), "{r:?}");
        let image = dir.join("class").join(student.name).join("default.png");
        assert_eq!(r[1], diff_mean(&reference, &image, dir), "{}", student.name);
        let page = std::fs::read_to_string(report.join(format!("{}.html", student.name))).unwrap();
        assert!(
            page.contains(&html_escape(student.says)),
            "{}'s page does not say {:?}",
            student.name,
            student.says
        );
    }
    // The shadows a student left out are explained where they are, with crops around the
    // worst pixels, the worst framed.
    let page = std::fs::read_to_string(report.join("no-shadows.html")).unwrap();
    for says in [
        "region 1 of ",
        "raylab&#39;s eye ray hits ",
        "shadow ray",
        "brighter by",
    ] {
        assert!(
            page.contains(says),
            "the page does not say {says:?}:\n{page}"
        );
    }
    for crop in ["raylab", "image", "difference"] {
        let file = format!("no-shadows/0-region1-{crop}.png");
        assert!(page.contains(&file), "no {file} on the page");
        let (width, height) = image::image_dimensions(report.join(&file)).unwrap();
        assert_eq!((width, height), (25, 25), "{file}");
    }
    assert!(
        page.contains("class=\"worst\""),
        "the worst pixel is not framed"
    );
    assert_images_in(&report);
    let out = raylab(
        &["grade", "assignment.toml", "--student", "class/no-shadows"],
        dir,
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("\n  likely cause: shadows are missing"),
        "{text}"
    );
}

#[test]
fn a_student_grades_their_own_folder_before_handing_in() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let assignment = assignment(dir);
    class(dir);
    let out = raylab(&["grade", &assignment, "--student", "class/bob"], dir);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("shadows: mean "), "{text}");
    assert!(text.contains("> 0.5: fail, 0 of 10 points"), "{text}");
    assert!(
        text.contains("mirrors: mean 0.0000 ≤ 0.5: pass, 5 of 5 points"),
        "{text}"
    );
    assert!(text.contains("total: 5 of 15 points"), "{text}");
}

#[test]
fn a_wrong_assignment_exits_1_at_its_line_and_a_wrong_command_line_2() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    std::fs::create_dir_all(dir.join("class")).unwrap();
    for (text, says) in [
        (
            "[assignment]\nname = \"x\"\ncolour = 3\n[[scene]]\nfile = \"a.toml\"\nimage = \"a\"\n",
            "assignment.toml:3:1",
        ),
        (
            "[assignment]\nname = \"x\"\n[[scene]]\nfile = \"nowhere.toml\"\nimage = \"a\"\n",
            "assignment.toml:4:8: no scene file",
        ),
        (
            "[assignment]\nname = \"x\"\n[[scene]]\nfile = \"nowhere.toml\"\nimage = \"a.png\"\n",
            "assignment.toml:5:9",
        ),
    ] {
        std::fs::write(dir.join("assignment.toml"), text).unwrap();
        let out = raylab(&["grade", "assignment.toml", "class", "-o", "report"], dir);
        assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
        assert!(stderr(&out).contains(says), "{}", stderr(&out));
    }
    assignment(dir);
    let out = raylab(&["grade", "assignment.toml", "--student", "nobody"], dir);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("nobody: no such folder"),
        "{}",
        stderr(&out)
    );
    let out = raylab(&["grade", "assignment.toml"], dir);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let out = raylab(&["grade", "assignment.toml", "class"], dir);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}
