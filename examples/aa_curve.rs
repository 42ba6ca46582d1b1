//! How much anti-aliasing buys for the rays it costs: the default scene rendered with uniform
//! sampling and with adaptive anti-aliasing (`aa_threshold`) at caps of 1 to 32 samples per
//! pixel, each image's error against a 256-samples-per-pixel reference, printed as a table and
//! drawn as a curve of error against rays traced into `docs/aa_curve.png`.
//!
//! ```sh
//! cargo run --release --example aa_curve            # 512×384, about a minute on 2 cores
//! cargo run --release --example aa_curve -- 256x192 # smaller and quicker
//! ```
//!
//! The error is the root mean square difference of the images as saved and shown (8-bit sRGB,
//! on a 0–1 scale), the rays are all the rays traced (eye, shadow, reflected, transmitted).

use std::path::Path;

use image::{Rgb, RgbImage};
use raylab::backend::{Backend, RenderError};
use raylab::color::{Color, to_srgb8};
use raylab::formats::load_any;
use raylab::render::assemble;

/// The sample caps measured.
const CAPS: [u32; 6] = [1, 2, 4, 8, 16, 32];
/// The curves: uniform sampling (threshold 0) and adaptive anti-aliasing at two thresholds.
const THRESHOLDS: [f32; 3] = [0.0, 0.03, 0.1];
/// Their colours in the plot: blue, orange, green.
const COLORS: [[u8; 3]; 3] = [[31, 119, 180], [255, 127, 14], [44, 160, 44]];
const REFERENCE_SAMPLES: u32 = 256;

/// One render: its error against the reference and what it traced.
struct Point {
    threshold: f32,
    cap: u32,
    eye_rays: u64,
    rays: u64,
    seconds: f64,
    rmse: f64,
}

fn main() {
    if let Err(error) = run() {
        eprintln!("error: {error}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let size = std::env::args().nth(1).unwrap_or("512x384".into());
    let (width, height) = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or(format!("`{size}` is not a size WIDTHxHEIGHT"))?;
    let mut scene = load_any("assets/scenes/default.toml")?;
    (scene.settings.width, scene.settings.height) = (width, height);
    let assembled = assemble(scene)?;
    let mut backend = Backend::on_all_cores()?;
    let mut render = |samples, aa_threshold| {
        let mut assembled = assembled.clone();
        let settings = &mut assembled.scene.settings;
        (settings.samples, settings.aa_threshold) = (samples, aa_threshold);
        let (film, stats) = backend.render_image(&assembled)?;
        Ok::<_, RenderError>((film.pixels(), stats))
    };
    eprintln!("the {REFERENCE_SAMPLES}-spp reference at {width}×{height}…");
    let (reference, _) = render(REFERENCE_SAMPLES, 0.0)?;
    let reference = to_srgb8(&reference);
    println!("| aa_threshold | cap (spp) | eye rays / pixel | rays (M) | time (s) | RMSE |");
    println!("|---|---|---|---|---|---|");
    let mut points = Vec::new();
    for threshold in THRESHOLDS {
        for cap in CAPS {
            let (image, stats) = render(cap, threshold)?;
            let point = Point {
                threshold,
                cap,
                eye_rays: stats.rays.primary,
                rays: stats.rays.total(),
                seconds: stats.time.as_secs_f64(),
                rmse: display_rmse(&image, &reference),
            };
            println!(
                "| {} | {} | {:.2} | {:.2} | {:.2} | {:.4} |",
                point.threshold,
                point.cap,
                point.eye_rays as f64 / f64::from(width * height),
                point.rays as f64 / 1e6,
                point.seconds,
                point.rmse
            );
            points.push(point);
        }
    }
    let out = Path::new("docs/aa_curve.png");
    plot(&points).save(out)?;
    eprintln!("→ {}", out.display());
    Ok(())
}

/// Root mean square difference of `image` and the 8-bit `reference` as shown, on a 0–1 scale.
fn display_rmse(image: &[Color], reference: &[u8]) -> f64 {
    let sum: f64 = to_srgb8(image)
        .iter()
        .zip(reference)
        .map(|(&a, &b)| ((f64::from(a) - f64::from(b)) / 255.0).powi(2))
        .sum();
    (sum / reference.len() as f64).sqrt()
}

// The plot: RMSE up, rays traced across on a log₂ scale, one polyline per threshold.

const PLOT_SIZE: (u32, u32) = (640, 400);
/// The frame of the axes inside the image: left, top, right, bottom.
const FRAME: (f64, f64, f64, f64) = (60.0, 20.0, 620.0, 350.0);

fn plot(points: &[Point]) -> RgbImage {
    let mut image = RgbImage::from_pixel(PLOT_SIZE.0, PLOT_SIZE.1, Rgb([255, 255, 255]));
    let (left, top, right, bottom) = FRAME;
    let x_of = |p: &Point| (p.rays as f64).log2();
    let (x_min, x_max) = points
        .iter()
        .map(x_of)
        .fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)));
    let y_max = points.iter().map(|p| p.rmse).fold(0.0, f64::max) * 1.1;
    let to_pixel = |x: f64, y: f64| {
        let px = left + (x - x_min) / (x_max - x_min).max(1e-9) * (right - left);
        let py = bottom - y / y_max.max(1e-9) * (bottom - top);
        (px, py)
    };
    let grey = Rgb([120, 120, 120]);
    line(&mut image, (left, bottom), (right, bottom), grey);
    line(&mut image, (left, top), (left, bottom), grey);
    // Ticks across: every doubling of the rays, labelled in millions.
    let mut x = x_min.ceil();
    while x <= x_max {
        let (px, _) = to_pixel(x, 0.0);
        line(&mut image, (px, bottom), (px, bottom + 5.0), grey);
        let label = format!("{:.1}", 2f64.powf(x) / 1e6);
        text(&mut image, px - 8.0, bottom + 9.0, &label, grey);
        x += 1.0;
    }
    // Ticks up: every 0.01 of RMSE.
    let mut y = 0.0;
    while y <= y_max {
        let (_, py) = to_pixel(x_min, y);
        line(&mut image, (left - 5.0, py), (left, py), grey);
        text(&mut image, 14.0, py - 5.0, &format!("{y:.2}"), grey);
        y += 0.01;
    }
    for (threshold, color) in THRESHOLDS.into_iter().zip(COLORS) {
        let color = Rgb(color);
        let curve: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.threshold == threshold)
            .map(|p| to_pixel(x_of(p), p.rmse))
            .collect();
        for pair in curve.windows(2) {
            line(&mut image, pair[0], pair[1], color);
        }
        for &(px, py) in &curve {
            square(&mut image, px, py, 3, color);
        }
        // The legend: a square of the curve's colour before its threshold.
        let row = THRESHOLDS.iter().position(|&t| t == threshold).unwrap_or(0);
        let (lx, ly) = (right - 90.0, top + 10.0 + 18.0 * row as f64);
        square(&mut image, lx, ly, 5, color);
        text(
            &mut image,
            lx + 12.0,
            ly - 5.0,
            &format!("{threshold}"),
            color,
        );
    }
    image
}

