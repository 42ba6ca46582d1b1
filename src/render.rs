//! Where a render is assembled, as pbrt's `render.cpp` does it: a scene is given its BVH, the
//! caustic photons its settings ask for are shot with a tracer over both, and
//! [`Assembled::tracer`] hands out the Whitted tracer over all three. Every program assembles its
//! renders here (`raylab render`, `inspect` and `bench`, the viewer, the examples and the image
//! tests), so that the same scene gives the same image everywhere. A second tracer backend plugs
//! in here too: it takes what is assembled.
//!
//! ```
//! use raylab::formats::load_any;
//! use raylab::progressive::render_image;
//! use raylab::render::assemble;
//!
//! let mut scene = load_any("assets/scenes/caustic_ring.toml")?;
//! (scene.settings.width, scene.settings.height) = (32, 24);
//! let assembled = assemble(scene)?; // scene → BVH → caustic photons
//! assert!(assembled.caustics.is_some());
//! let (pixels, _) = render_image(&assembled.tracer()); // → image
//! assert_eq!(pixels.len(), 32 * 24);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::bvh::Bvh;
use crate::photon::{PhotonMap, caustic_map};
use crate::scene::Scene;
use crate::whitted::Tracer;

/// Which tracer renders: the CPU's, on all cores, or the GPU's (`gpu`, with the `gpu` feature).
/// The command line and the viewer name them `cpu` and `gpu`.
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase", parse_err_ty = String, parse_err_fn = unknown_device)]
pub enum Device {
    #[default]
    Cpu,
    Gpu,
}

fn unknown_device(s: &str) -> String {
    use strum::VariantNames;
    unknown_choice("device", s, Device::VARIANTS)
}

/// Why `s` is none of the `choices` of `what`.
fn unknown_choice(what: &str, s: &str, choices: &[&str]) -> String {
    format!("unknown {what} `{s}` (use one of: {})", choices.join(", "))
}

/// Where a render's eye rays find their first hits: by searching the BVH (`rays`), or starting
/// from the item buffer a raster pass drew on the GPU (`raster`, the lecture's modified
/// Z-buffer, [`crate::item_buffer`]). The image is the same either way.
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase", parse_err_ty = String, parse_err_fn = unknown_first_hit)]
pub enum FirstHit {
    #[default]
    Rays,
    Raster,
}

fn unknown_first_hit(s: &str) -> String {
    use strum::VariantNames;
    unknown_choice("first-hit search", s, FirstHit::VARIANTS)
}

/// What a render needs: the scene, its BVH and its caustic photon map. The BVH and the map are
/// shared, so that copies of the scene (the viewer's, with the user's camera and edits) trace
/// without building them again.
#[derive(Clone, Debug)]
pub struct Assembled {
    pub scene: Scene,
    pub bvh: Arc<Bvh>,
    /// The caustic photon map; `None` with caustics off or not shot yet.
    pub caustics: Option<Arc<PhotonMap>>,
    /// The time the BVH took to build, and the caustic photons to shoot.
    pub bvh_time: Duration,
    pub caustics_time: Duration,
}

/// Assembles a render of `scene`: builds its BVH and shoots the caustic photons its settings ask
/// for, on the current rayon thread pool. The error says the photons would not fit in memory.
pub fn assemble(scene: Scene) -> Result<Assembled, String> {
    let mut assembled = Assembled::without_caustics(scene);
    assembled.shoot_caustics()?;
    Ok(assembled)
}

impl Assembled {
    /// The scene and its BVH, without caustic photons (a viewer shoots them round by round).
    pub fn without_caustics(scene: Scene) -> Assembled {
        let start = Instant::now();
        let bvh = Arc::new(Bvh::build(&scene.geometry));
        Assembled {
            scene,
            bvh,
            caustics: None,
            bvh_time: start.elapsed(),
            caustics_time: Duration::ZERO,
        }
    }

    /// Shoots the scene's `caustic_photons` into a new caustic photon map (none with caustics
    /// off). The error says the photons would not fit in memory.
    pub fn shoot_caustics(&mut self) -> Result<(), String> {
        let start = Instant::now();
        let count = self.scene.settings.caustic_photons;
        self.caustics = match count {
            0 => None,
            _ => Some(Arc::new(caustic_map(
                &Tracer::new(&self.scene, &self.bvh),
                count,
            )?)),
        };
        self.caustics_time = start.elapsed();
        Ok(())
    }

    /// The Whitted tracer of the scene, with the light of the caustic photon map if there is one.
    pub fn tracer(&self) -> Tracer<'_> {
        Tracer::new(&self.scene, &self.bvh).with_caustics(self.caustics.as_deref())
    }
}
