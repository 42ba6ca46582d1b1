//! Big work in proportion: `diff`, `check` and the caustic photons take the memory they say,
//! measured as the peak resident memory of the raylab process, and refuse what would not fit
//! before reading it, naming the limit.

use std::path::Path;
use std::time::Duration;

use raylab::compare::check::memory_bytes;
use raylab::formats::load_any;

use crate::common::random::Rng;
use crate::common::run::{Measured, raylab_measured, stderr};

/// Long enough for any of these runs on a slow machine; a run that hangs fails.
const LIMIT: Duration = Duration::from_secs(300);

fn manifest(path: &str) -> String {
    format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))
}

/// Writes a `width × height` PNG of seeded noise (colours that do not compress) at `path`.
fn noise_png(path: &Path, width: u32, height: u32, seed: u64) {
    let mut rng = Rng::with_seed(seed);
    let image = image::RgbImage::from_fn(width, height, |_, _| {
        image::Rgb([rng.u8(..), rng.u8(..), rng.u8(..)])
    });
    image.save(path).unwrap();
}

/// Writes a black `side × side` PNG at `path` a row at a time (small, however large the image).
fn black_png(path: &Path, side: u32) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let mut encoder = png::Encoder::new(file, side, side);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().unwrap();
    let mut stream = writer.stream_writer().unwrap();
    let row = vec![0u8; side as usize * 3];
    for _ in 0..side {
        std::io::Write::write_all(&mut stream, &row).unwrap();
    }
    stream.finish().unwrap();
}

/// The peak memory of `raylab ARGS` in `dir`, a comparison that must find the images differ.
fn peak_of_a_difference(args: &[&str], dir: &Path) -> u64 {
    let measured = raylab_measured(args, dir, &[], LIMIT);
    let out = &measured.output;
    assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(out));
    measured.peak_bytes
}

#[test]
fn diff_takes_at_most_20_bytes_a_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let (width, height) = (3000, 2000);
    for (name, size, seed) in [("a.png", width, 1), ("b.png", width, 2)] {
        noise_png(&dir.path().join(name), size, height, seed);
    }
    noise_png(&dir.path().join("small_a.png"), 30, 20, 1);
    noise_png(&dir.path().join("small_b.png"), 30, 20, 2);
    let run =
        |a: &str, b: &str| peak_of_a_difference(&["diff", a, b, "-o", "heat.png"], dir.path());
    let small = run("small_a.png", "small_b.png");
    let big = run("a.png", "b.png");
    let pixels = f64::from(width * height);
    let per_pixel = big.saturating_sub(small) as f64 / pixels;
    eprintln!("diff of two {width}×{height} images: {per_pixel:.1} bytes a pixel");
    assert!(
        per_pixel <= 20.0,
        "diff took {per_pixel:.1} bytes a pixel, more than 20"
    );
}

#[test]
fn diff_and_check_refuse_images_too_large_for_the_limit_before_reading_them() {
    let dir = tempfile::tempdir().unwrap();
    black_png(&dir.path().join("black.png"), 16384);
    let default_scene = manifest("assets/scenes/default.toml");
    let runs: [(Vec<&str>, &str, &str); 2] = [
        (
            vec!["diff", "black.png", "black.png"],
            "1G",
            "comparing two 16384×16384 images would take about",
        ),
        (
            vec!["check", &default_scene, "black.png"],
            "2G",
            "checking a 16384×16384 image would take about",
        ),
    ];
    for (args, limit, expected) in runs {
        let env = [("RAYLAB_MAX_MEMORY", limit)];
        let Measured { output, peak_bytes } = raylab_measured(&args, dir.path(), &env, LIMIT);
        let text = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {text}");
        assert!(
            text.contains(expected) && text.contains("RAYLAB_MAX_MEMORY"),
            "{text}"
        );
        assert!(
            peak_bytes < 200 << 20,
            "{args:?} held {peak_bytes} bytes before refusing"
        );
    }
}

#[test]
fn check_takes_the_memory_it_says() {
    let dir = tempfile::tempdir().unwrap();
    let scene = manifest("assets/scenes/default.toml");
    let run = |width: u32, height: u32| {
        let name = format!("mine_{width}.png");
        noise_png(&dir.path().join(&name), width, height, 3);
        peak_of_a_difference(&["check", &scene, &name], dir.path())
    };
    let small = run(64, 48);
    let (width, height) = (1280, 960);
    let big = run(width, height);
    let mut settings = load_any(&scene).unwrap().settings;
    (settings.width, settings.height) = (width, height);
    let pixels = u64::from(width * height);
    // The image, the decoder's buffer it is read from, and what `check` says it takes.
    let stated = pixels * 3 + pixels * 3 + memory_bytes(&settings);
    let measured = big.saturating_sub(small);
    eprintln!("check at {width}×{height}: {measured} bytes, {stated} stated");
    assert!(
        measured <= stated,
        "check took {measured} bytes, more than the {stated} it says"
    );
}

#[test]
fn the_caustic_photons_estimate_is_within_a_tenth_of_what_they_take() {
    let dir = tempfile::tempdir().unwrap();
    let scene = manifest("assets/scenes/caustic_glass_ball.toml");
    let run = |photons: &str, limit: Option<String>| {
        let args = [
            "render",
            &scene,
            "-o",
            "x.ppm",
            "--size",
            "8",
            "--caustic-photons",
            photons,
        ];
        let env: Vec<(&str, &str)> = limit
            .as_deref()
            .map(|limit| ("RAYLAB_MAX_MEMORY", limit))
            .into_iter()
            .collect();
        raylab_measured(&args, dir.path(), &env, LIMIT)
    };
    let base = run("1000", None);
    let photons = "4000000";
    let full = run(photons, None);
    assert_eq!(
        full.output.status.code(),
        Some(0),
        "{}",
        stderr(&full.output)
    );
    let taken = full.peak_bytes.saturating_sub(base.peak_bytes);
    eprintln!("{photons} caustic photons took {taken} bytes");
    let below = run(photons, Some((taken * 9 / 10).to_string()));
    let text = stderr(&below.output);
    assert_eq!(
        below.output.status.code(),
        Some(1),
        "refused under 90 %: {text}"
    );
    assert!(text.contains("caustic photons"), "{text}");
    let above = run(photons, Some((taken * 11 / 10).to_string()));
    assert_eq!(
        above.output.status.code(),
        Some(0),
        "{}",
        stderr(&above.output)
    );
}
