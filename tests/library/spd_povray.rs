//! The SPD scenes under `--nff-lights povray` against POV-Ray 3.7's own renders of the SPD
//! library's POV-Ray output (`tests/reference/povray/`, made as its README says): the mean
//! absolute difference of the linear values, in 8-bit levels, stays within 4.

use std::path::Path;

use raylab::formats::load_any_with;
use raylab::formats::nff::NffLighting;
use raylab::progressive::render_image;
use raylab::render::assemble;

/// Each SPD generator raylab has built in (`spd:NAME:SIZE`), at the size of the reference, and
/// the files of `tests/nff/` of other generators.
const SCENES: [&str; 8] = [
    "balls-2",
    "gears-2",
    "mount-6",
    "rings-7",
    "teapot-6",
    "tetra-6",
    "tree-6",
    "sombrero-1",
];
const FILES: [&str; 1] = ["sombrero-1"];

/// The mean absolute difference per channel, in levels, between raylab's render of `name`
/// under POV-Ray's conventions, encoded as POV-Ray writes linear values (`clamp(c)·255`,
/// rounded), and POV-Ray's render at the same size.
fn difference_from_povray(name: &str, lighting: NffLighting) -> f64 {
    let references = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/reference/povray");
    let reference = image::open(references.join(format!("{name}.png")))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .to_rgb8();
    let source = match FILES.contains(&name) {
        true => format!("{}/tests/nff/{name}.nff", env!("CARGO_MANIFEST_DIR")),
        false => format!("spd:{}", name.replace('-', ":")),
    };
    let mut scene = load_any_with(&source, lighting).unwrap_or_else(|e| panic!("{e}"));
    scene.settings.width = reference.width();
    scene.settings.height = reference.height();
    let (pixels, _) = render_image(&assemble(scene).unwrap().tracer());
    let sum: f64 = pixels
        .iter()
        .zip(reference.pixels())
        .flat_map(|(color, texel)| {
            (0..3).map(move |c| {
                let ours = (color[c].clamp(0.0, 1.0) * 255.0).round();
                (f64::from(ours) - f64::from(texel[c])).abs()
            })
        })
        .sum();
    sum / (3 * pixels.len()) as f64
}

#[test]
fn every_spd_generator_renders_within_4_levels_of_povray() {
    let mut report = Vec::new();
    for name in SCENES {
        let mean = difference_from_povray(name, NffLighting::Povray);
        report.push(format!("{name} {mean:.2}"));
        assert!(
            mean <= 4.0,
            "{name}: {mean:.2} levels from POV-Ray ({report:?})"
        );
    }
    eprintln!("mean difference from POV-Ray, in levels: {report:?}");
}

#[test]
fn the_readme_convention_is_not_povrays() {
    // The SPD readme's lights and materials light the balls' floor differently: the
    // comparison tells them apart.
    let mean = difference_from_povray("balls-2", NffLighting::Readme);
    assert!(mean > 10.0, "{mean:.2}");
}
