//! Render a scene file to a PNG: the shortest complete use of the library.
//!
//! ```sh
//! cargo run --release --example render_png -- assets/scenes/glass.toml glass.png
//! ```
//!
//! The scene may be anything `raylab render` takes: a TOML scene file, an NFF file or a
//! built-in SPD scene such as `spd:balls`.

use std::path::Path;

use raylab::formats::image::save_image;
use raylab::formats::load_any;
use raylab::progressive::render_image;
use raylab::render::assemble;

fn main() {
    if let Err(error) = run() {
        eprintln!("error: {error}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let scene_name = args.next().unwrap_or("assets/scenes/default.toml".into());
    let out = args.next().unwrap_or("render.png".into());

    let scene = load_any(&scene_name)?; // scene file → Scene
    let assembled = assemble(scene)?; // Scene → BVH → caustic photons
    let tracer = assembled.tracer(); // the Whitted tracer over them
    let (pixels, stats) = render_image(&tracer); // every pass, on all cores

    let (width, height) = (tracer.scene.settings.width, tracer.scene.settings.height);
    save_image(Path::new(&out), width, height, &pixels)?;
    println!(
        "{width}×{height} in {:.2} s, {} rays → {out}",
        stats.time.as_secs_f64(),
        stats.rays.total()
    );
    Ok(())
}
