//! The viewer and the files beside it: a broken scene file keeps the last good scene, a saved one
//! is read again, the camera flags and camera file hold on every load, edited materials are saved
//! into the scene file with its comments, and stored views go into a views file.

use std::path::Path;

use glam::Vec3;
use raylab::camera::CameraSpec;
use raylab::formats::toml::load_scene;

use crate::harness::{
    ball_scene, cpu_render, image_rect, mismatches, printed_camera, run_to_screenshot,
    run_viewer_watching,
};

#[test]
fn a_broken_scene_file_shows_its_error_and_keeps_the_last_good_scene() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.toml");
    let broken = dir.path().join("broken.toml");
    std::fs::write(&good, ball_scene([0.0, 2.0, 6.0])).unwrap();
    std::fs::write(&broken, "[camera]\neye = [0, 1]\n").unwrap();
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            good.to_str().unwrap(),
            "--size",
            "64",
            "--samples",
            "1",
            "--script",
            &format!("wait; open {}; wait", broken.display()),
        ],
    );
    // The loader's message, located: file:line:column.
    let located = format!("{}:2:", broken.display());
    assert!(run.stderr.contains(&located), "{}", run.stderr);
    let scene = load_scene(&good).unwrap();
    let expected = cpu_render(&scene, 64, scene.camera.spec);
    assert_eq!(mismatches(&shot, image_rect(&run.stdout), 64, &expected), 0);
}

#[test]
fn saving_the_watched_scene_file_renders_it_again() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ball.toml");
    std::fs::write(&path, ball_scene([0.0, 2.0, 6.0])).unwrap();
    let shot = dir.path().join("shot.png");
    let moved = [3.0, 3.0, 4.0];
    let (edit_path, temp) = (path.clone(), dir.path().join(".ball.toml.new"));
    let mut edited = false;
    // Once the first view is done, save the file with the camera moved, as an editor would
    // (write a new file, rename it over the old one).
    let on_line = move |line: &str, _| {
        if !edited && line.contains("block size 1 at") {
            edited = true;
            std::fs::write(&temp, ball_scene(moved)).unwrap();
            std::fs::rename(&temp, &edit_path).unwrap();
        }
    };
    let run = run_viewer_watching(
        &[
            path.to_str().unwrap(),
            "--size",
            "64",
            "--stats",
            "--exit-when-done",
            "--samples",
            "1",
            "--script",
            "wait; wait-load 2; wait; print-camera",
            "--screenshot",
            shot.to_str().unwrap(),
        ],
        &[],
        on_line,
    );
    run.assert_success();
    assert_eq!(printed_camera(&run.stdout).eye, Vec3::from(moved));
    let scene = load_scene(&path).unwrap();
    assert_eq!(scene.camera.spec.eye, Vec3::from(moved));
    let expected = cpu_render(&scene, 64, scene.camera.spec);
    assert_eq!(mismatches(&shot, image_rect(&run.stdout), 64, &expected), 0);
}

#[test]
fn the_camera_flags_and_camera_file_hold_on_every_load() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ball.toml");
    std::fs::write(&path, ball_scene([0.0, 2.0, 6.0])).unwrap();
    // The camera file moves the eye; the flag narrows the view.
    std::fs::write(
        dir.path().join("ball.camera.toml"),
        "[camera]\neye = [2.0, 2.0, 5.0]\n",
    )
    .unwrap();
    let (edit_path, temp) = (path.clone(), dir.path().join(".ball.toml.new"));
    let mut edited = false;
    // Once the first view is done, the scene file's camera changes (its look-at point, which
    // neither the camera file nor the flags give).
    let on_line = move |line: &str, _| {
        if !edited && line.contains("block size 1 at") {
            edited = true;
            let moved =
                ball_scene([0.0, 2.0, 6.0]).replace("look_at = [0, 1, 0]", "look_at = [0, 0, 0]");
            std::fs::write(&temp, moved).unwrap();
            std::fs::rename(&temp, &edit_path).unwrap();
        }
    };
    let run = run_viewer_watching(
        &[
            path.to_str().unwrap(),
            "--view-angle",
            "30",
            "--stats",
            "--exit-when-done",
            "--script",
            "wait; wait-load 2; wait; print-camera",
        ],
        &[],
        on_line,
    );
    run.assert_success();
    // The scene's new look-at point, the file's eye and the flag's view angle.
    let reloaded = printed_camera(&run.stdout);
    assert_eq!(reloaded.eye, Vec3::new(2.0, 2.0, 5.0));
    assert_eq!((reloaded.look_at, reloaded.view_angle), (Vec3::ZERO, 30.0));
}

