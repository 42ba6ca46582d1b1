//! The viewer's tools, each checked against the CPU: a clicked pixel's ray tree in the panel and
//! over the image, debug views, exposure and tone curves (shown and saved alike), a snapshot
//! beside the live image, and an image compared with (`--compare`) beside its difference.

use std::path::Path;

use raylab::color::{srgb8, to_srgb8};
use raylab::formats::toml::default_scene;
use raylab::inspect::{DebugView, RayTree, heat, trace_ray_tree};
use raylab::progressive;
use raylab::render::Assembled;
use raylab::whitted::RayKind;

use crate::harness::{
    Run, cpu_render, cpu_render_view, differing, image_rect, mismatches, run_to_screenshot,
    shown_pixels, sized,
};

/// The image rows the split view's labels cover.
const LABEL_ROWS: u32 = 4;

/// The screenshot's pixels inside the image area that differ (by more than 2 levels) from the
/// CPU's image shown there at the same scale (nearest pixel), in window coordinates.
fn differing_window_pixels(
    screenshot: &Path,
    rect: (f32, f32, f32, f32),
    size: u32,
    expected: &[u8],
) -> Vec<(u32, u32)> {
    let shot = image::open(screenshot).unwrap().to_rgb8();
    let (x0, y0, w, h) = rect;
    let mut differing = Vec::new();
    for sy in y0 as u32..(y0 + h) as u32 {
        for sx in x0 as u32..(x0 + w) as u32 {
            let i = (((sx as f32 + 0.5 - x0) / w * size as f32) as u32).min(size - 1);
            let j = (((sy as f32 + 0.5 - y0) / h * size as f32) as u32).min(size - 1);
            let k = ((j * size + i) * 3) as usize;
            let got = shot.get_pixel(sx, sy).0;
            if (0..3).any(|c| got[c].abs_diff(expected[k + c]) > 2) {
                differing.push((sx, sy));
            }
        }
    }
    differing
}

/// The pixel of the default scene at `size × size` with the largest ray tree (the first of
/// them, row by row), and that tree.
fn busiest_pixel(assembled: &Assembled, size: u32) -> RayTree {
    let tracer = assembled.tracer();
    let mut best: Option<RayTree> = None;
    for y in 0..size {
        for x in 0..size {
            let tree = trace_ray_tree(&tracer, x, y);
            if best
                .as_ref()
                .is_none_or(|b| tree.nodes.len() > b.nodes.len())
            {
                best = Some(tree);
            }
        }
    }
    best.unwrap()
}

/// Checks that the viewer printed (`print-tree`) the headings of `tree`, in the tree's order, each
/// indented by its depth.
fn assert_printed_tree(run: &Run, tree: &RayTree) {
    let printed: Vec<&str> = run
        .stdout
        .lines()
        .filter_map(|l| l.strip_prefix("tree: "))
        .filter(|l| !l.starts_with("your "))
        .collect();
    assert_eq!(
        printed.len(),
        tree.nodes.len(),
        "stdout: {}\nstderr: {}",
        run.stdout,
        run.stderr
    );
    let mut order = vec![0];
    let mut preorder = Vec::new();
    while let Some(i) = order.pop() {
        preorder.push(i);
        order.extend(tree.nodes[i].children.iter().rev());
    }
    for (line, &i) in printed.iter().zip(&preorder) {
        let node = &tree.nodes[i];
        let indent = line.len() - line.trim_start().len();
        assert_eq!(indent, 2 * (node.depth as usize - 1), "{line}");
        let kind = match node.kind {
            RayKind::Eye => "eye",
            RayKind::Reflected => "reflected",
            RayKind::Transmitted => "transmitted",
        };
        assert!(line.trim_start().starts_with(kind), "{line}: {kind}");
        assert!(line.contains(&format!("depth {}", node.depth)), "{line}");
        match &node.hit {
            Some(hit) => assert!(line.contains(&hit.label), "{line}: {}", hit.label),
            None => assert!(line.contains("miss"), "{line}"),
        }
    }
}

/// The default scene rendered on the CPU at `size × size`, as linear colours.
fn cpu_render_linear(size: u32) -> Vec<raylab::color::Color> {
    let scene = default_scene().unwrap();
    let assembled = sized(&scene, size, scene.camera.spec);
    progressive::render_image_with(&assembled.tracer(), &DebugView::Shaded).0
}

