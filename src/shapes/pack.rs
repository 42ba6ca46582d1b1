//! What the packs of shapes tested four at a time share: their size, and for the packs of
//! objects placed in the world (spheres, open cylinders, small polygons) the hits they report
//! and the one way they are tested ([`ObjectPack`]).

use glam::Vec4;

use crate::ray::Ray;

/// Shapes in one pack: one per lane of an SSE register.
pub const PACK_SIZE: usize = 4;

/// The lanes of a pack of objects that a ray hits: bit k of `mask` where it hits object k, at
/// `t[k]`.
#[derive(Clone, Copy, Debug)]
pub struct LaneHits {
    pub mask: u32,
    /// Each lane's `t`, in a register rather than an array: a pack's hits are returned by
    /// value, and four floats stored one by one and read back as a block stall the load.
    pub t: Vec4,
}

/// Four objects of one kind tested against a ray at once, each lane giving exactly what the
/// object's own test gives.
pub trait ObjectPack {
    /// Which objects `ray` hits with `t` in `(t_min, t_max)`, and where.
    fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> LaneHits;
    /// Each lane's number for the caller (`u32::MAX` for an unused lane).
    fn tags(&self) -> &[u32; PACK_SIZE];
}
