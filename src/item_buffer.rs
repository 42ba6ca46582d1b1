//! The lecture's modified Z-buffer, the item buffer: for each pixel of a film, the primitive
//! that a raster pass over the scene found first along the eye ray through the pixel's centre,
//! and how far along that ray (`gpu::item_raster` draws one on the GPU).
//!
//! The CPU tracer fed with one ([`crate::whitted::Tracer::with_item_buffer`]) starts each eye
//! ray from its pixel's item: it intersects the named primitive with its own code, then walks
//! the BVH only up to that distance ([`far_limit`]). Any nearer surface that the raster's
//! rounding put elsewhere is still found, so the image is bit for bit the one a full search
//! makes, and the walk prunes every box beyond the first hit from the start. A pixel the raster
//! found empty, or whose primitive the CPU's ray misses (at a silhouette), is searched in full.
//!
//! The raster pass looks at each pixel's centre, where sample 0's eye ray passes. A jittered
//! sample of anti-aliasing takes its pixel's item too, tested along its own ray: each pixel's
//! jitter is its own ([`crate::sampling::jitter`]), while a raster pass samples every pixel at
//! the same point, so no raster pass finds the jittered samples' hits themselves.

use crate::primitive::{Geometry, PrimId};
use crate::ray::Ray;

/// What the raster pass found at one pixel: the primitive, the part of it (a CSG node's
/// operand) and the distance `t` along the pixel's eye ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Item {
    pub prim: PrimId,
    pub part: u32,
    pub t: f32,
}

/// The items of a film's pixels, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct ItemBuffer {
    /// The whole image's size, and where the film lies in it.
    image_size: (u32, u32),
    origin: (u32, u32),
    width: u32,
    height: u32,
    items: Vec<Option<Item>>,
}

impl ItemBuffer {
    /// The buffer of a film of `width × height` pixels at `origin` of an image of `image_size`,
    /// from its `items` row by row.
    ///
    /// # Panics
    /// When `items` does not hold one entry per pixel.
    pub fn new(
        image_size: (u32, u32),
        origin: (u32, u32),
        (width, height): (u32, u32),
        items: Vec<Option<Item>>,
    ) -> ItemBuffer {
        assert_eq!(
            items.len(),
            width as usize * height as usize,
            "one item per pixel"
        );
        ItemBuffer {
            image_size,
            origin,
            width,
            height,
            items,
        }
    }

    /// Whether this buffer is for a film of `size` at `origin` of an image of `image_size`.
    pub fn fits(&self, image_size: (u32, u32), origin: (u32, u32), size: (u32, u32)) -> bool {
        (self.image_size, self.origin, (self.width, self.height)) == (image_size, origin, size)
    }

    /// The item of film pixel (x, y), `None` where the raster pass drew nothing (or the pixel
    /// lies outside the film).
    pub fn at(&self, x: u32, y: u32) -> Option<Item> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.items[y as usize * self.width as usize + x as usize]
    }

    /// Every pixel's item, row by row from the top.
    pub fn items(&self) -> &[Option<Item>] {
        &self.items
    }
}

/// How far beyond its item's distance an eye ray's search looks, as a share of that distance.
/// The BVH's leaves test primitives four or eight at a time with SIMD, which rounds otherwise
/// than the test of one primitive alone: the same hit may lie a few units in the last place
/// further there. A margin far wider than that costs nothing measurable in pruning.
pub const FAR_MARGIN: f32 = 1e-4;

/// How far the closest-hit search beyond `t_min` for the eye ray `ray` through a pixel must
/// look, given the pixel's `item`: a little beyond where the CPU's own test meets the item's
/// primitive ([`FAR_MARGIN`]), so that any surface at that distance or nearer is found (and a
/// surface at exactly that distance that comes first in the scene still wins); `f32::INFINITY`
/// where there is no item or the CPU's ray misses its primitive.
pub fn far_limit(geometry: &Geometry, item: Option<Item>, ray: &Ray, t_min: f32) -> f32 {
    item.filter(|item| geometry.contains(item.prim))
        .and_then(|item| geometry.intersect(item.prim, ray, t_min, f32::INFINITY))
        .map_or(f32::INFINITY, |hit| (hit.t * (1.0 + FAR_MARGIN)).next_up())
}
