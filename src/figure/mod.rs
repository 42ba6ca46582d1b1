//! The lecture's ray-tree figure: one pixel's ray tree drawn in the scene and seen from an
//! observer camera other than the scene's. The lines ([`RayFigure`]: the eye ray, each hit's
//! normal, shadow rays to the lights or their blockers, reflected and transmitted rays
//! generation by generation, the scene camera's image plane with the pixel's cell) are drawn
//! ([`draw`]) over the scene as the observer sees it, which any tracer renders
//! ([`observed`]), hidden where a surface lies in front of them ([`observer_depths`]). The same
//! lines are written as OBJ polylines ([`RayFigure::write_obj`]).
//!
//! ```
//! use raylab::figure::{FigureStyle, RayFigure, draw, observed, observer_depths, side_view};
//! use raylab::camera::Camera;
//! use raylab::formats::load_any;
//! use raylab::inspect::trace_ray_tree;
//! use raylab::render::assemble;
//! use raylab::srgb_image::SrgbImage;
//!
//! let mut scene = load_any("assets/scenes/glass.toml")?;
//! scene.settings.width = 64;
//! scene.settings.height = 48;
//! let assembled = assemble(scene)?;
//! let tree = trace_ray_tree(&assembled.tracer(), 32, 24);
//! let figure = RayFigure::new(&tree, (&assembled.scene, &assembled.scene.camera), (64, 48), 3);
//!
//! // The observer, from the side, and the scene as it sees it.
//! let size = (160, 120);
//! let observer = Camera::new(side_view(&figure, &assembled.scene.camera, 45.0, 4.0 / 3.0))?;
//! let mut backend = raylab::backend::Backend::on_all_cores()?;
//! let mut shade = |a: &raylab::render::Assembled| {
//!     let (film, _) = backend.render_image(a).expect("the CPU renders any view");
//!     SrgbImage::from_linear(film.width(), film.height(), &film.pixels())
//! };
//! let seen = shade(&observed(&assembled, observer, size));
//! let depths = observer_depths(&assembled.tracer(), &observer, size);
//! let image = draw(&figure, &observer, &seen, &depths, &shade(&assembled), &FigureStyle::default());
//! assert_eq!((image.width, image.height), size);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod draw;
mod layer;
mod legend;
mod observer;
mod segments;

pub use draw::{FigureStyle, draw, draw_layer};
pub use layer::{Layer, line_width};
pub use legend::area as legend_area;
pub use observer::{OBSERVER_ANGLE, observed, observer_depths, side_view, view_depth};
pub use segments::{RayFigure, Segment, SegmentKind};
