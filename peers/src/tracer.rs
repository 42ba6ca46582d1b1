//! What every BVH under comparison offers: built over the same triangles, it answers the same
//! rays. A closest-hit answer is the index of the triangle hit (−1 for none), an occlusion
//! answer is 1 or 0, as Embree's are written in the dump.

use crate::anchor::{AnchorMesh, AnchorRay, Query};

/// The cost of one walk, counted the same way for every crate.
#[derive(Clone, Copy, Debug, Default)]
pub struct WalkCost {
    /// Interior nodes visited: nodes whose children's boxes were tested against the ray (two
    /// boxes in the `bvh` crate's binary tree, up to four in raylab's, up to eight in `obvhs`'s).
    pub nodes: u32,
    /// Triangles tested against the ray.
    pub triangles: u32,
}

pub trait Tracer: Send + Sync + Sized {
    /// The name in the tables.
    const NAME: &'static str;

    /// Builds the BVH over `mesh`'s triangles, on the threads of the current rayon pool.
    fn build(mesh: &AnchorMesh) -> Result<Self, String>;

    /// The index of the nearest triangle hit in `(0, ray.tfar)`, −1 for none.
    fn closest(&self, ray: &AnchorRay) -> i32;

    /// Whether any triangle is hit in `(0, ray.tfar)`.
    fn occluded(&self, ray: &AnchorRay) -> bool;

    /// What the walk for `query` cost on `ray`, where the crate can tell; traced apart from the
    /// timed runs, so counting never slows them.
    fn cost(&self, ray: &AnchorRay, query: Query) -> Option<WalkCost>;

    /// [`Self::closest`] of up to 64 neighbouring camera rays (an 8 × 8 tile) into `answers`:
    /// one by one, unless the crate traces packets.
    fn closest_in_packet(&self, rays: &[AnchorRay], answers: &mut [i32]) {
        for (ray, answer) in rays.iter().zip(answers) {
            *answer = self.closest(ray);
        }
    }

    /// The answer to `query` in Embree's terms.
    #[inline]
    fn answer(&self, ray: &AnchorRay, query: Query) -> i32 {
        match query {
            Query::Closest => self.closest(ray),
            Query::Occluded => i32::from(self.occluded(ray)),
        }
    }
}
