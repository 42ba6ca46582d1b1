//! The shadow cache (Haines and Greenberg, 1986): the object that kept a light from one point
//! often keeps it from the next, since neighbouring pixels are traced one after another on the
//! same thread. So each thread remembers, for each light, the last opaque primitive that blocked
//! a shadow ray towards it, and the tracer tests that primitive first: if it blocks the new
//! shadow ray too, the point is in shadow without a walk through the BVH.
//!
//! What the cache holds is only a guess to try first. The tracer accepts it only after testing
//! it against the new ray in the current scene, so the answer is always the full search's.

use std::cell::RefCell;

use crate::primitive::PrimId;

thread_local! {
    /// Per light index, the primitive that last blocked it on this thread.
    static LAST_BLOCKER: RefCell<Vec<Option<PrimId>>> = const { RefCell::new(Vec::new()) };
}

/// The primitive that last blocked light `light` on this thread, if any.
pub fn last_blocker(light: usize) -> Option<PrimId> {
    LAST_BLOCKER.with_borrow(|blockers| blockers.get(light).copied().flatten())
}

/// Remembers `blocker` as the last blocker of light `light` on this thread (`None`: the last
/// shadow ray towards it had no opaque blocker).
pub fn remember(light: usize, blocker: Option<PrimId>) {
    LAST_BLOCKER.with_borrow_mut(|blockers| {
        if blockers.len() <= light {
            blockers.resize(light + 1, None);
        }
        blockers[light] = blocker;
    });
}