#[test]
fn a_material_edited_in_the_viewer_changes_the_image_and_saves_into_the_file_with_its_comments() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ball.toml");
    let original = format!(
        "# A ball for the materials test.\n{}",
        ball_scene([0.0, 2.0, 6.0])
    )
    .replace(
        "[materials.red]\ncolor = [0.8, 0.2, 0.1]\n",
        "[materials.red]  # the ball\ncolor = [0.8, 0.2, 0.1]  # brick red\n",
    );
    std::fs::write(&path, &original).unwrap();
    let before = load_scene(&path).unwrap();
    // After the save, a few idle frames give the watcher time to report the viewer's own write
    // (which must not reload the file) before the viewer exits.
    let idle_frames = "; close-inspector".repeat(30);
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            path.to_str().unwrap(),
            "--stats",
            "--size",
            "64",
            "--samples",
            "1",
            "--script",
            &format!("wait; material red color 0.1 0.3 0.9; wait; save-scene{idle_frames}; wait"),
        ],
    );
    assert!(
        run.stdout.contains("saved the scene's materials"),
        "{}",
        run.stdout
    );
    // The file has the new colour in place of the old, and every comment.
    let saved = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        saved,
        original.replace(
            "color = [0.8, 0.2, 0.1]  # brick red",
            "color = [0.1, 0.3, 0.9]  # brick red"
        )
    );
    // The window shows the edited material: not the scene as it was, but the saved file.
    let rect = image_rect(&run.stdout);
    let old_image = cpu_render(&before, 64, before.camera.spec);
    assert!(mismatches(&shot, rect, 64, &old_image) > 100);
    let after = load_scene(&path).unwrap();
    let expected = cpu_render(&after, 64, after.camera.spec);
    assert_eq!(mismatches(&shot, rect, 64, &expected), 0);
    // The scene was loaded once: the viewer did not reload what it wrote itself.
    assert_eq!(
        run.stderr.matches("stats: loaded").count(),
        1,
        "{}",
        run.stderr
    );
}

#[test]
fn a_stored_view_is_recalled_saved_beside_the_scene_and_a_turntable_preview_ends_on_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ball.toml");
    std::fs::write(&path, ball_scene([0.0, 2.0, 6.0])).unwrap();
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            path.to_str().unwrap(),
            "--size",
            "64",
            "--block-size",
            "8",
            "--samples",
            "1",
            "--script",
            "bookmark 1; orbit 40 0; wait; print-camera; recall 1; wait; turntable 4; wait",
        ],
    );
    let scene = load_scene(&path).unwrap();
    let moved = printed_camera(&run.stdout);
    assert!(
        (moved.eye - scene.camera.spec.eye).length() > 1.0,
        "the orbit moved the camera"
    );
    assert!(run.stdout.contains("view 1 stored in"), "{}", run.stdout);
    // Back on the first view: the window shows it as the CPU renders it.
    let expected = cpu_render(&scene, 64, scene.camera.spec);
    let rect = image_rect(&run.stdout);
    assert_eq!(mismatches(&shot, rect, 64, &expected), 0);
    // The view went into ball.views.toml beside the scene, as the camera it was.
    let text = std::fs::read_to_string(dir.path().join("ball.views.toml")).unwrap();
    let views =
        raylab::formats::toml::parse_views(&text, Path::new("v"), CameraSpec::default()).unwrap();
    assert_eq!(views.get(1), Some(scene.camera.spec));
}
