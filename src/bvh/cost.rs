//! The cost of a walk through the BVH: how many nodes it visited and how many primitives it
//! tested. The traversal takes a [`TraversalCost`]; the renderer passes `()`, whose methods do
//! nothing and vanish when compiled, and the BVH cost view passes a [`BvhCost`] that counts.

/// Told of every node visited and every primitive tested during a traversal.
pub trait TraversalCost {
    /// An interior node's four child boxes were tested against the ray.
    #[inline(always)]
    fn node_visited(&mut self) {}
    /// `count` primitives were tested against the ray.
    #[inline(always)]
    fn prims_tested(&mut self, count: usize) {
        let _ = count;
    }
}

/// Counts nothing: the renderer's traversal.
impl TraversalCost for () {}

/// Nodes visited and primitives tested, summed over any number of rays.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BvhCost {
    pub nodes: u64,
    pub prims: u64,
}

impl BvhCost {
    /// Nodes and primitives together: the cost the heat map shows.
    pub fn total(&self) -> u64 {
        self.nodes + self.prims
    }
}

impl TraversalCost for BvhCost {
    #[inline(always)]
    fn node_visited(&mut self) {
        self.nodes += 1;
    }
    #[inline(always)]
    fn prims_tested(&mut self, count: usize) {
        self.prims += count as u64;
    }
}
