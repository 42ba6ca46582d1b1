//! The report of `raylab grade` in a real browser: headless Chromium (Debian's `chromium`)
//! opens the class table and students' pages from the report folder. Every image loads, no
//! script runs from the student id that is HTML, the crops frame a pixel, a click on a column's
//! head sorts the table, and a screenshot of the class table shows each cell in the colour the
//! CSV's points call for.

use std::path::Path;
use std::process::{Command, Output};

use raylab::grade::report::{FAIL_COLOR, PASS_COLOR};

use crate::common::run::{raylab, stderr};
use crate::grade::{HOSTILE, assignment, class, row};

/// The window the pages are opened in, in CSS pixels (one screenshot pixel each).
const WINDOW: (u32, u32) = (1400, 1800);

/// What is put at the start of a copy of a page to probe it: any alert is recorded, and once the
/// page has loaded, its images (whether each loaded and its natural width), where each crop's
/// frame around its worst pixel lies on the crop, the class table's cells (where each lies),
/// links and totals once sorted by a click on the total's head, and the alerts are written into
/// a hidden `pre#probe`.
const PROBE: &str = r##"<script>
window.alerts = [];
window.alert = message => window.alerts.push(String(message));
window.addEventListener("load", () => {
  const lines = [];
  for (const img of document.images) {
    lines.push(`image ${img.getAttribute("src")} ${img.complete} ${img.naturalWidth}`);
  }
  for (const td of document.querySelectorAll("#class td")) {
    const r = td.getBoundingClientRect();
    lines.push(`cell ${td.parentElement.rowIndex} ${td.cellIndex} ${Math.round(r.left)} ` +
      `${Math.round(r.top)} ${Math.round(r.width)} ${Math.round(r.height)}`);
  }
  for (const crop of document.querySelectorAll(".crop")) {
    const [img, mark] = [crop.querySelector("img"), crop.querySelector(".worst")];
    const [i, m] = [img.getBoundingClientRect(), mark.getBoundingClientRect()];
    lines.push(`crop ${img.naturalWidth} ${i.width} ${m.left - i.left} ${m.top - i.top} ` +
      `${m.width} ${m.height}`);
  }
  for (const a of document.querySelectorAll("#class a")) {
    lines.push(`link ${a.getAttribute("href")} ${a.textContent}`);
  }
  lines.push(`handlers ${document.querySelectorAll("[onerror], [onload]").length}`);
  // A click on the last column's head (the total) sorts the rows by it.
  const heads = document.querySelectorAll("#class th");
  if (heads.length > 0) {
    heads[heads.length - 1].click();
    const totals = Array.from(document.querySelectorAll("#class tbody tr"), row =>
      row.cells[row.cells.length - 1].textContent);
    lines.push(`sorted ${totals.join(" ")}`);
  }
  lines.push(`alerts ${window.alerts.length}`);
  const out = document.createElement("pre");
  out.id = "probe";
  out.hidden = true;
  out.textContent = lines.join("\n");
  document.body.appendChild(out);
});
</script>"##;

/// The longest a run of the browser may take before it is stopped (coreutils' `timeout`), so
/// that a browser that hangs fails the test rather than holding it up.
const BROWSER_SECONDS: &str = "120";

/// Runs headless Chromium with `args` after the flags every run takes.
fn chromium(args: &[&str]) -> Output {
    let window = format!("--window-size={},{}", WINDOW.0, WINDOW.1);
    let out = Command::new("timeout")
        .args([BROWSER_SECONDS, "chromium"])
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
            &window,
        ])
        .args(args)
        .output()
        .expect("coreutils' timeout runs");
    match out.status.code() {
        // `timeout` found no program to run.
        Some(126 | 127) => panic!(
            "headless Chromium cannot run ({}): install Debian's chromium with `sudo apt-get \
             install -y --no-install-recommends chromium` (scripts/test installs it when run as \
             root)",
            stderr(&out).trim()
        ),
        Some(124) => panic!(
            "headless Chromium did not finish in {BROWSER_SECONDS} s: {}",
            stderr(&out)
        ),
        _ => out,
    }
}

