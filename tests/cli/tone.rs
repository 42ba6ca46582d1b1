//! `render --exposure` and `--tonemap`: what they do to the written pixels, the plain encoding
//! without them, and their errors.

use std::path::Path;
use std::process::Output;

use crate::common::run::{raylab, stderr};

/// Renders the default scene at 40×30 with `extra` flags into `name`.
fn render_small(name: &str, extra: &[&str], dir: &Path) -> Output {
    let mut args = vec!["render", "-o", name, "--size", "40x30", "--threads", "1"];
    args.extend_from_slice(extra);
    raylab(&args, dir)
}

#[test]
fn render_exposure_doubles_the_linear_values_before_the_curve() {
    use raylab::tone::{Tone, ToneCurve};
    use strum::IntoEnumIterator;
    let dir = tempfile::tempdir().unwrap();
    let out = render_small("linear.exr", &[], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let linear = image::open(dir.path().join("linear.exr"))
        .unwrap()
        .to_rgb32f();
    let mut brightened = 0;
    for curve in ToneCurve::iter() {
        let name = format!("{curve}.png");
        let out = render_small(
            &name,
            &["--exposure", "1", "--tonemap", &curve.to_string()],
            dir.path(),
        );
        assert!(out.status.success(), "{curve}: {}", stderr(&out));
        let shown = image::open(dir.path().join(&name)).unwrap().to_rgb8();
        let doubled = Tone::new(0.0, curve).unwrap();
        for (got, linear) in shown.pixels().zip(linear.pixels()) {
            let expected = linear.0.map(|v| doubled.srgb8(2.0 * v));
            assert_eq!(got.0, expected, "{curve}");
        }
        let plain = Tone::default();
        brightened += shown
            .pixels()
            .zip(linear.pixels())
            .filter(|(s, l)| s.0 != l.0.map(|v| plain.srgb8(v)))
            .count();
    }
    assert!(brightened > 0, "one stop changes the picture");
}

#[test]
fn render_without_exposure_or_curve_writes_the_plain_encoding() {
    let dir = tempfile::tempdir().unwrap();
    for (name, extra) in [
        ("plain.png", &[][..]),
        ("explicit.png", &["--exposure", "0", "--tonemap", "clamp"]),
    ] {
        let out = render_small(name, extra, dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let out = render_small("linear.exr", &[], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let linear = image::open(dir.path().join("linear.exr"))
        .unwrap()
        .to_rgb32f();
    let encoded: Vec<u8> = linear
        .pixels()
        .flat_map(|p| p.0.map(raylab::color::srgb8))
        .collect();
    for name in ["plain.png", "explicit.png"] {
        let png = image::open(dir.path().join(name)).unwrap().to_rgb8();
        assert_eq!(png.into_raw(), encoded, "{name}");
    }
}

#[test]
fn bad_exposures_and_tone_curves_are_clear_errors() {
    let dir = tempfile::tempdir().unwrap();
    // Clap refuses what is not a curve or a number (code 2), raylab an exposure out of range (1).
    for (extra, code, message) in [
        (
            &["--tonemap", "aces"][..],
            2,
            "unknown tone curve `aces` (use one of: clamp, reinhard, filmic)",
        ),
        (&["--exposure", "bright"], 2, "invalid value 'bright'"),
        (
            &["--exposure", "40"],
            1,
            "exposure must be from -16 to 16 stops",
        ),
        (
            &["--exposure", "nan"],
            1,
            "exposure must be from -16 to 16 stops",
        ),
    ] {
        let out = render_small("a.png", extra, dir.path());
        assert_eq!(out.status.code(), Some(code), "{extra:?}");
        assert!(
            stderr(&out).contains(message),
            "{extra:?}: {}",
            stderr(&out)
        );
    }
    assert!(!dir.path().join("a.png").exists());
    let out = render_small("a.exr", &["--exposure", "1"], dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("shape 8-bit images only; a.exr keeps the linear values"),
        "{}",
        stderr(&out)
    );
}
