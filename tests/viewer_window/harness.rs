//! Running the viewer and reading what it shows, for every topic: one viewer at a time in a
//! window on a real or virtual display (the test failed for want of one), the
//! image area and the camera it reports, CPU renders of the same scene to compare with, and a
//! small scene file to edit.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use glam::Vec3;
use raylab::camera::{Camera, CameraSpec};
use raylab::color::to_srgb8;
use raylab::formats::toml::default_scene;
use raylab::inspect::DebugView;
use raylab::progressive;
use raylab::render::{Assembled, assemble};
use raylab::scene::Scene;

/// One viewer at a time: they share two cores, and parallel `xvfb-run -a` can race for a display.
static DISPLAY_LOCK: Mutex<()> = Mutex::new(());
const TIMEOUT: Duration = Duration::from_secs(240);

/// What a run of the viewer did: whether it succeeded, and what it printed.
pub struct Run {
    success: bool,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    pub fn assert_success(&self) {
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

/// Where no display can be had: fails, saying how to get one.
fn no_display() -> ! {
    let packages = "xvfb xauth mesa-vulkan-drivers libvulkan1 libxkbcommon-x11-0";
    panic!(
        "the viewer's window tests need a display, and there is neither DISPLAY nor xvfb-run. \
         Install Xvfb and Mesa's software Vulkan (Debian: sudo apt-get install {packages}) and \
         run `cargo test --test viewer_window` (the tests start Xvfb themselves), or \
         `xvfb-run -a cargo test --test viewer_window`, or scripts/test, which installs them"
    );
}

/// Runs the viewer with `args` in a window.
fn run_viewer(args: &[&str]) -> Run {
    run_viewer_watching(args, &[], |_, _| {})
}

/// [`run_viewer`] with `args`, until refinement is done, then a screenshot of the window saved
/// into `dir`: the run, which must have succeeded, and the screenshot's path.
pub fn run_to_screenshot(dir: &Path, args: &[&str]) -> (Run, PathBuf) {
    let shot = dir.join("window.png");
    let shot_arg = shot.to_str().unwrap().to_string();
    let mut all = args.to_vec();
    all.extend(["--exit-when-done", "--screenshot", &shot_arg]);
    let run = run_viewer(&all);
    run.assert_success();
    (run, shot)
}

/// [`run_viewer`] with environment variables `env`, handing each line the viewer prints on
/// stderr to `on_line` as it comes, with the process id of the command started (xvfb-run, or
/// the viewer itself).
pub fn run_viewer_watching(
    args: &[&str],
    env: &[(&str, &str)],
    mut on_line: impl FnMut(&str, u32) + Send + 'static,
) -> Run {
    let Some(wrapper) = display_wrapper() else {
        no_display();
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
    run
}

/// Where the screenshot put the image: `(x, y, width, height)` from the viewer's report.
pub fn image_rect(stdout: &str) -> (f32, f32, f32, f32) {
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
pub fn printed_camera(stdout: &str) -> CameraSpec {
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

/// The scene at `size × size` seen with `camera`, assembled for rendering.
pub fn sized(scene: &Scene, size: u32, camera: CameraSpec) -> Assembled {
    let mut scene = scene.clone();
    scene.settings.width = size;
    scene.settings.height = size;
    scene.camera = Camera::new(camera).unwrap();
    assemble(scene).unwrap()
}

/// `view` of the scene rendered on the CPU at `size × size` with `camera`, as sRGB bytes.
pub fn cpu_render_view(scene: &Scene, size: u32, camera: CameraSpec, view: DebugView) -> Vec<u8> {
    let (pixels, _) = progressive::render_image_with(&sized(scene, size, camera).tracer(), &view);
    to_srgb8(&pixels)
}

/// The scene rendered on the CPU at `size × size` with `camera`, as sRGB bytes.
pub fn cpu_render(scene: &Scene, size: u32, camera: CameraSpec) -> Vec<u8> {
    cpu_render_view(scene, size, camera, DebugView::Shaded)
}

/// The default scene rendered on the CPU at `size × size` with `samples` per pixel and
/// `aa_threshold`, as sRGB bytes.
pub fn cpu_render_sampled(size: u32, samples: u32, aa_threshold: f32) -> Vec<u8> {
    let scene = default_scene().unwrap();
    let mut assembled = sized(&scene, size, scene.camera.spec);
    let settings = &mut assembled.scene.settings;
    (settings.samples, settings.aa_threshold) = (samples, aa_threshold);
    to_srgb8(&progressive::render_image(&assembled.tracer()).0)
}

/// The screenshot's image area at `rect` sampled at the centre of each of the `width × height`
/// image pixels, as sRGB bytes.
pub fn shown_pixels(
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
pub fn differing(got: &[u8], expected: &[u8]) -> usize {
    assert_eq!(got.len(), expected.len(), "images of the same size");
    got.chunks_exact(3)
        .zip(expected.chunks_exact(3))
        .filter(|(g, e)| (0..3).any(|c| g[c].abs_diff(e[c]) > 2))
        .count()
}

/// Compares the screenshot's image area, sampled at the centre of each image pixel, with the
/// CPU's `size × size` image; returns the number of pixels that differ by more than 2 levels.
pub fn mismatches(
    screenshot: &Path,
    rect: (f32, f32, f32, f32),
    size: u32,
    expected: &[u8],
) -> usize {
    differing(&shown_pixels(screenshot, rect, (size, size)), expected)
}

/// A small scene file: a red ball on a floor, seen from `eye`.
pub fn ball_scene(eye: [f32; 3]) -> String {
    format!(
        "[render]\nwidth = 64\nheight = 64\n\n[camera]\neye = {eye:?}\nlook_at = [0, 1, 0]\n\
         view_angle = 45\n\n[[lights]]\ntype = \"point\"\nposition = [3, 6, 4]\n\n\
         [materials.red]\ncolor = [0.8, 0.2, 0.1]\n\n[[objects]]\ntype = \"plane\"\n\n\
         [[objects]]\ntype = \"sphere\"\ncenter = [0, 1, 0]\nradius = 1\nmaterial = \"red\"\n"
    )
}
