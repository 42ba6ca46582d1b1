//! The viewer as a person sees it: the real app in a real window under a virtual X display
//! (Xvfb) with Mesa's software Vulkan, told to exit once refinement is over and to save a
//! screenshot of its window; the image area is compared with a CPU render of the same scene and
//! camera. The tests start Xvfb themselves through `xvfb-run` (`scripts/test` installs it on
//! Debian), or use the display in `DISPLAY`. Without either they fail, saying what to install,
//! unless `RAYLAB_SKIP_WINDOW_TESTS=1` is set: then they pass, printing that they were skipped.

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::camera::{Camera, CameraSpec};
use raylab::color::to_srgb8;
use raylab::formats::nff::NffLighting;
use raylab::formats::toml::{default_scene, load_scene};
use raylab::formats::{SceneFormat, load_any_as};
use raylab::inspect::{DebugView, RayTree, trace_ray_tree};
use raylab::progressive;
use raylab::scene::Scene;
use raylab::whitted::{RayKind, Tracer};

/// One viewer at a time: they share two cores, and parallel `xvfb-run -a` can race for a display.
static DISPLAY_LOCK: Mutex<()> = Mutex::new(());
const TIMEOUT: Duration = Duration::from_secs(240);

struct Run {
    success: bool,
    stdout: String,
    stderr: String,
}

impl Run {
    fn assert_success(&self) {
        assert!(
            self.success,
            "stdout: {}\nstderr: {}",
            self.stdout, self.stderr
        );
    }
}

