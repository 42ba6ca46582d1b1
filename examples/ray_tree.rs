//! Trace the eye ray of one pixel and print its ray tree: every reflected, transmitted and
//! shadow ray, what each hit and the colour it brought back (what `raylab inspect` prints).
//!
//! ```sh
//! cargo run --example ray_tree -- assets/scenes/glass.toml 320 240
//! ```

use raylab::formats::load_any;
use raylab::inspect::trace_ray_tree;
use raylab::render::assemble;

fn main() {
    if let Err(error) = run() {
        eprintln!("error: {error}");
        std::process::exit(1);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene_name = args.first().map_or("assets/scenes/default.toml", |s| s);
    let scene = load_any(scene_name)?;
    let (width, height) = (scene.settings.width, scene.settings.height);
    let pixel = |i: usize, middle: u32| args.get(i).map_or(Ok(middle), |s| s.parse());
    let (x, y) = (pixel(1, width / 2)?, pixel(2, height / 2)?);

    let assembled = assemble(scene)?;
    let tree = trace_ray_tree(&assembled.tracer(), x, y);
    print!("{}", tree.to_text());
    Ok(())
}
