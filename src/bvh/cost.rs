//! The cost of a walk through the BVH: how many nodes it visited and how many primitives it
//! tested. The traversal takes a [`TraversalCost`]; the renderer passes `()`, whose methods do
//! nothing and vanish when compiled, and the BVH cost view passes a [`BvhCost`] that counts.
//! `sah_cost` estimates a whole tree's cost for a ray, as the builder does for one split.

use super::build::{TRAVERSAL_COST, binary_tree, tests};
use super::leaf::LeafKind;
use super::{Bvh, Node};
use crate::aabb::Aabb;
use crate::primitive::Geometry;

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

/// The surface area heuristic's estimate of a tree's cost: the expected number of node visits
/// (each costing [`TRAVERSAL_COST`]) and primitive tests of a ray that passes through the
/// root's box, with the chance of entering a node taken as its surface area over the root's.
/// A leaf of packed primitives costs a test per pack of four, as the traversal tests
/// them; a leaf of objects one per object. `nodes` is the builder's binary tree (root first,
/// an interior node's children at `first` and `first + 1`, a leaf's primitives `first..`, whose
/// kinds are `kinds[first..]`;
/// [`super::Bvh::binary_tree_cost`] measures the builder's): the lower, the fewer boxes and
/// primitives a ray is expected to test. 0 for an empty tree.
pub(super) fn sah_cost(nodes: &[Node], kinds: &[LeafKind]) -> f64 {
    let Some(root) = nodes.first() else {
        return 0.0;
    };
    let area = |node: &Node| Aabb::new(node.min.into(), node.max.into()).surface_area() as f64;
    let root_area = area(root).max(f64::MIN_POSITIVE);
    let mut cost = 0.0;
    let mut stack = vec![0];
    while let Some(i) = stack.pop() {
        let node = &nodes[i];
        if node.is_leaf() {
            // A leaf holds one kind of primitive: its first says which.
            let block = kinds[node.first as usize].block();
            cost += area(node) * tests(node.count, block) as f64;
        } else {
            cost += area(node) * TRAVERSAL_COST as f64;
            stack.extend([node.first as usize, node.first as usize + 1]);
        }
    }
    cost / root_area
}

impl Bvh {
    /// The SAH cost (`sah_cost`) of the binary tree that [`Bvh::build`] collapses, and its
    /// number of nodes: for measuring the builder. `(0, 0)` when nothing is bounded.
    pub fn binary_tree_cost(geometry: &Geometry) -> (f64, usize) {
        match binary_tree(geometry) {
            Some((tree, kinds)) => (sah_cost(&tree, &kinds), tree.len()),
            None => (0.0, 0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(min: [f32; 3], max: [f32; 3], first: u32, count: u32) -> Node {
        Node {
            min,
            first,
            max,
            count,
        }
    }

    #[test]
    fn sah_cost_weighs_each_node_by_its_area_and_packs_triangles() {
        // A unit cube (area 6) split into two halves (area 4 each): one object on the left,
        // five triangles on the right (two packs).
        let tree = [
            node([0.0; 3], [1.0; 3], 1, Node::INTERIOR | 2),
            node([0.0; 3], [0.5, 1.0, 1.0], 0, 1),
            node([0.5, 0.0, 0.0], [1.0; 3], 1, 5),
        ];
        let kinds = [LeafKind::Objects]
            .into_iter()
            .chain([LeafKind::Triangles; 5])
            .collect::<Vec<_>>();
        let expected = TRAVERSAL_COST as f64 + (4.0 * 1.0 + 4.0 * 2.0) / 6.0;
        let cost = sah_cost(&tree, &kinds);
        assert!((cost - expected).abs() < 1e-9, "{cost}");
        assert_eq!(sah_cost(&tree[1..2], &kinds), 1.0);
        assert_eq!(sah_cost(&[], &[]), 0.0);
    }
}