/// How to get a display: an existing one, or a virtual one through xvfb-run; `None` if neither.
fn display_wrapper() -> Option<Vec<String>> {
    let has = |program: &str| {
        Command::new("sh")
            .args(["-c", &format!("command -v {program}")])
            .stdout(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    };
    if has("xvfb-run") {
        Some(
            ["xvfb-run", "-a", "-s", "-screen 0 1280x800x24"]
                .map(String::from)
                .to_vec(),
        )
    } else if std::env::var_os("DISPLAY").is_some() {
        Some(Vec::new())
    } else {
        None
    }
}

/// Where no display can be had: fails saying how to get one, or, if the person running the tests
/// opted out with `RAYLAB_SKIP_WINDOW_TESTS=1`, says that the test is skipped. The note goes to
/// the real stderr, which the test runner does not capture, so that it shows among the results.
fn skip_or_fail_without_display() {
    let packages = "xvfb xauth mesa-vulkan-drivers libvulkan1 libxkbcommon-x11-0";
    if std::env::var("RAYLAB_SKIP_WINDOW_TESTS").is_ok_and(|v| v == "1") {
        let test = std::thread::current().name().unwrap_or("?").to_string();
        let _ = writeln!(
            std::io::stderr(),
            "SKIPPED {test}: no display, and RAYLAB_SKIP_WINDOW_TESTS=1"
        );
        return;
    }
    panic!(
        "the viewer's window tests need a display, and there is neither DISPLAY nor xvfb-run. \
         Install Xvfb and Mesa's software Vulkan (Debian: sudo apt-get install {packages}) and \
         run `cargo test --test viewer_window` (the tests start Xvfb themselves), or \
         `xvfb-run -a cargo test --test viewer_window`, or scripts/test, which installs them; \
         to skip these tests instead, set RAYLAB_SKIP_WINDOW_TESTS=1"
    );
}

/// Runs the viewer with `args` in a window; `None` if skipped for want of a display.
fn run_viewer(args: &[&str]) -> Option<Run> {
    run_viewer_watching(args, &[], |_, _| {})
}

/// [`run_viewer`] with `args`, until refinement is done, then a screenshot of the window saved
/// into `dir`: the run, which must have succeeded, and the screenshot's path.
fn run_to_screenshot(dir: &Path, args: &[&str]) -> Option<(Run, PathBuf)> {
    let shot = dir.join("window.png");
    let shot_arg = shot.to_str().unwrap().to_string();
    let mut all = args.to_vec();
    all.extend(["--exit-when-done", "--screenshot", &shot_arg]);
    let run = run_viewer(&all)?;
    run.assert_success();
    Some((run, shot))
}

/// [`run_viewer`] with environment variables `env`, handing each line the viewer prints on
/// stderr to `on_line` as it comes, with the process id of the command started (xvfb-run, or
/// the viewer itself).
fn run_viewer_watching(
    args: &[&str],
    env: &[(&str, &str)],
    mut on_line: impl FnMut(&str, u32) + Send + 'static,
) -> Option<Run> {
    let Some(wrapper) = display_wrapper() else {
        skip_or_fail_without_display();
        return None;
    };
    let _one_at_a_time = DISPLAY_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    let runtime_dir = tempfile::tempdir().unwrap();
    let bin = env!("CARGO_BIN_EXE_raylab");
    let mut command = match wrapper.split_first() {
        Some((program, rest)) => {
            let mut c = Command::new(program);
            c.args(rest).arg(bin);
            c
        }
        None => Command::new(bin),
    };
    let mut child = command
        .args(args)
        .env("XDG_RUNTIME_DIR", runtime_dir.path())
        .envs(env.iter().copied())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the viewer");
    let mut stdout = child.stdout.take().unwrap();
    let stderr = child.stderr.take().unwrap();
    let child_id = child.id();
    let out = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = stdout.read_to_string(&mut s);
        s
    });
    let err = std::thread::spawn(move || {
        let mut all = String::new();
        for line in BufReader::new(stderr).lines().map_while(Result::ok) {
            on_line(&line, child_id);
            all.push_str(&line);
            all.push('\n');
        }
        all
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            panic!("the viewer did not exit within {TIMEOUT:?}");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let run = Run {
        success: status.success(),
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    };
    assert!(!run.stderr.contains("panicked"), "{}", run.stderr);
    Some(run)
}

/// Where the screenshot put the image: `(x, y, width, height)` from the viewer's report.
fn image_rect(stdout: &str) -> (f32, f32, f32, f32) {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("screenshot "))
        .unwrap_or_else(|| panic!("no screenshot line in {stdout}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let after = |key: &str| {
        let i = words.iter().position(|w| *w == key).unwrap();
        words[i + 1]
    };
    let size = after("size");
    let (w, h) = size.split_once('×').unwrap();
    (
        after("x").parse().unwrap(),
        after("y").parse().unwrap(),
        w.parse().unwrap(),
        h.parse().unwrap(),
    )
}

/// The `[camera]` snippet printed by the viewer, as a camera spec.
fn printed_camera(stdout: &str) -> CameraSpec {
    let start = stdout.find("[camera]").expect("a printed camera");
    let table: toml::Table = stdout[start..]
        .lines()
        .take(6)
        .collect::<Vec<_>>()
        .join("\n")
        .parse()
        .unwrap();
    let c = table["camera"].as_table().unwrap();
    let number = |v: &toml::Value| v.as_float().unwrap() as f32;
    let vector = |key: &str| {
        let a = c[key].as_array().unwrap();
        Vec3::new(number(&a[0]), number(&a[1]), number(&a[2]))
    };
    CameraSpec {
        eye: vector("eye"),
        look_at: vector("look_at"),
        up: vector("up"),
        view_angle: number(&c["view_angle"]),
        near: number(&c["near"]),
    }
}

/// The scene at `size × size` seen with `camera`, and its BVH.
fn sized(scene: &Scene, size: u32, camera: CameraSpec) -> (Scene, Bvh) {
    let mut scene = scene.clone();
    scene.settings.width = size;
    scene.settings.height = size;
    scene.camera = Camera::new(camera).unwrap();
    let bvh = Bvh::build(&scene.geometry);
    (scene, bvh)
}

/// `view` of the scene rendered on the CPU at `size × size` with `camera`, as sRGB bytes.
fn cpu_render_view(scene: &Scene, size: u32, camera: CameraSpec, view: DebugView) -> Vec<u8> {
    let (scene, bvh) = sized(scene, size, camera);
    let (pixels, _) = progressive::render_image_with(&Tracer::new(&scene, &bvh), &view);
    to_srgb8(&pixels)
}

/// The scene rendered on the CPU at `size × size` with `camera`, as sRGB bytes.
fn cpu_render(scene: &Scene, size: u32, camera: CameraSpec) -> Vec<u8> {
    cpu_render_view(scene, size, camera, DebugView::Shaded)
}

/// The screenshot's image area at `rect` sampled at the centre of each of the `width × height`
/// image pixels, as sRGB bytes.
fn shown_pixels(
    screenshot: &Path,
    rect: (f32, f32, f32, f32),
    (width, height): (u32, u32),
) -> Vec<u8> {
    let shot = image::open(screenshot).unwrap().to_rgb8();
    let (x0, y0, w, h) = rect;
    assert!(
        w >= width as f32 && h >= height as f32,
        "the image is shown at least 1:1"
    );
    let at = |i: u32, j: u32| {
        let sx = (x0 + (i as f32 + 0.5) * w / width as f32) as u32;
        let sy = (y0 + (j as f32 + 0.5) * h / height as f32) as u32;
        shot.get_pixel(sx, sy).0
    };
    (0..height)
        .flat_map(|j| (0..width).map(move |i| (i, j)))
        .flat_map(|(i, j)| at(i, j))
        .collect()
}

/// How many pixels of two sRGB images differ by more than 2 levels in a channel.
fn differing(got: &[u8], expected: &[u8]) -> usize {
    assert_eq!(got.len(), expected.len(), "images of the same size");
    got.chunks_exact(3)
        .zip(expected.chunks_exact(3))
        .filter(|(g, e)| (0..3).any(|c| g[c].abs_diff(e[c]) > 2))
        .count()
}

/// Compares the screenshot's image area, sampled at the centre of each image pixel, with the
/// CPU's `size × size` image; returns the number of pixels that differ by more than 2 levels.
fn mismatches(screenshot: &Path, rect: (f32, f32, f32, f32), size: u32, expected: &[u8]) -> usize {
    differing(&shown_pixels(screenshot, rect, (size, size)), expected)
}

#[test]
fn the_window_shows_the_default_scene_as_the_cpu_renders_it() {
    let dir = tempfile::tempdir().unwrap();
    let size = 96;
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
    let name = path.to_str().unwrap();
    let scene = load_any_as(name, NffLighting::default(), Some(SceneFormat::Sdl)).unwrap();
    let expected = cpu_render(&scene, size, scene.camera.spec);
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &expected),
        0
    );
}

