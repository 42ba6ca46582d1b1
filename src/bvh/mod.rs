//! The bounding volume hierarchy: a tree of boxes over all bounded primitives, built with the
//! surface area heuristic as a binary tree (`build`), widened to four children per node
//! (`widen`) and flattened into an array of 32-byte nodes. Traversal (`traverse`) tests a
//! node's four children against a ray at once (`ray_box`); a tile of coherent eye rays walks
//! the tree once, together ([`packet`]). Unbounded primitives (planes) are kept in a list
//! beside the tree and tested against every ray.

mod build;
pub mod cost;
pub mod packet;
mod ray_box;
mod traverse;
mod widen;

use crate::aabb::Aabb;
use crate::primitive::PrimId;

/// Children per interior node of the finished tree.
pub const WIDTH: usize = 4;

/// A node of the flattened tree. An interior node's children are the two to [`WIDTH`] nodes
/// from `first`; a leaf holds primitives `first .. first + count` of [`Bvh::prims`]. 32 bytes,
/// aligned to 32 so that no node straddles two 64-byte cache lines.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct Node {
    pub min: [f32; 3],
    pub first: u32,
    pub max: [f32; 3],
    /// A leaf's number of primitives; an interior node's number of children plus
    /// [`Node::INTERIOR`].
    pub count: u32,
}

impl Node {
    /// The bit of `count` that marks an interior node.
    pub const INTERIOR: u32 = 1 << 31;

    pub fn is_leaf(&self) -> bool {
        self.count & Node::INTERIOR == 0
    }

    /// The indices of an interior node's children.
    pub fn children(&self) -> std::ops::Range<usize> {
        let count = (self.count & !Node::INTERIOR) as usize;
        self.first as usize..self.first as usize + count
    }
}

#[derive(Clone, Debug, Default)]
pub struct Bvh {
    /// The tree, root first, then [`WIDTH`] − 1 empty nodes, so that the traversal can load
    /// [`WIDTH`] nodes from any node's first child on; empty when the scene has no bounded
    /// primitive.
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

    /// The box around all bounded primitives (the root's), `None` when there are none.
    pub fn bounds(&self) -> Option<Aabb> {
        let root = self.nodes.first()?;
        Some(Aabb::new(root.min.into(), root.max.into()))
    }

    /// Depth of the tree (0 when empty), for statistics and tests.
    pub fn depth(&self) -> usize {
        fn depth_of(nodes: &[Node], i: usize) -> usize {
            let node = &nodes[i];
            if node.is_leaf() {
                1
            } else {
                1 + node
                    .children()
                    .map(|c| depth_of(nodes, c))
                    .max()
                    .unwrap_or(0)
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            depth_of(&self.nodes, 0)
        }
    }
}