#[test]
fn a_click_on_a_pixel_shows_its_ray_tree_and_draws_it_over_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let scene = default_scene().unwrap();
    let sized_scene = sized(&scene, size, scene.camera.spec);
    let tree = busiest_pixel(&sized_scene, size);
    assert!(tree.nodes.len() >= 3, "a pixel with secondary rays");
    let (x, y) = tree.pixel;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--window",
            "1000x600",
            "--samples",
            "1",
            "--script",
            &format!("wait; click {x} {y}; wait; print-tree"),
        ],
    );
    assert_printed_tree(&run, &tree);
    // The overlay: the image differs from the CPU's where the rays and the pixel's frame are
    // drawn, and around the picked pixel.
    let rect = image_rect(&run.stdout);
    let expected = cpu_render(&scene, size, scene.camera.spec);
    let differing = differing_window_pixels(&shot, rect, size, &expected);
    assert!(!differing.is_empty(), "the overlay is drawn");
    let scale = rect.2 / size as f32;
    let centre = (
        rect.0 + (x as f32 + 0.5) * scale,
        rect.1 + (y as f32 + 0.5) * scale,
    );
    let near_pixel = |&(sx, sy): &(u32, u32)| {
        (sx as f32 - centre.0).abs() <= scale + 2.0 && (sy as f32 - centre.1).abs() <= scale + 2.0
    };
    assert!(
        differing.iter().any(near_pixel),
        "the picked pixel is framed"
    );
    assert!(
        differing.len() < (rect.2 * rect.3 / 4.0) as usize,
        "the rest of the image is as rendered: {} pixels differ",
        differing.len()
    );
}

#[test]
fn a_click_at_the_default_window_shows_the_point_clicked_and_the_viewer_settles() {
    // As a newcomer meets it: no --size, no --window, the default sampling; the run must end
    // (within the harness's time limit) with the tree of the pixel clicked.
    let dir = tempfile::tempdir().unwrap();
    let (x, y) = (400, 330);
    let script = format!("wait; click {x} {y}; wait; print-tree");
    let (run, _) = run_to_screenshot(dir.path(), &["--stats", "--script", &script]);
    let picked = format!("ray tree of pixel ({x}, {y})");
    let after_click = run.stderr.split_once(&picked).map(|(_, rest)| rest);
    let after_click = after_click.unwrap_or_else(|| panic!("{picked}: {}", run.stderr));
    assert!(
        !after_click.contains("stats: first image ("),
        "opening the inspector rendered the image again: {}",
        run.stderr
    );
    // The image it was clicked in: the last size rendered at block size 1 before the click.
    let before_click = run.stderr.split_once(&picked).unwrap().0;
    let size = before_click
        .rsplit("block size 1 at ")
        .next()
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|size| size.split_once('×'))
        .map(|(w, h)| (w.parse::<u32>().unwrap(), h.parse::<u32>().unwrap()))
        .unwrap_or_else(|| panic!("no size rendered before the click: {}", run.stderr));
    let mut scene = default_scene().unwrap();
    (scene.settings.width, scene.settings.height) = size;
    let assembled = raylab::render::assemble(scene).unwrap();
    let tree = trace_ray_tree(&assembled.tracer(), x, y);
    assert_printed_tree(&run, &tree);
}

#[test]
fn a_debug_view_chosen_in_the_viewer_renders_as_on_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--samples",
            "1",
            "--view",
            "depth",
            "--stats",
            "--script",
            "wait; view normals; wait",
        ],
    );
    // Refined to block size 1 in the depth view, then again in the normals view.
    assert!(
        run.stderr.matches("block size 1 at").count() >= 2,
        "{}",
        run.stderr
    );
    let scene = default_scene().unwrap();
    let rect = image_rect(&run.stdout);
    let normals = cpu_render_view(&scene, size, scene.camera.spec, DebugView::Normals);
    assert_eq!(mismatches(&shot, rect, size, &normals), 0);
    let shaded = cpu_render(&scene, size, scene.camera.spec);
    assert!(mismatches(&shot, rect, size, &shaded) > (size * size / 4) as usize);
}

#[test]
fn exposure_and_tone_curve_show_in_the_window_and_save_as_shown() {
    use raylab::tone::{Tone, ToneCurve};
    let dir = tempfile::tempdir().unwrap();
    let saved = dir.path().join("saved.png");
    let size = 64;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--save",
            saved.to_str().unwrap(),
            "--samples",
            "1",
            "--script",
            "exposure 1.5; tonemap filmic; wait; save",
        ],
    );
    let rect = image_rect(&run.stdout);
    let saved_bytes = image::open(&saved).unwrap().to_rgb8().into_raw();
    assert_eq!(saved_bytes.len(), (size * size * 3) as usize);
    // What is saved is what the window shows.
    assert_eq!(mismatches(&shot, rect, size, &saved_bytes), 0);
    // And it is the library's tone mapping of the traced image.
    let linear = cpu_render_linear(size);
    let tone = Tone::new(1.5, ToneCurve::Filmic).unwrap();
    assert_eq!(mismatches(&shot, rect, size, &tone.to_srgb8(&linear)), 0);
    let plain = to_srgb8(&linear);
    assert!(mismatches(&shot, rect, size, &plain) > (size * size / 4) as usize);
}

