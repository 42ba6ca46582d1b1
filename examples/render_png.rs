//! Render a scene file to a PNG: the shortest complete use of the library.
//!
//! ```sh
//! cargo run --release --example render_png -- assets/scenes/glass.toml glass.png [gpu]
//! ```
//!
//! The scene may be anything `raylab render` takes: a TOML scene file, an NFF file or a
//! built-in SPD scene such as `spd:balls`. A third argument, `cpu` (the default) or `gpu`,
//! chooses the tracer.

use std::path::Path;

use raylab::backend::Backend;
use raylab::formats::image::save_image;
use raylab::formats::load_any;
use raylab::render::{Device, assemble};

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
    let device: Device = args.next().as_deref().unwrap_or("cpu").parse()?;

    let scene = load_any(&scene_name)?; // scene file → Scene
    let assembled = assemble(scene)?; // Scene → BVH → caustic photons
    let mut backend = Backend::on_all_cores()?; // the tracers, on all cores or the GPU
    backend.set_device(device);
    let (film, stats) = backend.render_image(&assembled)?; // → image

    let (width, height) = (film.width(), film.height());
    save_image(Path::new(&out), width, height, &film.pixels())?;
    println!(
        "{width}×{height} in {:.2} s on {}, {} rays → {out}",
        stats.time.as_secs_f64(),
        backend.label(),
        stats.rays.total()
    );
    Ok(())
}
