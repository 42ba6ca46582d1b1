//! Ray counts: the rays the tracer traces, by kind, counted as it goes ([`RayCounts`]) and
//! summed across threads ([`SharedRayCounts`]).

use std::sync::atomic::{AtomicU64, Ordering};

/// Rays traced, by kind. Each worker counts into its own and adds it to the shared total once
/// per band of rows it traced ([`crate::progressive`]), so counting costs nothing per ray.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RayCounts {
    /// Eye rays, one per pixel sample.
    pub primary: u64,
    /// Eye rays that hit something.
    pub primary_hits: u64,
    /// Eye rays whose closest hit was searched for only up to their pixel's item in the item
    /// buffer, and found there ([`crate::item_buffer`]).
    pub from_item_buffer: u64,
    pub shadow: u64,
    pub reflected: u64,
    pub transmitted: u64,
    /// Reflected or transmitted rays not traced because their eye ray's tree had used up
    /// [`crate::whitted::RAY_BUDGET`]. Not rays: not in [`Self::total`].
    pub over_budget: u64,
}

impl RayCounts {
    pub fn total(&self) -> u64 {
        self.primary + self.shadow + self.reflected + self.transmitted
    }
}

impl std::ops::AddAssign for RayCounts {
    fn add_assign(&mut self, o: RayCounts) {
        self.primary += o.primary;
        self.primary_hits += o.primary_hits;
        self.from_item_buffer += o.from_item_buffer;
        self.shadow += o.shadow;
        self.reflected += o.reflected;
        self.transmitted += o.transmitted;
        self.over_budget += o.over_budget;
    }
}

impl std::ops::Sub for RayCounts {
    type Output = RayCounts;
    fn sub(self, o: RayCounts) -> RayCounts {
        RayCounts {
            primary: self.primary - o.primary,
            primary_hits: self.primary_hits - o.primary_hits,
            from_item_buffer: self.from_item_buffer - o.from_item_buffer,
            shadow: self.shadow - o.shadow,
            reflected: self.reflected - o.reflected,
            transmitted: self.transmitted - o.transmitted,
            over_budget: self.over_budget - o.over_budget,
        }
    }
}

/// [`RayCounts`] that threads add to.
#[derive(Debug, Default)]
pub struct SharedRayCounts {
    primary: AtomicU64,
    primary_hits: AtomicU64,
    from_item_buffer: AtomicU64,
    shadow: AtomicU64,
    reflected: AtomicU64,
    transmitted: AtomicU64,
    over_budget: AtomicU64,
}

impl SharedRayCounts {
    pub fn add(&self, c: &RayCounts) {
        self.primary.fetch_add(c.primary, Ordering::Relaxed);
        self.primary_hits
            .fetch_add(c.primary_hits, Ordering::Relaxed);
        self.from_item_buffer
            .fetch_add(c.from_item_buffer, Ordering::Relaxed);
        self.shadow.fetch_add(c.shadow, Ordering::Relaxed);
        self.reflected.fetch_add(c.reflected, Ordering::Relaxed);
        self.transmitted.fetch_add(c.transmitted, Ordering::Relaxed);
        self.over_budget.fetch_add(c.over_budget, Ordering::Relaxed);
    }

    pub fn get(&self) -> RayCounts {
        RayCounts {
            primary: self.primary.load(Ordering::Relaxed),
            primary_hits: self.primary_hits.load(Ordering::Relaxed),
            from_item_buffer: self.from_item_buffer.load(Ordering::Relaxed),
            shadow: self.shadow.load(Ordering::Relaxed),
            reflected: self.reflected.load(Ordering::Relaxed),
            transmitted: self.transmitted.load(Ordering::Relaxed),
            over_budget: self.over_budget.load(Ordering::Relaxed),
        }
    }
}
