//! `raylab diff`: the figures against hand-computed ones, the heat map, the formats read, and
//! `cmp`'s exit codes (0 within the tolerance, 1 different, 2 trouble).

use std::path::Path;

use crate::common::run::{raylab, stderr};

fn write_png(dir: &Path, name: &str, width: u32, pixels: &[[u8; 3]]) {
    let bytes: Vec<u8> = pixels.iter().flatten().copied().collect();
    let height = pixels.len() as u32 / width;
    image::RgbImage::from_raw(width, height, bytes)
        .unwrap()
        .save(dir.join(name))
        .unwrap();
}

fn stdout(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn the_figures_are_the_hand_computed_ones_and_a_difference_exits_1() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path(), "ref.png", 2, &[[10, 20, 30], [100, 100, 100]]);
    write_png(dir.path(), "mine.png", 2, &[[13, 20, 30], [100, 90, 100]]);
    let out = raylab(&["diff", "ref.png", "mine.png"], dir.path());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = stdout(&out);
    // Channel differences 3, 0, 0 and 0, 10, 0: mean 13/6, RMSE √(109/6), PSNR
    // 20·log10(255/RMSE).
    for line in [
        "mine.png against ref.png: 2×1 pixels",
        "mean absolute difference: 2.1667 levels",
        "RMSE: 4.2622 levels",
        "PSNR: 35.54 dB",
        "largest difference: 10 levels at pixel (1, 0)",
        "over the tolerance of 2 levels: 2 pixels (100.00 %)",
        "\ndifferent\n",
    ] {
        assert!(text.contains(line), "{line:?} missing:\n{text}");
    }
    let out = raylab(
        &["diff", "ref.png", "mine.png", "--tolerance", "3"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stdout(&out).contains("over the tolerance of 3 levels: 1 pixels (50.00 %)"));
    let out = raylab(
        &["diff", "ref.png", "mine.png", "--tolerance", "10"],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
    assert!(stdout(&out).contains("\nwithin tolerance\n"));
}

#[test]
fn an_image_equals_itself_in_every_format_and_exits_0() {
    let dir = tempfile::tempdir().unwrap();
    let pixels: Vec<[u8; 3]> = (0..12u8).map(|i| [i * 20, 255 - i * 20, i * 7]).collect();
    write_png(dir.path(), "a.png", 4, &pixels);
    let image = image::open(dir.path().join("a.png")).unwrap();
    for name in ["a.ppm", "a.bmp"] {
        image.save(dir.path().join(name)).unwrap();
    }
    for other in ["a.png", "a.ppm", "a.bmp"] {
        let out = raylab(&["diff", "a.png", other], dir.path());
        assert_eq!(out.status.code(), Some(0), "{other}: {}", stderr(&out));
        let text = stdout(&out);
        assert!(
            text.contains("PSNR: infinite") && text.contains("FLIP: 0.0000"),
            "{text}"
        );
    }
}

#[test]
fn floats_are_compared_through_the_srgb_curve_as_raylab_writes_its_pngs() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["a.png", "a.exr", "a.hdr"] {
        let out = raylab(&["render", "--size", "32x24", "-o", name], dir.path());
        assert!(out.status.success(), "{}", stderr(&out));
    }
    // OpenEXR keeps the floats; Radiance HDR rounds them to 8-bit mantissas that share the
    // brightest channel's exponent, a few levels in a pixel's darker channels.
    for (other, tolerance) in [("a.exr", "0"), ("a.hdr", "4")] {
        let out = raylab(
            &["diff", "a.png", other, "--tolerance", tolerance],
            dir.path(),
        );
        assert_eq!(out.status.code(), Some(0), "{other}: {}", stdout(&out));
    }
}

#[test]
fn the_heat_map_is_brightest_at_the_largest_difference_and_has_a_legend() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path(), "ref.png", 3, &[[0; 3], [0; 3], [0; 3]]);
    write_png(dir.path(), "mine.png", 3, &[[0; 3], [0, 40, 0], [0, 0, 80]]);
    let out = raylab(&["diff", "ref.png", "mine.png", "-o", "d.png"], dir.path());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("largest channel difference, 8-bit levels") && text.contains("d.legend.png"),
        "{text}"
    );
    let heat = image::open(dir.path().join("d.png")).unwrap().to_rgb8();
    assert_eq!(heat.dimensions(), (3, 1));
    let brightness = |x: u32| {
        heat.get_pixel(x, 0)
            .0
            .iter()
            .map(|&c| u32::from(c))
            .sum::<u32>()
    };
    assert!(brightness(0) < brightness(1) && brightness(1) < brightness(2));
    assert!(dir.path().join("d.legend.png").exists());
}

#[test]
fn json_gives_every_figure() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path(), "ref.png", 2, &[[10, 20, 30], [100, 100, 100]]);
    write_png(dir.path(), "mine.png", 2, &[[13, 20, 30], [100, 90, 100]]);
    let out = raylab(&["diff", "ref.png", "mine.png", "--json"], dir.path());
    assert_eq!(out.status.code(), Some(1));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["largest"]["levels"], 10);
    assert_eq!(json["largest"]["x"], 1);
    assert_eq!(json["over_tolerance"], 2);
    assert_eq!(json["within_tolerance"], false);
    assert!((json["rmse"].as_f64().unwrap() - (109.0f64 / 6.0).sqrt()).abs() < 1e-9);
    assert!(json["flip"].as_f64().unwrap() > 0.0, "{json}");
    let out = raylab(&["diff", "ref.png", "ref.png", "--json"], dir.path());
    assert_eq!(out.status.code(), Some(0));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(json["psnr"].is_null(), "{json}");
    assert_eq!(json["flip"], 0.0);
}

#[test]
fn trouble_exits_2_and_says_what() {
    let dir = tempfile::tempdir().unwrap();
    write_png(dir.path(), "a.png", 2, &[[0; 3]; 4]);
    write_png(dir.path(), "b.png", 4, &[[0; 3]; 4]);
    std::fs::write(dir.path().join("c.png"), "not an image").unwrap();
    for (args, expected) in [
        (
            &["diff", "a.png", "b.png"][..],
            "the reference is 2×2, the image 4×1",
        ),
        (&["diff", "a.png", "none.png"], "none.png"),
        (
            &["diff", "c.png", "a.png"],
            "c.png: not an image raylab reads",
        ),
        (&["diff", "a.png", "a.png", "-o", "d.txt"], "d.txt"),
    ] {
        let out = raylab(args, dir.path());
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains(expected), "{args:?}: {err}");
    }
}
