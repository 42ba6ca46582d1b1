//! The image and the window's size: letterboxed in a resized window, fitted to the view area
//! whatever the scene's size and rendered again when the window changes, and drawn in physical
//! pixels on a HiDPI display.

use std::path::Path;

use raylab::color::to_srgb8;
use raylab::formats::toml::default_scene;
use raylab::progressive;
use raylab::render::assemble;

use crate::harness::{
    Run, cpu_render, differing, image_rect, mismatches, run_to_screenshot, run_viewer_watching,
    shown_pixels,
};

/// The default scene rendered on the CPU at `width × height` with its own camera, as sRGB bytes.
fn cpu_render_sized(width: u32, height: u32) -> Vec<u8> {
    let mut scene = default_scene().unwrap();
    scene.settings.width = width;
    scene.settings.height = height;
    let (pixels, _) = progressive::render_image(&assemble(scene).unwrap().tracer());
    to_srgb8(&pixels)
}

/// The pixels of the image shown 1:1 at `rect` in the screenshot that differ (by more than 2
/// levels) from `expected`, an image of the rectangle's size.
fn mismatches_one_to_one(screenshot: &Path, rect: (f32, f32, f32, f32), expected: &[u8]) -> usize {
    differing(
        &shown_pixels(screenshot, rect, (rect.2 as u32, rect.3 as u32)),
        expected,
    )
}

/// Where the fitted image sits in a window `window_width` wide: it must fill the view area (from
/// the side panel to the right edge, from the top to the status line) at its own size.
fn assert_fills_the_view_area(run: &Run, window_width: f32) -> (f32, f32, f32, f32) {
    let (x, y, w, h) = image_rect(&run.stdout);
    assert!(x > 0.0, "the side panel is on the left: {x}");
    assert_eq!(
        (y, x + w),
        (0.0, window_width),
        "no bars: {:?}",
        (x, y, w, h)
    );
    let rendered = format!("block size 1 at {w}×{h}");
    assert!(run.stderr.contains(&rendered), "{rendered}: {}", run.stderr);
    (x, y, w, h)
}

#[test]
fn a_resized_window_letterboxes_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--window",
            "700x500",
            "--samples",
            "1",
            "--script",
            "wait; resize 480 640; wait",
        ],
    );
    let image = image::open(&shot).unwrap();
    assert_eq!(
        (image.width(), image.height()),
        (480, 640),
        "the screenshot has the new size"
    );
    // Narrower than tall beside the panel: bars above and below, the image square.
    let (x, y, w, h) = image_rect(&run.stdout);
    assert_eq!(w, h);
    assert!(y > 0.0 && x + w <= 480.0, "{:?}", (x, y, w, h));
    let scene = default_scene().unwrap();
    let expected = cpu_render(&scene, size, scene.camera.spec);
    assert_eq!(mismatches(&shot, (x, y, w, h), size, &expected), 0);
}

#[test]
fn a_hidpi_window_draws_in_physical_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("hidpi.png");
    let size = 64;
    let run = run_viewer_watching(
        &[
            "--size",
            &size.to_string(),
            "--window",
            "560x360",
            "--samples",
            "1",
            "--exit-when-done",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
        &[("WINIT_X11_SCALE_FACTOR", "2")],
        |_, _| {},
    );
    run.assert_success();
    let image = image::open(&shot).unwrap();
    assert_eq!(
        (image.width(), image.height()),
        (1120, 720),
        "twice the logical size"
    );
    let scene = default_scene().unwrap();
    let expected = cpu_render(&scene, size, scene.camera.spec);
    let rect = image_rect(&run.stdout);
    assert!(
        rect.2 > 2.0 * size as f32,
        "the image fills the physical pixels: {rect:?}"
    );
    assert_eq!(mismatches(&shot, rect, size, &expected), 0);
}

#[test]
fn the_viewer_starts_fitted_to_the_window_whatever_the_scenes_size() {
    let dir = tempfile::tempdir().unwrap();
    // The default scene says 640×480; the window's view area is another shape.
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &["--window", "700x500", "--samples", "1", "--stats"],
    );
    let rect = assert_fills_the_view_area(&run, 700.0);
    assert!(
        rect.3 > 400.0,
        "all the height but the status line: {rect:?}"
    );
    // Shown 1:1, every pixel of the area the image's.
    let expected = cpu_render_sized(rect.2 as u32, rect.3 as u32);
    assert_eq!(mismatches_one_to_one(&shot, rect, &expected), 0);
}

#[test]
fn a_scripted_resize_renders_again_at_the_new_size() {
    let dir = tempfile::tempdir().unwrap();
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--window",
            "700x500",
            "--samples",
            "1",
            "--stats",
            "--script",
            "wait; resize 560 400; wait",
        ],
    );
    let image = image::open(&shot).unwrap();
    assert_eq!((image.width(), image.height()), (560, 400));
    let rect = assert_fills_the_view_area(&run, 560.0);
    // Refined to block size 1 at the first size, then again at the new one.
    let sizes: Vec<&str> = run
        .stderr
        .lines()
        .filter_map(|l| l.split("block size 1 at ").nth(1))
        .map(|rest| rest.split_whitespace().next().unwrap())
        .collect();
    assert!(sizes.len() >= 2, "{}", run.stderr);
    assert_ne!(sizes[0], sizes[sizes.len() - 1], "{sizes:?}");
    let expected = cpu_render_sized(rect.2 as u32, rect.3 as u32);
    assert_eq!(mismatches_one_to_one(&shot, rect, &expected), 0);
}

#[test]
fn a_fitted_image_on_a_hidpi_window_has_its_physical_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("hidpi_fit.png");
    let run = run_viewer_watching(
        &[
            "--window",
            "560x360",
            "--samples",
            "1",
            "--stats",
            "--exit-when-done",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
        &[("WINIT_X11_SCALE_FACTOR", "2")],
        |_, _| {},
    );
    run.assert_success();
    // Rendered at the view area's physical size (twice its logical one), shown 1:1.
    let rect = assert_fills_the_view_area(&run, 1120.0);
    let expected = cpu_render_sized(rect.2 as u32, rect.3 as u32);
    assert_eq!(mismatches_one_to_one(&shot, rect, &expected), 0);
}

#[test]
fn at_1280_by_800_the_side_panel_shows_that_it_scrolls() {
    // The screen's size, the default scene's panel longer than it: a scroll bar must be drawn
    // without the pointer over it, its handle shorter than its track.
    let dir = tempfile::tempdir().unwrap();
    let (run, shot) = run_to_screenshot(dir.path(), &["--window", "1280x800", "--samples", "1"]);
    let (x, _, _, height) = image_rect(&run.stdout);
    let shot = image::open(&shot).unwrap().to_rgb8();
    let rows = 10..(height as u32).saturating_sub(10);
    let scroll_bar = (x as u32 - 30..x as u32).find(|&column| {
        let mut colours: Vec<[u8; 3]> = rows.clone().map(|y| shot.get_pixel(column, y).0).collect();
        colours.sort_unstable();
        let mut runs: Vec<usize> = colours
            .chunk_by(|a, b| a == b)
            .map(<[[u8; 3]]>::len)
            .collect();
        runs.sort_unstable_by(|a, b| b.cmp(a));
        // A handle and a track, each a good part of the column, and little else (their edges).
        let tenth = colours.len() / 10;
        runs.len() <= 6 && runs.len() >= 2 && runs[1] >= tenth && runs[0] + runs[1] >= 9 * tenth
    });
    assert!(
        scroll_bar.is_some(),
        "no scroll bar in the side panel's right edge (x {} to {x})",
        x - 30.0
    );
}