#[test]
fn caustics_sharpen_while_the_view_is_still_and_a_camera_move_reuses_the_photons() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("caustic.toml");
    std::fs::write(
        &path,
        "[render]\ncaustic_photons = 5000\n[camera]\neye = [0, 3, 6]\nlook_at = [0, 0.5, 0]\n\
         [[lights]]\ntype = \"spot\"\nposition = [-2, 5, -2]\ndirection = [2, -5, 2]\n\
         angle = 30\nintensity = 30\n[materials.glass]\ndiffuse = 0\ntransparency = 1\n\
         ior = 1.5\n[[objects]]\ntype = \"plane\"\nnormal = [0, 1, 0]\n[[objects]]\n\
         type = \"sphere\"\ncenter = [0, 1, 0]\nradius = 1\nmaterial = \"glass\"\n",
    )
    .unwrap();
    let Some((run, _)) = run_to_screenshot(
        dir.path(),
        &[
            path.to_str().unwrap(),
            "--size",
            "64",
            "--stats",
            "--script",
            "wait; orbit 20 0; wait",
        ],
    ) else {
        return;
    };
    let stats = &run.stderr;
    // The first view: a new map, then a round at a time up to 8 × 5000 photons.
    let (first, after_move) = stats
        .rsplit_once("stats: first image")
        .expect("two views were rendered");
    assert_eq!(
        first.matches("caustics: new map, 5000 photons").count(),
        1,
        "{stats}"
    );
    assert!(
        first.contains("caustics: sharpened, 40000 photons"),
        "{stats}"
    );
    assert!(!first.contains("45000 photons"), "{stats}");
    // The camera moved: the same photons serve, none are shot.
    assert!(!after_move.contains("caustics:"), "{stats}");
}