/// A line one pixel wide from `a` to `b`.
fn line(image: &mut RgbImage, a: (f64, f64), b: (f64, f64), color: Rgb<u8>) {
    let steps = (b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil().max(1.0) as u32;
    for i in 0..=steps {
        let t = f64::from(i) / f64::from(steps);
        put(image, a.0 + (b.0 - a.0) * t, a.1 + (b.1 - a.1) * t, color);
    }
}

/// A filled square `2·half + 1` pixels a side centred on (x, y).
fn square(image: &mut RgbImage, x: f64, y: f64, half: i32, color: Rgb<u8>) {
    for dy in -half..=half {
        for dx in -half..=half {
            put(image, x + f64::from(dx), y + f64::from(dy), color);
        }
    }
}

fn put(image: &mut RgbImage, x: f64, y: f64, color: Rgb<u8>) {
    let (x, y) = (x.round(), y.round());
    if x >= 0.0 && y >= 0.0 && x < f64::from(image.width()) && y < f64::from(image.height()) {
        image.put_pixel(x as u32, y as u32, color);
    }
}

/// `digits` (0–9 and `.`) in a 3 × 5 pixel font drawn twice as large, top-left at (x, y).
fn text(image: &mut RgbImage, x: f64, y: f64, digits: &str, color: Rgb<u8>) {
    // Each glyph's 5 rows of 3 bits, the top row first.
    const GLYPHS: [[u8; 5]; 11] = [
        [7, 5, 5, 5, 7],
        [2, 6, 2, 2, 7],
        [7, 1, 7, 4, 7],
        [7, 1, 7, 1, 7],
        [5, 5, 7, 1, 1],
        [7, 4, 7, 1, 7],
        [7, 4, 7, 5, 7],
        [7, 1, 1, 1, 1],
        [7, 5, 7, 5, 7],
        [7, 5, 7, 1, 7],
        [0, 0, 0, 0, 2],
    ];
    for (i, c) in digits.chars().enumerate() {
        let glyph = match c {
            '.' => GLYPHS[10],
            _ => match c.to_digit(10) {
                Some(d) => GLYPHS[d as usize],
                None => continue,
            },
        };
        let left = x + 8.0 * i as f64;
        for (row, bits) in glyph.iter().enumerate() {
            for column in 0..3 {
                if bits & (4 >> column) != 0 {
                    let (px, py) = (left + 2.0 * column as f64, y + 2.0 * row as f64);
                    for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                        put(image, px + dx, py + dy, color);
                    }
                }
            }
        }
    }
}
