//! What every BVH under comparison offers: built over the same triangles, it answers the same
//! rays. A closest-hit answer is the index of the triangle hit (−1 for none), an occlusion
//! answer is 1 or 0, as Embree's are written in the dump.

use crate::anchor::{AnchorMesh, AnchorRay, Query};

pub trait Tracer: Send + Sync + Sized {
    /// The name in the tables.
    const NAME: &'static str;

    /// Builds the BVH over `mesh`'s triangles, on the threads of the current rayon pool.
    fn build(mesh: &AnchorMesh) -> Result<Self, String>;

    /// The index of the nearest triangle hit in `(0, ray.tfar)`, −1 for none.
    fn closest(&self, ray: &AnchorRay) -> i32;

    /// Whether any triangle is hit in `(0, ray.tfar)`.
    fn occluded(&self, ray: &AnchorRay) -> bool;

    /// BVH nodes whose boxes the walk tested for `ray`, where the crate can tell.
    fn nodes_visited(&self, ray: &AnchorRay, query: Query) -> Option<u32>;

    /// The answer to `query` in Embree's terms.
    #[inline]
    fn answer(&self, ray: &AnchorRay, query: Query) -> i32 {
        match query {
            Query::Closest => self.closest(ray),
            Query::Occluded => i32::from(self.occluded(ray)),
        }
    }
}