#[test]
fn the_viewer_takes_a_width_and_height_as_render_does() {
    let dir = tempfile::tempdir().unwrap();
    let Some((run, _)) = run_to_screenshot(
        dir.path(),
        &["view", "--width", "72", "--height", "48", "--stats"],
    ) else {
        return;
    };
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
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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

#[test]
fn a_scripted_camera_change_restarts_refinement_and_ends_on_the_new_view() {
    let dir = tempfile::tempdir().unwrap();
    let saved = dir.path().join("saved.png");
    let size = 80;
    let Some((run, shot)) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--samples",
            "1",
            "--block-size",
            "8",
            "--stats",
            "--script",
            "wait; orbit 40 15 4; dolly 1; wait; print-camera; save",
            "--save",
            saved.to_str().unwrap(),
        ],
    ) else {
        return;
    };
    let scene = default_scene().unwrap();
    let camera = printed_camera(&run.stdout);
    assert!(
        (camera.eye - scene.camera.spec.eye).length() > 0.5,
        "the camera moved"
    );
    assert_eq!(
        camera.look_at, scene.camera.spec.look_at,
        "orbit keeps the centre"
    );
    // Refinement ran to block size 1 once for the first view and again after the change.
    let block_ones = run.stderr.matches("block size 1 at").count();
    assert!(block_ones >= 2, "{}", run.stderr);
    let rect = image_rect(&run.stdout);
    let new_view = cpu_render(&scene, size, camera);
    assert_eq!(
        mismatches(&shot, rect, size, &new_view),
        0,
        "the window shows the new view"
    );
    let old_view = cpu_render(&scene, size, scene.camera.spec);
    assert!(mismatches(&shot, rect, size, &old_view) > (size * size / 10) as usize);
    // Save wrote the image itself and a camera snippet that reads back as the printed camera.
    assert_eq!(image::open(&saved).unwrap().to_rgb8().into_raw(), new_view);
    let snippet = std::fs::read_to_string(dir.path().join("saved.camera.toml")).unwrap();
    assert_eq!(printed_camera(&snippet), camera);
}

#[test]
fn a_resized_window_letterboxes_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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
    let Some(run) = run_viewer_watching(
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
    ) else {
        return;
    };
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

/// A small scene file: a red ball on a floor, seen from `eye`.
fn ball_scene(eye: [f32; 3]) -> String {
    format!(
        "[render]\nwidth = 64\nheight = 64\n\n[camera]\neye = {eye:?}\nlook_at = [0, 1, 0]\n\
         view_angle = 45\n\n[[lights]]\ntype = \"point\"\nposition = [3, 6, 4]\n\n\
         [materials.red]\ncolor = [0.8, 0.2, 0.1]\n\n[[objects]]\ntype = \"plane\"\n\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 1, 0]\nradius = 1\nmaterial = \"red\"\n"
    )
}

#[test]
fn a_broken_scene_file_shows_its_error_and_keeps_the_last_good_scene() {
    let dir = tempfile::tempdir().unwrap();
    let good = dir.path().join("good.toml");
    let broken = dir.path().join("broken.toml");
    std::fs::write(&good, ball_scene([0.0, 2.0, 6.0])).unwrap();
    std::fs::write(&broken, "[camera]\neye = [0, 1]\n").unwrap();
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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
    let Some(run) = run_viewer_watching(
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
    ) else {
        return;
    };
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
    let Some(run) = run_viewer_watching(
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
    ) else {
        return;
    };
    run.assert_success();
    // The scene's new look-at point, the file's eye and the flag's view angle.
    let reloaded = printed_camera(&run.stdout);
    assert_eq!(reloaded.eye, Vec3::new(2.0, 2.0, 5.0));
    assert_eq!((reloaded.look_at, reloaded.view_angle), (Vec3::ZERO, 30.0));
}

/// The viewer's process: `pid` itself or its child named raylab (under xvfb-run).
fn viewer_pid(pid: u32) -> Option<u32> {
    let comm = |p: u32| std::fs::read_to_string(format!("/proc/{p}/comm")).unwrap_or_default();
    if comm(pid).trim() == "raylab" {
        return Some(pid);
    }
    std::fs::read_dir("/proc")
        .ok()?
        .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .find(|&p| comm(p).trim() == "raylab" && stat_fields(p).get(1) == Some(&pid.to_string()))
}