/// The lines the probe writes of `page` (a file of the report folder) once a browser has loaded
/// it: the page is copied beside itself with [`PROBE`] at the start of its head.
fn probe(report: &Path, page: &str) -> Vec<String> {
    let text = std::fs::read_to_string(report.join(page)).unwrap();
    assert!(text.contains("<head>"), "{page} has no head");
    let probed = report.join(format!("probe-{page}"));
    std::fs::write(
        &probed,
        text.replacen("<head>", &format!("<head>{PROBE}"), 1),
    )
    .unwrap();
    let out = chromium(&[
        "--virtual-time-budget=20000",
        "--dump-dom",
        &format!("file://{}", probed.display()),
    ]);
    std::fs::remove_file(&probed).unwrap();
    let dom = String::from_utf8_lossy(&out.stdout);
    let Some(start) = dom.find("<pre id=\"probe\" hidden=\"\">") else {
        panic!(
            "{page}: the browser's DOM has no probe:\n{dom}\n{}",
            stderr(&out)
        );
    };
    let after = &dom[start..];
    let text = &after[after.find('>').unwrap() + 1..after.find("</pre>").unwrap()];
    let text = text
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    text.lines().map(String::from).collect()
}

/// Checks that every image of `page` loaded, that it has at least one, and that no script ran
/// from a name: no element has an event handler and nothing called `alert`.
fn assert_loaded_and_inert(lines: &[String], page: &str) {
    let images: Vec<&String> = lines.iter().filter(|l| l.starts_with("image ")).collect();
    assert!(!images.is_empty(), "{page} shows no image: {lines:?}");
    for image in images {
        let fields: Vec<&str> = image.split(' ').collect();
        assert!(
            fields[2] == "true" && fields[3].parse::<u32>().unwrap() > 0,
            "{page}: an image did not load: {image}"
        );
    }
    for nothing in ["handlers 0", "alerts 0"] {
        assert!(
            lines.iter().any(|l| l == nothing),
            "{page}: expected {nothing:?} in {lines:?}"
        );
    }
}

/// Checks that `page` shows crops, and that each frame covers one pixel of its crop as shown:
/// as wide as a pixel, and at a whole number of pixels from the crop's corner.
fn assert_frames_on_pixels(lines: &[String], page: &str) {
    let crops: Vec<Vec<f64>> = lines
        .iter()
        .filter_map(|l| l.strip_prefix("crop "))
        .map(|l| l.split(' ').map(|n| n.parse().unwrap()).collect())
        .collect();
    assert!(!crops.is_empty(), "{page} shows no crops: {lines:?}");
    for crop in crops {
        let [pixels, width, left, top, frame_width, frame_height] = crop[..] else {
            panic!("{page}: {crop:?}");
        };
        let pixel = width / pixels;
        let whole = |v: f64| (v / pixel - (v / pixel).round()).abs() < 0.05;
        assert!(
            (frame_width - pixel).abs() < 0.5 && (frame_height - pixel).abs() < 0.5,
            "{page}: a frame of {frame_width}×{frame_height} on pixels of {pixel}"
        );
        assert!(
            whole(left) && whole(top) && (0.0..width).contains(&left),
            "{page}: a frame at ({left}, {top}) on pixels of {pixel}"
        );
    }
}

/// The colour `#rrggbb` as levels.
fn levels(color: &str) -> [u8; 3] {
    let channel = |i: usize| u8::from_str_radix(&color[1 + 2 * i..3 + 2 * i], 16).unwrap();
    [channel(0), channel(1), channel(2)]
}

