//! Participating media and the render settings that go with them: the atmosphere and a
//! material's medium read with their defaults, fog steps, caustic photons, the anti-aliasing
//! threshold, and their mistakes at their value.

use raylab::color::Color;
use raylab::medium::{Atmosphere, Medium};
use raylab::settings::RenderSettings;

use crate::harness::{assert_error, parse};

#[test]
fn an_atmosphere_is_read_with_defaults_for_what_it_leaves_out() {
    let scene =
        parse("[atmosphere]\ndensity = 0.2\nalbedo = 0.5\ncolor = [1, 0.9, 0.8]\n").unwrap();
    assert_eq!(
        scene.atmosphere,
        Atmosphere {
            medium: Medium {
                density: 0.2,
                albedo: 0.5,
                color: Color::new(1.0, 0.9, 0.8),
            },
            background_distance: None,
        }
    );
    let thin = parse("[atmosphere]\ndensity = 0.1\nbackground_distance = 50\n").unwrap();
    assert_eq!(
        thin.atmosphere,
        Atmosphere {
            medium: Medium {
                density: 0.1,
                ..Medium::default()
            },
            background_distance: Some(50.0),
        }
    );
    let endless = parse("[atmosphere]\ndensity = 0.1\nbackground_distance = inf\n").unwrap();
    assert_eq!(endless.atmosphere.background_distance, Some(f32::INFINITY));
    assert!(parse("").unwrap().atmosphere.is_clear());
    assert_eq!(RenderSettings::default().fog_steps, 16);
}

#[test]
fn caustic_settings_are_read_and_checked() {
    let scene = parse("[render]\ncaustic_photons = 50000\ncaustic_gather = 32\n").unwrap();
    assert_eq!(
        (
            scene.settings.caustic_photons,
            scene.settings.caustic_gather
        ),
        (50000, 32)
    );
    let old = parse("").unwrap();
    assert_eq!(
        old.settings.caustic_photons, 0,
        "caustics are off in old scenes"
    );
    assert_error(
        "[render]\ncaustic_gather = 0\n",
        2,
        18,
        "caustic_gather must be between 1 and 512",
    );
    assert_error(
        "[render]\ncaustic_photons = 200000000\n",
        2,
        19,
        "caustic_photons must be at most 100000000",
    );
}

#[test]
fn atmosphere_mistakes_are_errors_at_their_value() {
    assert_error("[atmosphere]\ndensity = -1\n", 2, 11, "zero or more");
    assert_error(
        "[atmosphere]\ndensity = 1\nalbedo = 1.5\n",
        3,
        10,
        "from 0 to 1",
    );
    assert_error(
        "[atmosphere]\ndensity = 1\ncolor = [1, -1, 0]\n",
        3,
        9,
        "non-negative",
    );
    assert_error(
        "[atmosphere]\nalbedo = 0.5\n",
        1,
        1,
        "missing field `density`",
    );
    assert_error("[atmosphere]\ndensity = 1\ndensty = 1\n", 3, 1, "`density`");
    assert_error(
        "[atmosphere]\ndensity = 1\nbackground_distance = 0\n",
        3,
        23,
        "a positive number or inf",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, background_distance = 5 }\n",
        2,
        25,
        "unknown field `background_distance`",
    );
    assert_error(
        "[render]\nfog_steps = 0\n",
        2,
        13,
        "fog_steps must be between 1 and 1024",
    );
    assert_error("[render]\nfog_steps = 2000\n", 2, 13, "fog_steps");
}

#[test]
fn a_material_medium_is_read_with_defaults_for_what_it_leaves_out() {
    let scene = parse(
        "[materials.smoke]\ntransparency = 1\n\
         medium = { density = 0.5, albedo = 0.25, color = [1, 0.5, 0] }\n\
         [materials.ink]\nmedium = { density = 2 }\n[materials.clear]\n",
    )
    .unwrap();
    // Materials are numbered in name order after the default: clear, ink, smoke.
    let media: Vec<_> = scene.materials.iter().map(|m| m.medium).collect();
    assert_eq!(
        media,
        [
            None,
            None,
            Some(Medium {
                density: 2.0,
                ..Medium::default()
            }),
            Some(Medium {
                density: 0.5,
                albedo: 0.25,
                color: Color::new(1.0, 0.5, 0.0),
            }),
        ]
    );
    // Ink is opaque: nothing enters it to see its medium.
    assert_eq!(
        scene.warnings,
        [
            "test.toml: material `ink` has a medium but is opaque (transparency 0): no light passes \
          into it, so the medium shows nowhere"
        ]
    );
}

#[test]
fn material_medium_mistakes_are_errors_at_their_value() {
    assert_error(
        "[materials.m]\nmedium = { density = -1 }\n",
        2,
        22,
        "zero or more",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, albedo = 2 }\n",
        2,
        34,
        "from 0 to 1",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, color = [0, -1, 0] }\n",
        2,
        33,
        "non-negative",
    );
    assert_error(
        "[materials.m]\nmedium = { albedo = 0.5 }\n",
        2,
        10,
        "missing field `density`",
    );
    assert_error(
        "[materials.m]\nmedium = { density = 1, densty = 1 }\n",
        2,
        25,
        "`density`",
    );
    assert_error(
        "[materials.m]\nmedium = 0.5\n",
        2,
        10,
        "expected a medium: a table like { density = 0.5",
    );
}

#[test]
fn the_anti_aliasing_threshold_is_read_checked_and_listed() {
    let scene = parse("[render]\nsamples = 16\naa_threshold = 0.03\n").unwrap();
    assert_eq!(
        (scene.settings.samples, scene.settings.aa_threshold),
        (16, 0.03)
    );
    assert_eq!(
        parse("").unwrap().settings.aa_threshold,
        0.0,
        "uniform by default"
    );
    assert_error(
        "[render]\naa_threshold = 1.5\n",
        2,
        16,
        "aa_threshold must be between 0 (uniform sampling) and 1, got 1.5",
    );
    assert_error(
        "[render]\naa_threshold = -0.1\n",
        2,
        16,
        "aa_threshold must be",
    );
    assert_error("[render]\naa_treshold = 0.1\n", 2, 1, "`aa_threshold`");
}