/// The fields of /proc/PID/stat after the command's name: state, parent, …
fn stat_fields(pid: u32) -> Vec<String> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
    let after_name = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    after_name.split_whitespace().map(String::from).collect()
}

/// User and system CPU time of a process so far, in clock ticks.
fn cpu_ticks(pid: u32) -> u64 {
    let fields = stat_fields(pid);
    let field = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<u64>().ok())
            .unwrap_or(0)
    };
    field(11) + field(12)
}

#[test]
fn an_idle_viewer_uses_no_cpu() {
    let measured = Arc::new(Mutex::new(None));
    let result = measured.clone();
    // Once refinement is done (anti-aliasing included), measure the viewer's CPU time for two
    // seconds, then close it.
    let on_line = move |line: &str, child: u32| {
        if line.contains("refined at") && result.lock().unwrap().is_none() {
            let pid = viewer_pid(child).expect("the viewer's process");
            std::thread::sleep(Duration::from_millis(500));
            let before = cpu_ticks(pid);
            std::thread::sleep(Duration::from_secs(2));
            let used = cpu_ticks(pid) - before;
            *result.lock().unwrap() = Some(used);
            let _ = Command::new("kill").arg(pid.to_string()).status();
        }
    };
    let Some(run) = run_viewer_watching(&["--size", "64", "--stats"], &[], on_line) else {
        return;
    };
    let used = measured
        .lock()
        .unwrap()
        .unwrap_or_else(|| panic!("{}", run.stderr));
    assert!(
        used <= 5,
        "an idle viewer used {used} clock ticks of CPU in 2 s"
    );
}

