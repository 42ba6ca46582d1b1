//! The report of a graded class, a folder a browser opens offline: `index.html` (the class
//! table, students × scenes, each cell the measure coloured by pass or fail and the points,
//! sortable by any column, the references on top), a page per student (`ID.html`: for each
//! scene raylab's image, the student's and the heat map of where they differ, side by side at
//! the same scale, the figures, and for a failed image what `raylab check` finds: the mistakes
//! that account for it and the worst pixels explained from raylab's ray tree, with crops of the
//! three pictures around them), the images they show, and `grades.csv` for a grade book.
//! Every name that comes from a file or a folder is escaped in the HTML and in the CSV, and
//! every file the report links to lies inside it under a name it chose.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use super::assignment::Assignment;
use super::{ReferenceKey, References, SceneGrade, StudentGrades};
use crate::compare::check::CheckReport;
use crate::compare::difference::HeatMap;
use crate::formats::image::{PixelAt, save_toned_pixels};
use crate::output::write_atomically;
use crate::srgb_image::SrgbImage;
use crate::tone::Tone;

/// The colours of a passing and a failing cell in the class table.
pub const PASS_COLOR: &str = "#b9e6b3";
pub const FAIL_COLOR: &str = "#f2b8b5";

/// `text` safe inside HTML text and attribute values.
pub fn html_escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&#39;"),
            c if c.is_control() => escaped.push('\u{fffd}'),
            c => escaped.push(c),
        }
    }
    escaped
}

/// `text` as one CSV field: quoted, its quotes doubled, where it holds a comma, a quote or a
/// line break; a leading `=`, `+`, `-` or `@` (a spreadsheet formula) behind a quote.
pub fn csv_field(text: &str) -> String {
    let formula = text.starts_with(['=', '+', '-', '@']);
    let text = if formula {
        format!("'{text}")
    } else {
        text.to_string()
    };
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text
    }
}

/// The name of each student's page and image folder: their id with every character but
/// letters, digits, `-` and `_` made `_`, numbered where two ids come out alike (or one
/// would be the class's own `index`, `grades` or `references`).
pub fn page_names(grades: &[StudentGrades]) -> Vec<String> {
    let mut taken: BTreeSet<String> = ["index", "grades", "references"].map(String::from).into();
    grades
        .iter()
        .map(|g| {
            let safe: String = g
                .student
                .id
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                        c
                    } else {
                        '_'
                    }
                })
                .collect();
            let mut name = safe.clone();
            let mut n = 2;
            while !taken.insert(name.clone()) {
                name = format!("{safe}-{n}");
                n += 1;
            }
            name
        })
        .collect()
}

/// `grades.csv`: a row per student, each scene's measure (empty where the image could not be
/// measured) and points, and the total.
pub fn csv(assignment: &Assignment, grades: &[StudentGrades]) -> String {
    let mut text = String::from("student");
    for scene in &assignment.scenes {
        let image = csv_field(&scene.image);
        let _ = write!(text, ",{image} {},{image} points", assignment.measure);
    }
    text.push_str(",total\n");
    for student in grades {
        text.push_str(&csv_field(&student.student.id));
        for scene in &student.scenes {
            let measure = scene
                .measured
                .as_ref()
                .map_or(String::new(), |m| format!("{:.4}", m.measure));
            let _ = write!(text, ",{measure},{}", scene.points);
        }
        let _ = writeln!(text, ",{}", student.total());
    }
    text
}

/// Writes the report of `grades` into `folder` (made if need be).
pub fn write_report(
    folder: &Path,
    assignment: &Assignment,
    grades: &[StudentGrades],
    references: &References,
) -> Result<(), String> {
    let io = |path: &Path, e: std::io::Error| format!("{}: {e}", path.display());
    std::fs::create_dir_all(folder.join("references")).map_err(|e| io(folder, e))?;
    let names = page_names(grades);
    let mut reference_files = Vec::new();
    for (&(k, size), reference) in references {
        if let Ok(traces) = reference {
            let file = format!("references/{}-{}x{}.png", k, size.0, size.1);
            save_png(&folder.join(&file), &traces.reference)?;
            reference_files.push(((k, size), file));
        }
    }
    let reference_of = |k: usize, size: (u32, u32)| {
        reference_files
            .iter()
            .find(|(key, _)| *key == (k, size))
            .map(|(_, file)| file.clone())
    };
    for (student, name) in grades.iter().zip(&names) {
        std::fs::create_dir_all(folder.join(name)).map_err(|e| io(folder, e))?;
        let page = student_page(assignment, student, name, references, &reference_of, folder)?;
        write_text(&folder.join(format!("{name}.html")), &page)?;
    }
    write_text(&folder.join("grades.csv"), &csv(assignment, grades))?;
    let index = index_page(assignment, grades, &names, &reference_files);
    write_text(&folder.join("index.html"), &index)
}