#[test]
fn a_snapshot_shows_left_of_the_divider_and_the_live_image_right_of_it() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--samples",
            "1",
            "--script",
            "wait; snapshot; view normals; divider 0.5; wait",
        ],
    );
    let scene = default_scene().unwrap();
    let shaded = cpu_render(&scene, size, scene.camera.spec);
    let normals = cpu_render_view(&scene, size, scene.camera.spec, DebugView::Normals);
    // Left half the snapshot (shaded), right half the live normals; the top rows hold the
    // labels, the divider runs between the halves' pixel centres.
    let half = (size / 2) as usize;
    let split: Vec<u8> = shaded
        .chunks_exact(3)
        .zip(normals.chunks_exact(3))
        .enumerate()
        .flat_map(|(i, (s, n))| if i % size as usize >= half { n } else { s }.to_vec())
        .collect();
    let rect = image_rect(&run.stdout);
    let shown = shown_pixels(&shot, rect, (size, size));
    let below_labels = (LABEL_ROWS * size * 3) as usize;
    assert_eq!(
        differing(&shown[below_labels..], &split[below_labels..]),
        0,
        "the split view shows snapshot | live"
    );
    // Both halves are really there: the picture is neither all shaded nor all normals.
    assert!(mismatches(&shot, rect, size, &shaded) > (size * size / 8) as usize);
    assert!(mismatches(&shot, rect, size, &normals) > (size * size / 8) as usize);
}

#[test]
fn an_image_to_compare_shows_left_of_the_divider_its_difference_right_and_beside_a_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64u32;
    let scene = default_scene().unwrap();
    let shaded = cpu_render(&scene, size, scene.camera.spec);
    // "Their" image: raylab's with a black square right of the middle.
    let mut theirs = shaded.clone();
    for y in 20..40 {
        for x in 36..56 {
            let k = ((y * size + x) * 3) as usize;
            theirs[k..k + 3].copy_from_slice(&[0, 0, 0]);
        }
    }
    let path = dir.path().join("theirs.png");
    image::RgbImage::from_raw(size, size, theirs.clone())
        .unwrap()
        .save(&path)
        .unwrap();
    let path = path.to_str().unwrap();
    // No --samples: an image is compared with raylab's at one sample a pixel unless asked.
    let compare_with = |script: &str| {
        let args = ["--compare", path, "--script", script];
        run_to_screenshot(dir.path(), &args)
    };
    let (run, shot) = compare_with("wait; compare diff; divider 0.5; wait");
    // Left half their image; right half the heat map of each pixel's largest channel
    // difference from it, 32 levels at the top of the ramp (dark where equal).
    let heat_bytes = |levels: u8| heat(f32::from(levels) / 32.0).to_array().map(srgb8);
    let half = (size / 2) as usize;
    let expected: Vec<u8> = shaded
        .chunks_exact(3)
        .zip(theirs.chunks_exact(3))
        .enumerate()
        .flat_map(|(i, (ours, theirs))| {
            if i % size as usize >= half {
                let d = (0..3).map(|c| ours[c].abs_diff(theirs[c])).max().unwrap();
                heat_bytes(d)
            } else {
                [theirs[0], theirs[1], theirs[2]]
            }
        })
        .collect();
    let shown = shown_pixels(&shot, image_rect(&run.stdout), (size, size));
    let below_labels = (LABEL_ROWS * size * 3) as usize;
    assert_eq!(
        differing(&shown[below_labels..], &expected[below_labels..]),
        0,
        "their image | the difference"
    );
    // The square shows bright on the right, the rest dark.
    let at = |i: u32, j: u32| {
        let k = ((j * size + i) * 3) as usize;
        [shown[k], shown[k + 1], shown[k + 2]]
    };
    assert!(at(45, 30).iter().map(|&c| u32::from(c)).sum::<u32>() > 300);
    assert_eq!(at(45, 10), heat_bytes(0));

    // A picked pixel in the square: both colours, and why they differ.
    let (run, _) = compare_with("wait; pick 45 30; wait; print-tree");
    // Beside the inspector the image is shown no smaller than it is.
    let (_, _, width, height) = image_rect(&run.stdout);
    assert!(
        width >= size as f32 && height >= size as f32,
        "{width}×{height}"
    );
    let k = ((30 * size + 45) * 3) as usize;
    let colours = format!(
        "tree: your image (0, 0, 0), raylab ({}, {}, {})",
        shaded[k],
        shaded[k + 1],
        shaded[k + 2]
    );
    assert!(run.stdout.contains(&colours), "{colours}: {}", run.stdout);
    assert!(
        run.stdout.contains("tree: your pixel is darker by"),
        "{}",
        run.stdout
    );
}

#[test]
fn a_compared_image_of_a_students_size_stays_whole_beside_the_inspector() {
    // At the default window, a 320×240 image (a size students hand in) with a pixel picked: the
    // inspector's panel must leave it at least its own size.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mine.png");
    image::RgbImage::from_fn(320, 240, |x, y| image::Rgb([x as u8, y as u8, 90]))
        .save(&path)
        .unwrap();
    let args = [
        "--compare",
        path.to_str().unwrap(),
        "--script",
        "wait; pick 150 150; wait; print-tree",
    ];
    let (run, _) = run_to_screenshot(dir.path(), &args);
    assert!(run.stdout.contains("tree: your image ("), "{}", run.stdout);
    let (_, _, width, height) = image_rect(&run.stdout);
    assert!(
        width >= 320.0 && height >= 240.0,
        "shown at {width}×{height}"
    );
}
