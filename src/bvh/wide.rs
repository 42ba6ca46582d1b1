//! From a binary tree to an eight-wide one. The builder makes a binary tree (the surface area
//! heuristic splits a set in two); traversal prefers eight children per node, tested at once
//! with SIMD, which divides the depth of the tree, and the number of dependent memory loads a
//! ray waits for, by about three. Each wide node takes its binary node's two children and
//! opens the largest of them (by surface area) that has children of its own, until it has
//! eight: the grandchildren that a ray is most likely to visit move up.

use super::{Child, Node, WIDTH, WideNode};
use crate::aabb::Aabb;

/// A node with no children yet. An unused slot's box lies at +∞ on every axis: the slab test
/// never enters it for a ray that stops at a finite distance (the traversal clamps its far
/// limit to `f32::MAX`).
const EMPTY: WideNode = WideNode {
    min: [[f32::INFINITY; WIDTH]; 3],
    max: [[f32::INFINITY; WIDTH]; 3],
    first: [0; WIDTH],
    count: [0; WIDTH],
};

/// The eight-wide tree over the binary tree `binary` (root first, children of an interior node
/// at `first` and `first + 1`). The root is node 0; when the binary root is a leaf it is the
/// wide root's only child. The interior children of a node follow one another, and each
/// child's subtree comes before the next child's children (depth first).
pub(super) fn collapse(binary: &[Node]) -> Vec<WideNode> {
    let mut wide = Vec::new();
    if !binary.is_empty() {
        wide.push(EMPTY);
        fill(binary, 0, &mut wide, 0);
    }
    wide.shrink_to_fit();
    wide
}

/// Writes into wide node `at` the children of binary node `node`, and their subtrees after it.
fn fill(binary: &[Node], node: usize, wide: &mut Vec<WideNode>, at: usize) {
    let children = wide_children(binary, node);
    let mut interior = arrayvec::ArrayVec::<_, WIDTH>::new();
    for (k, &c) in children.iter().enumerate() {
        let child = &binary[c];
        for axis in 0..3 {
            wide[at].min[axis][k] = child.min[axis];
            wide[at].max[axis][k] = child.max[axis];
        }
        let slot = if child.is_leaf() {
            Child {
                first: child.first,
                count: child.count,
            }
        } else {
            wide.push(EMPTY);
            interior.push((c, wide.len() - 1));
            Child::node(wide.len() as u32 - 1)
        };
        wide[at].first[k] = slot.first;
        wide[at].count[k] = slot.count;
    }
    for (c, index) in interior {
        fill(binary, c, wide, index);
    }
}

/// The up to [`WIDTH`] binary nodes that become the wide children of binary node `node`: its
/// children, with the largest interior one replaced by its own two children until there are
/// [`WIDTH`] or only leaves. A leaf `node` is its own only child.
fn wide_children(binary: &[Node], node: usize) -> arrayvec::ArrayVec<usize, WIDTH> {
    let mut children = arrayvec::ArrayVec::new();
    if binary[node].is_leaf() {
        children.push(node);
        return children;
    }
    let first = binary[node].first as usize;
    children.extend([first, first + 1]);
    while children.len() < WIDTH {
        let Some(largest) = (0..children.len())
            .filter(|&k| !binary[children[k]].is_leaf())
            .max_by(|&a, &b| area(&binary[children[a]]).total_cmp(&area(&binary[children[b]])))
        else {
            break;
        };
        // Replace the child by its own two children, in place.
        let opened = binary[children[largest]].first as usize;
        children[largest] = opened;
        children.insert(largest + 1, opened + 1);
    }
    children
}

fn area(node: &Node) -> f32 {
    Aabb::new(node.min.into(), node.max.into()).surface_area()
}
