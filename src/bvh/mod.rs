//! The bounding volume hierarchy: a binary tree of boxes over all bounded primitives, built with
//! the surface area heuristic and flattened into an array of 32-byte nodes. Unbounded primitives
//! (planes) are kept in a list beside the tree and tested against every ray.

mod build;
mod traverse;

use crate::primitive::PrimId;

/// A node of the flattened tree. An interior node's children are `first` and `first + 1`; a
/// leaf holds primitives `first .. first + count` of [`Bvh::prims`]. 32 bytes: two nodes per
/// 64-byte cache line.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Node {
    pub min: [f32; 3],
    pub first: u32,
    pub max: [f32; 3],
    /// Number of primitives; 0 for an interior node.
    pub count: u32,
}

impl Node {
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }
}

#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// The tree, root first; empty when the scene has no bounded primitive.
    pub nodes: Vec<Node>,
    /// Bounded primitives in leaf order.
    pub prims: Vec<PrimId>,
    /// Primitives without bounds, tested against every ray.
    pub unbounded: Vec<PrimId>,
}

impl Bvh {
    /// Bytes held by the tree and its primitive list.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.capacity() * std::mem::size_of::<Node>()
            + (self.prims.capacity() + self.unbounded.capacity()) * std::mem::size_of::<PrimId>()
    }

    /// Depth of the tree (0 when empty), for statistics and tests.
    pub fn depth(&self) -> usize {
        fn depth_of(nodes: &[Node], i: usize) -> usize {
            let node = &nodes[i];
            if node.is_leaf() {
                1
            } else {
                let first = node.first as usize;
                1 + depth_of(nodes, first).max(depth_of(nodes, first + 1))
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            depth_of(&self.nodes, 0)
        }
    }
}