#[test]
fn the_report_loads_in_a_real_browser_and_its_colours_are_the_csvs() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    let assignment = assignment(dir);
    class(dir);
    let out = raylab(&["grade", &assignment, "class", "-o", "report"], dir);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let report = dir.join("report");
    let csv = std::fs::read_to_string(report.join("grades.csv")).unwrap();

    let index = probe(&report, "index.html");
    assert_loaded_and_inert(&index, "index.html");
    // The class table's links: each student's page, the hostile id shown as text.
    let links: Vec<(String, String)> = index
        .iter()
        .filter_map(|l| l.strip_prefix("link "))
        .map(|l| {
            let (href, text) = l.split_once(' ').unwrap();
            (href.to_string(), text.to_string())
        })
        .collect();
    let page_of = |id: &str| {
        let found = links.iter().find(|(_, text)| text == id);
        found
            .unwrap_or_else(|| panic!("no link shows {id:?}: {links:?}"))
            .0
            .clone()
    };
    for id in [HOSTILE, "bob"] {
        let page = page_of(id);
        let lines = probe(&report, &page);
        assert_loaded_and_inert(&lines, &page);
        if id == "bob" {
            assert_frames_on_pixels(&lines, &page);
        }
    }

    // Sorted by a click on the total's head: the CSV's totals, smallest first.
    let sorted: Vec<f64> = index
        .iter()
        .find_map(|l| l.strip_prefix("sorted "))
        .expect("the table was sorted")
        .split(' ')
        .map(|t| t.parse().unwrap())
        .collect();
    let mut totals: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
        .collect();
    totals.sort_by(f64::total_cmp);
    assert_eq!(sorted, totals, "the totals as sorted by a click");

    // The screenshot of the class table: each scene's cell is the pass colour where the CSV
    // gives points, else the fail colour.
    let shot = dir.join("index.png");
    let out = chromium(&[
        &format!("--screenshot={}", shot.display()),
        &format!("file://{}", report.join("index.html").display()),
    ]);
    let image = image::open(&shot)
        .unwrap_or_else(|e| panic!("no screenshot ({e}): {}", stderr(&out)))
        .to_rgb8();
    assert_eq!(image.dimensions(), WINDOW, "the screenshot's size");
    let cells: Vec<[u32; 6]> = index
        .iter()
        .filter_map(|l| l.strip_prefix("cell "))
        .map(|l| {
            let numbers: Vec<u32> = l.split(' ').map(|n| n.parse().unwrap()).collect();
            numbers.try_into().unwrap()
        })
        .collect();
    let (mut passes, mut fails) = (0, 0);
    for (_, id) in &links {
        let csv_row = row(&csv, &raylab::grade::report::csv_field(id));
        let table_row = 1 + links.iter().position(|(_, text)| text == id).unwrap() as u32;
        for scene in 0..2u32 {
            let [_, _, left, top, width, height] = *cells
                .iter()
                .find(|c| c[0] == table_row && c[1] == 1 + scene)
                .unwrap_or_else(|| panic!("no cell for {id}, scene {scene}: {cells:?}"));
            assert!(
                left + width <= WINDOW.0 && top + height <= WINDOW.1,
                "{id}: off the page"
            );
            let points: f64 = csv_row[2 + 2 * scene as usize].parse().unwrap();
            let expected = if points > 0.0 { PASS_COLOR } else { FAIL_COLOR };
            if points > 0.0 {
                passes += 1;
            } else {
                fails += 1;
            }
            // Inside the cell's padding, clear of its border and its text.
            let shown = image.get_pixel(left + 3, top + 3).0;
            let apart = shown
                .iter()
                .zip(levels(expected))
                .map(|(a, b)| a.abs_diff(b))
                .max()
                .unwrap();
            assert!(
                apart <= 2,
                "{id}, scene {scene}: the cell is {shown:?}, the CSV's {points} points call for \
                 {expected}"
            );
        }
    }
    assert!(passes > 0 && fails > 0, "{passes} passes, {fails} fails");
}
