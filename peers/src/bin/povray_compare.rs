//! raylab's renders of SPD scenes under `--nff-lights povray` against POV-Ray 3.7's renders of
//! the SPD library's own POV-Ray output: the mean absolute difference per channel in 8-bit
//! levels of the linear values (POV-Ray's files hold `clamp(c)·255`, `File_Gamma=1`), and the
//! share of pixels off by more than 3 levels in any channel.
//!
//! ```sh
//! cargo run --release --manifest-path peers/Cargo.toml --bin povray_compare -- \
//!     ../shared/scenes/spd ../shared/scenes/povray-ref
//! ```

use std::path::Path;

use raylab::bvh::Bvh;
use raylab::formats::load_any_with;
use raylab::formats::nff::NffLighting;
use raylab::progressive::render_image;
use raylab::whitted::Tracer;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [spd, references] = &args[..] else {
        eprintln!("usage: povray_compare SPD_DIR POVRAY_REFERENCE_DIR");
        std::process::exit(2);
    };
    let mut names: Vec<_> = std::fs::read_dir(references)
        .expect("the reference folder")
        .filter_map(|entry| {
            let name = entry.ok()?.file_name().into_string().ok()?;
            Some(name.strip_suffix(".png")?.to_string())
        })
        .collect();
    names.sort();
    println!("| scene | size | mean difference (levels) | pixels off by more than 3 |");
    println!("|---|---|---|---|");
    for name in names {
        let reference = image::open(Path::new(references).join(format!("{name}.png")))
            .expect("a PNG")
            .to_rgb8();
        let nff = Path::new(spd).join(format!("{name}.nff"));
        let mut scene = load_any_with(nff.to_str().unwrap(), NffLighting::Povray)
            .unwrap_or_else(|e| panic!("{e}"));
        scene.settings.width = reference.width();
        scene.settings.height = reference.height();
        let bvh = Bvh::build(&scene.geometry);
        let (pixels, _) = render_image(&Tracer::new(&scene, &bvh));
        let (mut sum, mut far) = (0.0, 0);
        for (color, texel) in pixels.iter().zip(reference.pixels()) {
            let mut worst = 0.0f64;
            for channel in 0..3 {
                let ours = (color[channel].clamp(0.0, 1.0) * 255.0).round() as f64;
                let difference = (ours - f64::from(texel[channel])).abs();
                sum += difference;
                worst = worst.max(difference);
            }
            far += usize::from(worst > 3.0);
        }
        let n = pixels.len();
        println!(
            "| {name} | {}×{} | {:.2} | {:.2} % |",
            reference.width(),
            reference.height(),
            sum / (3 * n) as f64,
            100.0 * far as f64 / n as f64
        );
    }
}
