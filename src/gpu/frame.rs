//! The frame record: what the GPU tracer's WGSL reads once per render (`Frame` in
//! `shaders/scene.wgsl`): the camera, the image, the settings, the fog and the caustics'
//! numbers, and the view it draws ([`GpuView`]), with the switches of its flags.

use super::record::gpu_record;

gpu_record! {
    /// WGSL's `Frame`: the camera, the image and the settings.
    pub struct GpuFrame {
        pub eye: [f32; 3],
        pub near: f32,
        pub u: [f32; 3],
        pub half_height: f32,
        pub v: [f32; 3],
        pub width: u32,
        pub n: [f32; 3],
        pub height: u32,
        pub background: [f32; 3],
        pub max_depth: u32,
        pub ambient: [f32; 3],
        pub min_weight: f32,
        pub flags: u32,
        pub unbounded_first: u32,
        pub unbounded: u32,
        pub node_count: u32,
        pub light_count: u32,
        pub object_count: u32,
        pub film_left: u32,
        pub film_top: u32,
        /// The background image's texture record ([`super::texture::NO_TEXTURE`]: none).
        pub background_image: u32,
        /// `fog_steps`: the sample points of the light a medium scatters into a ray, per light.
        pub fog_steps: u32,
        /// The fog's [`crate::medium::Medium`]: its albedo, and below its colour and density (zero: no fog).
        pub fog_albedo: f32,
        /// The fog's [`crate::medium::Backdrop::Distance`] (unless [`BALL_BACKDROP`] is set).
        pub backdrop_distance: f32,
        pub fog_color: [f32; 3],
        pub fog_density: f32,
        /// The fog's [`crate::medium::Backdrop::Ball`] (where [`BALL_BACKDROP`] is set).
        pub backdrop_center: [f32; 3],
        pub backdrop_radius: f32,
        /// What the pixels show: a [`GpuView`]'s number.
        pub view: u32,
        /// The depth view's range ([`GpuView::Depth`]).
        pub depth_near: f32,
        pub depth_far: f32,
        /// `caustic_gather`: the photons each caustic estimate gathers.
        pub caustic_gather: u32,
        /// The caustic photon map ([`crate::photon_map::PhotonMap`]): the box around its photons, their number, how
        /// far an estimate looks at most, and how many photons were shot.
        pub photons_min: [f32; 3],
        pub photon_count: u32,
        pub photons_max: [f32; 3],
        pub photon_radius: f32,
        pub photons_shot: f32,
        pub pad0: u32,
        pub pad1: u32,
        pub pad2: u32,
    }
}

/// What the GPU's pixels show: the Whitted colour, or one of the debug views that look at the
/// eye ray's first hit (the twins of `inspect::DebugView`'s, which the CPU draws; the heat
/// maps of the whole ray tree are drawn on the CPU only).
#[derive(Clone, Copy, Debug, Default, PartialEq, strum::EnumDiscriminants)]
#[strum_discriminants(
    name(ViewKind),
    doc = "The kinds of view, one per variant of `GpuView`: the frame record names its view by its number.",
    derive(strum::EnumIter)
)]
pub enum GpuView {
    #[default]
    Shaded,
    Normals,
    /// Grey from white at `near` to black at `far`, along the view direction.
    Depth {
        near: f32,
        far: f32,
    },
    Uv,
    Object,
    Material,
}

/// Switches of [`GpuFrame::flags`], as `shaders/scene.wgsl` names them.
pub const SHADOWS: u32 = 1;
pub const REFLECTIONS: u32 = 2;
pub const TRANSMISSION: u32 = 4;
pub const OPAQUE: u32 = 8;
pub const TEXTURES: u32 = 16;
/// The fog's backdrop is the ball around the scene ([`crate::medium::Backdrop::Ball`]).
pub const BALL_BACKDROP: u32 = 32;
/// Caustics are on: the photon map brings the light that glass bends.
pub const CAUSTICS: u32 = 64;
/// A material cuts its surface away by its texture's alpha: searches go on past cut-away hits.
pub const CUT_OUTS: u32 = 128;
