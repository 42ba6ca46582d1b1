//! `raylab inspect --draw` and `--obj`: the lecture's ray-tree figure of the inspected pixel,
//! seen from an observer camera, and its lines as OBJ polylines.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use glam::Vec3;

use raylab::backend::Backend;
use raylab::camera::{Camera, CameraSpec};
use raylab::figure::{
    FigureStyle, OBSERVER_ANGLE, RayFigure, draw, observed, observer_depths, side_view,
};
use raylab::film::Film;
use raylab::formats::image::{check_image_path, save_image};
use raylab::inspect::{DebugView, RayTree};
use raylab::limits::check_image_size;
use raylab::memory;
use raylab::output::write_atomically;
use raylab::render::{Assembled, Device, FirstHit};
use raylab::srgb_image::SrgbImage;

use super::overrides::{parse_number, parse_size, parse_vector};

/// What drawing a figure takes a pixel beyond the observer's film: its depth (4 bytes), the
/// layer (4), the render and the figure as 8-bit images (3 each) and as linear colours to write
/// (12).
const FIGURE_BYTES_PER_PIXEL: u64 = 26;

#[derive(Args, Debug)]
pub struct FigureArgs {
    /// Draw the pixel's ray tree in the scene, seen from an observer camera: the lecture's
    /// figure, as a PNG (or PPM, EXR, HDR) image. With --draw, --look-at is the point the
    /// observer looks at (the scene camera keeps its own).
    #[arg(long, value_name = "FIGURE.png")]
    pub draw: Option<PathBuf>,
    /// Write the pixel's rays as OBJ polylines, one group per kind (eye, shadow,
    /// shadow-blocked, reflected, transmitted, normal, image-plane).
    #[arg(long, value_name = "TREE.obj")]
    pub obj: Option<PathBuf>,
    /// Where the observer stands (default: beside the scene camera, a little above, far enough
    /// to see the whole tree).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vector, allow_hyphen_values = true, requires = "draw")]
    from: Option<Vec3>,
    /// The observer's vertical view angle in degrees.
    #[arg(long, value_name = "DEG", value_parser = parse_number, allow_hyphen_values = true, default_value_t = OBSERVER_ANGLE)]
    observer_angle: f32,
    /// The figure's size.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "1024x768")]
    draw_size: (u32, u32),
    /// Show the tree up to generation K only: 1 the eye ray and its shadow rays, 2 adds the first
    /// reflected and transmitted rays and theirs, … (default: all).
    #[arg(long, value_name = "K")]
    generations: Option<u32>,
    /// Draw the hidden parts of rays dashed instead of hiding them.
    #[arg(long)]
    xray: bool,
    /// Which tracer renders the scene for the figure: cpu or gpu.
    #[arg(long, default_value_t = Device::Cpu)]
    device: Device,
}

impl FigureArgs {
    /// Checks what can be checked before any tracing.
    pub fn check(&self) -> Result<(), String> {
        if self.generations == Some(0) {
            return Err(
                "--generations must be at least 1 (1: the eye ray and its shadow rays)".into(),
            );
        }
        let (width, height) = self.draw_size;
        check_image_size(width, height).map_err(|e| format!("--draw-size: {e}"))?;
        // The observer's film, its depths, the layer and the image written from them.
        let pixels = u64::from(width) * u64::from(height);
        let bytes = Film::memory_bytes(width, height) + pixels * FIGURE_BYTES_PER_PIXEL;
        memory::check(&format!("a {width}×{height} figure"), bytes)
            .map_err(|e| format!("--draw-size: {e}"))?;
        if let Some(path) = &self.draw {
            check_image_path(path).map_err(|e| format!("--draw: {e}"))?;
        }
        Ok(())
    }

    /// Writes the figure and the OBJ file asked for; `look_at` is the observer's `--look-at`.
    pub fn write(
        &self,
        tree: &RayTree,
        assembled: &Assembled,
        look_at: Option<Vec3>,
        backend: &mut Backend,
    ) -> Result<(), String> {
        let settings = &assembled.scene.settings;
        let generations = self.generations.unwrap_or(u32::MAX);
        let figure = RayFigure::new(
            tree,
            (&assembled.scene, &assembled.scene.camera),
            (settings.width, settings.height),
            generations,
        );
        if let Some(path) = &self.obj {
            let io = |e: std::io::Error| format!("--obj {}: {e}", path.display());
            write_atomically(path, io, |out| figure.write_obj(out).map_err(io))?;
            eprintln!(
                "ray tree: {} lines written to {}",
                figure.segments.len(),
                path.display()
            );
        }
        let Some(path) = &self.draw else {
            return Ok(());
        };
        let start = Instant::now();
        let (width, height) = self.draw_size;
        let side = side_view(
            &figure,
            &assembled.scene.camera,
            self.observer_angle,
            width as f32 / height as f32,
        );
        let spec = CameraSpec {
            eye: self.from.unwrap_or(side.eye),
            look_at: look_at.unwrap_or(side.look_at),
            view_angle: self.observer_angle,
            ..side
        };
        let observer = Camera::new(spec)
            .map_err(|e| format!("the observer (--from, --look-at, --observer-angle): {e}"))?;
        backend.set_device(self.device);
        let explain = |e| super::explain(e, DebugView::Shaded, FirstHit::Rays);
        let traced = image(&backend.render_image(assembled).map_err(explain)?.0);
        let seen = image(
            &backend
                .render_image(&observed(assembled, observer, self.draw_size))
                .map_err(explain)?
                .0,
        );
        let depths = observer_depths(&assembled.tracer(), &observer, self.draw_size);
        let (x, y) = tree.pixel;
        let depth = match self.generations {
            Some(1) => "generation 1".into(),
            Some(k) => format!("generations 1-{k}"),
            None => "all generations".into(),
        };
        let style = FigureStyle {
            xray: self.xray,
            highlight: None,
            legend: Some(format!("pixel ({x}, {y}), {depth}")),
        };
        let figure_image = draw(&figure, &observer, &seen, &depths, &traced, &style);
        save_image(path, width, height, &figure_image.to_linear()).map_err(|e| e.to_string())?;
        let at = |p: Vec3| format!("({:.3}, {:.3}, {:.3})", p.x, p.y, p.z);
        eprintln!(
            "figure: {} ({width}×{height}, observer at {} looking at {}, {}): {:.2} s",
            path.display(),
            at(spec.eye),
            at(spec.look_at),
            backend.label(),
            start.elapsed().as_secs_f64()
        );
        Ok(())
    }
}

/// The film as 8-bit sRGB.
fn image(film: &Film) -> SrgbImage {
    SrgbImage::from_linear(film.width(), film.height(), &film.pixels())
}
