//! What the viewer shows for the scene and flags it is started with, as the CPU renders them: the
//! default scene, a scene in the format given whatever its file's name, and the size and
//! minimum-weight overrides that `render` takes too.

use raylab::formats::nff::NffLighting;
use raylab::formats::toml::{default_scene, load_scene};
use raylab::formats::{SceneFormat, load_any_as};

use crate::harness::{ball_scene, cpu_render, image_rect, mismatches, run_to_screenshot};

#[test]
fn the_window_shows_the_default_scene_as_the_cpu_renders_it() {
    let dir = tempfile::tempdir().unwrap();
    let size = 96;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "view",
            "--size",
            &size.to_string(),
            "--samples",
            "1",
            "--window",
            "700x500",
            "--stats",
        ],
    );
    assert!(
        run.stderr.contains("block size 1 at 96×96"),
        "{}",
        run.stderr
    );
    let scene = default_scene().unwrap();
    let expected = cpu_render(&scene, size, scene.camera.spec);
    let rect = image_rect(&run.stdout);
    assert_eq!(mismatches(&shot, rect, size, &expected), 0);
    // Outside the image: the letterbox bars and the panels, not the image.
    let shot_image = image::open(&shot).unwrap().to_rgb8();
    assert_eq!(shot_image.dimensions(), (700, 500));
}

#[test]
fn the_viewer_reads_a_scene_in_the_format_given_whatever_its_name() {
    // An SDL scene with a texture and a background image, in a file whose name says nothing.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.txt");
    let backdrop =
        image::RgbImage::from_fn(4, 2, |x, y| image::Rgb([60 * x as u8, 100, 90 * y as u8]));
    backdrop.save(dir.path().join("sky.bmp")).unwrap();
    std::fs::write(
        &path,
        "light 3 5 4 1 1 1 backgroundImage sky.bmp diffuse .9 .3 .2 texture -1 sphere",
    )
    .unwrap();
    let size = 64;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            path.to_str().unwrap(),
            "--samples",
            "1",
            "--format",
            "sdl",
            "--size",
            &size.to_string(),
            "--window",
            "600x400",
        ],
    );
    let name = path.to_str().unwrap();
    let scene = load_any_as(name, NffLighting::default(), Some(SceneFormat::Sdl)).unwrap();
    let expected = cpu_render(&scene, size, scene.camera.spec);
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &expected),
        0
    );
}

#[test]
fn the_viewer_takes_a_width_and_height_as_render_does() {
    let dir = tempfile::tempdir().unwrap();
    let (run, _) = run_to_screenshot(
        dir.path(),
        &["view", "--width", "72", "--height", "48", "--stats"],
    );
    assert!(
        run.stderr.contains("block size 1 at 72×48"),
        "{}",
        run.stderr
    );
    let (_, _, w, h) = image_rect(&run.stdout);
    assert!((w / h - 1.5).abs() < 0.02, "shown at {w}×{h}");
}

#[test]
fn the_viewer_takes_a_width_alone_and_a_min_weight_as_render_does() {
    let dir = tempfile::tempdir().unwrap();
    // A 96×64 scene whose floor reflects the ball: --width 64 alone makes it 64×64 (the file's
    // height stays), and --min-weight 0.5 cuts the floor's reflected rays (weight 0.4).
    let path = dir.path().join("mirror_floor.toml");
    let text = ball_scene([0.0, 2.0, 6.0])
        .replace("width = 64", "width = 96")
        .replace(
            "[[objects]]\ntype = \"plane\"\n",
            "[materials.mirror]\nreflectivity = 0.4\n\n\
             [[objects]]\ntype = \"plane\"\nmaterial = \"mirror\"\n",
        );
    std::fs::write(&path, text).unwrap();
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            path.to_str().unwrap(),
            "--width",
            "64",
            "--samples",
            "1",
            "--min-weight",
            "0.5",
            "--stats",
        ],
    );
    assert!(
        run.stderr.contains("block size 1 at 64×64"),
        "{}",
        run.stderr
    );
    let mut scene = load_scene(&path).unwrap();
    assert_eq!((scene.settings.width, scene.settings.height), (96, 64));
    let rect = image_rect(&run.stdout);
    let reflecting = cpu_render(&scene, 64, scene.camera.spec);
    scene.settings.min_weight = 0.5;
    let cut = cpu_render(&scene, 64, scene.camera.spec);
    assert_eq!(mismatches(&shot, rect, 64, &cut), 0);
    assert!(
        mismatches(&shot, rect, 64, &reflecting) > 64 * 64 / 10,
        "the floor's reflection is gone"
    );
}