#[test]
fn without_a_display_the_viewer_says_so_and_fails() {
    let output = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(["view", "--exit-when-done"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("display"), "{stderr}");
    assert!(stderr.contains("raylab render"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn help_documents_the_viewer() {
    for args in [&["--help"][..], &["view", "--help"][..]] {
        let output = Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args(args)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&output.stdout);
        assert!(output.status.success());
        for option in [
            "--size",
            "--block-size",
            "--screenshot",
            "--exit-when-done",
            "--script",
            "--view",
        ] {
            assert!(text.contains(option), "{args:?} lacks {option}: {text}");
        }
    }
}

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
fn busiest_pixel(scene: &Scene, bvh: &Bvh, size: u32) -> RayTree {
    let tracer = Tracer::new(scene, bvh);
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

#[test]
fn a_click_on_a_pixel_shows_its_ray_tree_and_draws_it_over_the_image() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let scene = default_scene().unwrap();
    let (sized_scene, bvh) = sized(&scene, size, scene.camera.spec);
    let tree = busiest_pixel(&sized_scene, &bvh, size);
    assert!(tree.nodes.len() >= 3, "a pixel with secondary rays");
    let (x, y) = tree.pixel;
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
    // The panel's headings, in the tree's order, each indented by its depth.
    let printed: Vec<&str> = run
        .stdout
        .lines()
        .filter_map(|l| l.strip_prefix("tree: "))
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
fn a_debug_view_chosen_in_the_viewer_renders_as_on_the_cpu() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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

/// The default scene rendered on the CPU at `size × size`, as linear colours.
fn cpu_render_linear(size: u32) -> Vec<raylab::color::Color> {
    let scene = default_scene().unwrap();
    let (scene, bvh) = sized(&scene, size, scene.camera.spec);
    progressive::render_image_with(&Tracer::new(&scene, &bvh), &DebugView::Shaded).0
}

#[test]
fn exposure_and_tone_curve_show_in_the_window_and_save_as_shown() {
    use raylab::tone::{Tone, ToneCurve};
    let dir = tempfile::tempdir().unwrap();
    let saved = dir.path().join("saved.png");
    let size = 64;
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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
    let Some((run, shot)) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--samples",
            "1",
            "--script",
            "wait; snapshot; view normals; divider 0.5; wait",
        ],
    ) else {
        return;
    };
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
    let shot_image = image::open(&shot).unwrap().to_rgb8();
    let (x0, y0, w, h) = image_rect(&run.stdout);
    let mut bad = 0;
    for j in 4..size {
        for i in 0..size {
            let sx = (x0 + (i as f32 + 0.5) * w / size as f32) as u32;
            let sy = (y0 + (j as f32 + 0.5) * h / size as f32) as u32;
            let got = shot_image.get_pixel(sx, sy).0;
            let k = ((j * size + i) * 3) as usize;
            if (0..3).any(|c| got[c].abs_diff(split[k + c]) > 2) {
                bad += 1;
            }
        }
    }
    assert_eq!(bad, 0, "the split view shows snapshot | live");
    // Both halves are really there: the picture is neither all shaded nor all normals.
    let rect = (x0, y0, w, h);
    assert!(mismatches(&shot, rect, size, &shaded) > (size * size / 8) as usize);
    assert!(mismatches(&shot, rect, size, &normals) > (size * size / 8) as usize);
}

/// The default scene rendered on the CPU at `size × size` with `samples` per pixel and
/// `aa_threshold`, as sRGB bytes.
fn cpu_render_sampled(size: u32, samples: u32, aa_threshold: f32) -> Vec<u8> {
    let scene = default_scene().unwrap();
    let (mut scene, bvh) = sized(&scene, size, scene.camera.spec);
    (scene.settings.samples, scene.settings.aa_threshold) = (samples, aa_threshold);
    to_srgb8(&progressive::render_image(&Tracer::new(&scene, &bvh)).0)
}

/// Root mean square difference of two sRGB images, on a 0–1 scale.
fn rmse(a: &[u8], b: &[u8]) -> f64 {
    let sum: f64 = a
        .iter()
        .zip(b)
        .map(|(&p, &q)| ((f64::from(p) - f64::from(q)) / 255.0).powi(2))
        .sum();
    (sum / a.len() as f64).sqrt()
}

#[test]
fn left_alone_the_viewer_refines_the_default_scene_close_to_a_256_spp_reference() {
    let dir = tempfile::tempdir().unwrap();
    let size = 96;
    let Some((run, shot)) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--window",
            "700x500",
            "--stats",
        ],
    ) else {
        return;
    };
    assert!(run.stderr.contains("refined at 96×96"), "{}", run.stderr);
    let shown = shown_pixels(&shot, image_rect(&run.stdout), (size, size));
    let reference = cpu_render_sampled(size, 256, 0.0);
    let one_sample = cpu_render_sampled(size, 1, 0.0);
    let (shown_error, one_error) = (rmse(&shown, &reference), rmse(&one_sample, &reference));
    assert!(
        shown_error < 0.5 * one_error,
        "RMSE against 256 spp: the viewer {shown_error:.4}, one sample {one_error:.4}"
    );
    // The viewer's default (16 samples at most, threshold 0.03) is the CPU's, pixel for pixel.
    let adaptive = cpu_render_sampled(size, 16, 0.03);
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &adaptive),
        0
    );
}

#[test]
fn with_a_threshold_of_zero_the_viewer_shows_what_render_saves() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let sampling = ["--samples", "4", "--aa-threshold", "0"];
    let Some((run, shot)) = run_to_screenshot(
        dir.path(),
        &[&["--size", "64", "--window", "600x400"][..], &sampling].concat(),
    ) else {
        return;
    };
    let saved = dir.path().join("render.png");
    let render = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(
            [
                &["render", "-o", saved.to_str().unwrap(), "--size", "64"][..],
                &sampling,
            ]
            .concat(),
        )
        .output()
        .unwrap();
    assert!(render.status.success(), "{render:?}");
    let rendered = image::open(&saved).unwrap().to_rgb8().into_raw();
    assert_eq!(
        rendered,
        cpu_render_sampled(size, 4, 0.0),
        "uniform sampling"
    );
    assert_ne!(rendered, cpu_render_sampled(size, 1, 0.0));
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &rendered),
        0
    );
}