fn write_text(path: &Path, text: &str) -> Result<(), String> {
    write_atomically(
        path,
        |e| format!("{}: {e}", path.display()),
        |out| {
            out.write_all(text.as_bytes())
                .map_err(|e| format!("{}: {e}", path.display()))
        },
    )
}

/// Saves `image` as a PNG at `path`, byte for byte.
fn save_png(path: &Path, image: &SrgbImage) -> Result<(), String> {
    let size = (image.width, image.height);
    save_window(path, (0, 0), size, &|x, y| image.linear_at(x, y))
}

/// Saves the window of `size` pixels with its top-left corner at `corner` of the picture whose
/// pixel `(x, y)` is `pixel` as a PNG at `path`.
fn save_window(
    path: &Path,
    corner: (u32, u32),
    size: (u32, u32),
    pixel: PixelAt,
) -> Result<(), String> {
    let window = |x, y| pixel(corner.0 + x, corner.1 + y);
    save_toned_pixels(path, size.0, size.1, &window, Tone::default()).map_err(|e| e.to_string())
}

/// The page's head: its title, and the styles of the tables and images.
fn head(title: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{}</title>\n<style>\n\
         body {{ font-family: sans-serif; margin: 1.5em; }}\n\
         table {{ border-collapse: collapse; }}\n\
         th, td {{ border: 1px solid #999; padding: 0.3em 0.6em; text-align: left; }}\n\
         th {{ background: #eee; cursor: pointer; }}\n\
         td.pass {{ background: {PASS_COLOR}; }}\n\
         td.fail {{ background: {FAIL_COLOR}; }}\n\
         figure {{ display: inline-block; vertical-align: top; margin: 0 1em 1em 0; }}\n\
         figcaption {{ max-width: 320px; }}\n\
         img {{ image-rendering: pixelated; width: 320px; }}\n\
         .crop {{ position: relative; display: inline-block; }}\n\
         .crop img {{ display: block; }}\n\
         .crop .worst {{ position: absolute; box-sizing: border-box; border: 2px solid #00e5ff; }}\n\
         </style>\n</head>\n<body>\n",
        html_escape(title)
    )
}

/// The class table, sortable by a click on a column's head (the script is the page's own).
fn index_page(
    assignment: &Assignment,
    grades: &[StudentGrades],
    names: &[String],
    references: &[(ReferenceKey, String)],
) -> String {
    let mut page = head(&assignment.name);
    let _ = writeln!(page, "<h1>{}</h1>", html_escape(&assignment.name));
    let _ = writeln!(
        page,
        "<p>{} students. A scene passes when its {} is at most {} (tolerance {} levels).</p>",
        grades.len(),
        assignment.measure,
        assignment.pass,
        assignment.tolerance
    );
    page.push_str("<div>\n");
    for ((k, size), file) in references {
        let scene = &assignment.scenes[*k];
        let _ = writeln!(
            page,
            "<figure><img src=\"{file}\" alt=\"raylab's {image}\"><figcaption>raylab's {image} \
             ({}×{})</figcaption></figure>",
            size.0,
            size.1,
            image = html_escape(&scene.image)
        );
    }
    page.push_str("</div>\n<table id=\"class\">\n<thead><tr><th>student</th>");
    for scene in &assignment.scenes {
        let _ = write!(
            page,
            "<th>{} ({} points)</th>",
            html_escape(&scene.image),
            scene.points
        );
    }
    page.push_str("<th>total</th></tr></thead>\n<tbody>\n");
    for (student, name) in grades.iter().zip(names) {
        let _ = write!(
            page,
            "<tr><td><a href=\"{name}.html\">{}</a></td>",
            html_escape(&student.student.id)
        );
        for scene in &student.scenes {
            page.push_str(&cell(scene));
        }
        let _ = writeln!(page, "<td>{}</td></tr>", student.total());
    }
    page.push_str("</tbody>\n</table>\n");
    page.push_str(SORT_SCRIPT);
    page.push_str("</body>\n</html>\n");
    page
}

/// A cell of the class table: the measure and the points, or what is wrong.
fn cell(scene: &SceneGrade) -> String {
    match &scene.measured {
        Ok(m) => {
            let class = if m.passed { "pass" } else { "fail" };
            format!(
                "<td class=\"{class}\" data-sort=\"{:.4}\">{:.2} · {} points</td>",
                m.measure, m.measure, scene.points
            )
        }
        Err(problem) => format!(
            "<td class=\"fail\" data-sort=\"Infinity\">{} · 0 points</td>",
            html_escape(problem)
        ),
    }
}

/// Sorts the class table by the column whose head is clicked, numbers as numbers; a second
/// click reverses the order.
const SORT_SCRIPT: &str = r##"<script>
document.querySelectorAll("#class th").forEach((th, column) => {
  th.addEventListener("click", () => {
    const body = document.querySelector("#class tbody");
    const rows = Array.from(body.rows);
    const key = row => {
      const cell = row.cells[column];
      const text = cell.dataset.sort ?? cell.textContent;
      const number = parseFloat(text);
      return isNaN(number) && text !== "Infinity" ? text : (text === "Infinity" ? Infinity : number);
    };
    const down = th.dataset.down !== "true";
    th.dataset.down = down;
    rows.sort((a, b) => {
      const [x, y] = [key(a), key(b)];
      const order = x < y ? -1 : x > y ? 1 : 0;
      return down ? order : -order;
    });
    rows.forEach(row => body.appendChild(row));
  });
});
</script>
"##;

/// A student's page: for each scene, raylab's image, the student's and the heat map.
fn student_page(
    assignment: &Assignment,
    student: &StudentGrades,
    name: &str,
    references: &References,
    reference_of: &dyn Fn(usize, (u32, u32)) -> Option<String>,
    folder: &Path,
) -> Result<String, String> {
    let id = html_escape(&student.student.id);
    let mut page = head(&format!("{} — {}", student.student.id, assignment.name));
    let _ = writeln!(
        page,
        "<p><a href=\"index.html\">{}</a></p>\n<h1>{id}: {} points</h1>",
        html_escape(&assignment.name),
        student.total()
    );
    for (k, (scene, grade)) in assignment.scenes.iter().zip(&student.scenes).enumerate() {
        let _ = writeln!(
            page,
            "<h2>{} ({})</h2>",
            html_escape(&scene.image),
            html_escape(&scene.file)
        );
        let measured = match &grade.measured {
            Ok(measured) => measured,
            Err(problem) => {
                let _ = writeln!(page, "<p>{} · 0 points</p>", html_escape(problem));
                continue;
            }
        };
        let size = (measured.difference.width, measured.difference.height);
        let Some(Ok(traces)) = references.get(&(k, size)) else {
            continue;
        };
        let reference = &traces.reference;
        let image_path = grade.image.as_deref().unwrap_or(Path::new(""));
        let image = SrgbImage::read(image_path)?;
        let own = format!("{name}/{k}-image.png");
        let heat = format!("{name}/{k}-difference.png");
        save_png(&folder.join(&own), &image)?;
        let map = HeatMap::new(reference, &image, &measured.difference);
        save_window(&folder.join(&heat), (0, 0), size, &|x, y| map.color(x, y))?;
        let verdict = if measured.passed { "passed" } else { "failed" };
        let d = &measured.difference;
        let _ = writeln!(
            page,
            "<p>{} {:.4}: {verdict}, {} points. Mean {:.4} levels, RMSE {:.4}, PSNR {:.2} dB, \
             largest {} at ({}, {}), {} pixels over {} levels.</p>",
            assignment.measure,
            measured.measure,
            grade.points,
            d.mean_absolute,
            d.rmse,
            d.psnr,
            d.largest,
            d.largest_at.0,
            d.largest_at.1,
            d.over_tolerance,
            d.tolerance
        );
        let reference_file = reference_of(k, size).unwrap_or_default();
        let _ = writeln!(
            page,
            "<figure><img src=\"{reference_file}\" alt=\"raylab's image\"><figcaption>raylab's image\
             </figcaption></figure><figure><img src=\"{own}\" alt=\"{id}'s image\"><figcaption>\
             {id}'s image</figcaption></figure><figure><img src=\"{heat}\" alt=\"where they differ\">\
             <figcaption>where they differ: {}</figcaption></figure>",
            html_escape(&map.legend().to_text())
        );
        match &measured.check {
            Some(Ok(report)) => {
                let pictures = Pictures {
                    reference,
                    image: &image,
                    map: &map,
                };
                let prefix = format!("{name}/{k}");
                page += &findings(report, &pictures, &prefix, &id, folder)?;
            }
            Some(Err(problem)) => {
                let _ = writeln!(
                    page,
                    "<p>raylab's check could not look: {}</p>",
                    html_escape(problem)
                );
            }
            None => {}
        }
    }
    page.push_str("</body>\n</html>\n");
    Ok(page)
}

/// The three pictures of a scene a student page shows side by side.
struct Pictures<'a> {
    reference: &'a SrgbImage,
    image: &'a SrgbImage,
    map: &'a HeatMap<'a>,
}

/// How many pixels a side a crop around a region's worst pixel has at most, and how many
/// times larger it is shown.
const CROP_SIDE: u32 = 25;
const CROP_ZOOM: u32 = 8;

/// What `raylab check` found in a failed image, as HTML: the mistakes and notes, then each
/// region explained, with crops of the three pictures around its worst pixel (saved under
/// `prefix`, a file name's start inside `folder`). `id` is the student's, escaped.
fn findings(
    report: &CheckReport,
    pictures: &Pictures,
    prefix: &str,
    id: &str,
    folder: &Path,
) -> Result<String, String> {
    let mut html = String::from("<h3>What raylab's check finds</h3>\n<ul class=\"findings\">\n");
    for line in report.findings() {
        let _ = writeln!(html, "<li>{}</li>", html_escape(&line));
    }
    html.push_str("</ul>\n");
    let (width, height) = (pictures.reference.width, pictures.reference.height);
    for (i, explained) in report.regions.iter().enumerate() {
        let mut lines = explained.lines(i, report.region_count).into_iter();
        let title = lines.next().unwrap_or_default();
        let _ = writeln!(
            html,
            "<div class=\"region\">\n<h4>{}</h4>\n<ul>",
            html_escape(&title)
        );
        for line in lines {
            let _ = writeln!(html, "<li>{}</li>", html_escape(&line));
        }
        html.push_str("</ul>\n");
        let (x, y) = explained.explanation.pixel;
        let side = (CROP_SIDE.min(width), CROP_SIDE.min(height));
        let corner = (
            x.saturating_sub(side.0 / 2).min(width - side.0),
            y.saturating_sub(side.1 / 2).min(height - side.1),
        );
        let crops: [(&str, String, PixelAt); 3] = [
            ("raylab", "raylab's".into(), &|x, y| {
                pictures.reference.linear_at(x, y)
            }),
            ("image", format!("{id}'s"), &|x, y| {
                pictures.image.linear_at(x, y)
            }),
            ("difference", "the difference".into(), &|x, y| {
                pictures.map.color(x, y)
            }),
        ];
        for (what, whose, pixel) in crops {
            let file = format!("{prefix}-region{}-{what}.png", i + 1);
            save_window(&folder.join(&file), corner, side, pixel)?;
            // The worst pixel framed, in hundredths of the crop.
            let at = |v: u32, c: u32, s: u32| 100.0 * f64::from(v - c) / f64::from(s);
            let _ = writeln!(
                html,
                "<figure><div class=\"crop\"><img src=\"{file}\" alt=\"{whose} pixels around \
                 ({x}, {y})\" style=\"width: {}px\"><span class=\"worst\" style=\"left: {:.3}%; \
                 top: {:.3}%; width: {:.3}%; height: {:.3}%\"></span></div><figcaption>{whose}, \
                 around ({x}, {y})</figcaption></figure>",
                side.0 * CROP_ZOOM,
                at(x, corner.0, side.0),
                at(y, corner.1, side.1),
                100.0 / f64::from(side.0),
                100.0 / f64::from(side.1),
            );
        }
        html.push_str("</div>\n");
    }
    Ok(html)
}