/// The default scene rendered on the CPU at `width × height` with its own camera, as sRGB bytes.
fn cpu_render_sized(width: u32, height: u32) -> Vec<u8> {
    let mut scene = default_scene().unwrap();
    scene.settings.width = width;
    scene.settings.height = height;
    let bvh = Bvh::build(&scene.geometry);
    let (pixels, _) = progressive::render_image(&Tracer::new(&scene, &bvh));
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
fn the_viewer_starts_fitted_to_the_window_whatever_the_scenes_size() {
    let dir = tempfile::tempdir().unwrap();
    // The default scene says 640×480; the window's view area is another shape.
    let Some((run, shot)) = run_to_screenshot(
        dir.path(),
        &["--window", "700x500", "--samples", "1", "--stats"],
    ) else {
        return;
    };
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
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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
fn skip_traces_at_block_size_one_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let size = 256;
    let Some((run, shot)) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            &size.to_string(),
            "--block-size",
            "16",
            "--samples",
            "1",
            "--stats",
            "--script",
            "wait-load 1; skip; wait; print-status",
        ],
    ) else {
        return;
    };
    // The first image on screen is already at block size 1: no coarse pass was shown.
    let firsts: Vec<&str> = run
        .stderr
        .lines()
        .filter(|l| l.contains("stats: first image"))
        .collect();
    assert!(!firsts.is_empty(), "{}", run.stderr);
    assert!(
        firsts.iter().all(|l| l.contains("(block size 1)")),
        "{firsts:?}"
    );
    let status = run.stdout.lines().find(|l| l.starts_with("status: "));
    let status = status.unwrap_or_else(|| panic!("no status in {}", run.stdout));
    assert!(
        status.starts_with("status: done: 1 passes · started at block 1 ·"),
        "{status}"
    );
    let scene = default_scene().unwrap();
    let expected = cpu_render(&scene, size, scene.camera.spec);
    assert_eq!(
        mismatches(&shot, image_rect(&run.stdout), size, &expected),
        0
    );
}

#[test]
fn pause_stops_refinement_and_resume_finishes_it() {
    let dir = tempfile::tempdir().unwrap();
    let Some((run, _)) = run_to_screenshot(
        dir.path(),
        &[
            "--size",
            "256",
            "--samples",
            "1",
            "--stats",
            "--script",
            "wait-load 1; pause; print-status; sleep 0.5; print-status; resume; wait; print-status",
        ],
    ) else {
        return;
    };
    let statuses: Vec<&str> = run
        .stdout
        .lines()
        .filter_map(|l| l.strip_prefix("status: "))
        .collect();
    assert_eq!(statuses.len(), 3, "{}", run.stdout);
    let eye_rays = |status: &str| {
        let rays = status.split("rays: ").nth(1).unwrap();
        rays.split_whitespace().next().unwrap().to_string()
    };
    // Paused (within the passes: the coarse ones may be done before the pause arrives): the
    // status says so, and half a second later nothing more has been traced.
    for paused in &statuses[..2] {
        assert!(paused.starts_with("paused · pass "), "{paused}");
    }
    assert_eq!(eye_rays(statuses[0]), eye_rays(statuses[1]), "{statuses:?}");
    // Resumed: refinement runs to the end, and block size 1 reaches the screen only then.
    assert!(statuses[2].starts_with("done: "), "{}", statuses[2]);
    assert_eq!(eye_rays(statuses[2]), (256 * 256).to_string());
    let stats = &run.stderr;
    let resumed = stats.find("stats: resumed").expect(stats);
    assert!(stats.find("stats: paused").expect(stats) < resumed);
    assert!(stats.find("block size 1 at 256×256").expect(stats) > resumed);
}

#[test]
fn a_fitted_image_on_a_hidpi_window_has_its_physical_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("hidpi_fit.png");
    let Some(run) = run_viewer_watching(
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
    ) else {
        return;
    };
    run.assert_success();
    // Rendered at the view area's physical size (twice its logical one), shown 1:1.
    let rect = assert_fills_the_view_area(&run, 1120.0);
    let expected = cpu_render_sized(rect.2 as u32, rect.3 as u32);
    assert_eq!(mismatches_one_to_one(&shot, rect, &expected), 0);
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
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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
    let Some((run, shot)) = run_to_screenshot(
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
    ) else {
        return;
    };
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
