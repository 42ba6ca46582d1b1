//! From a binary tree to a four-wide one. The builder makes a binary tree (the surface area
//! heuristic splits a set in two); traversal prefers four children per node, tested at once
//! with SIMD, which halves the depth of the tree and the number of dependent memory loads a ray
//! waits for. Each wide node takes its binary node's two children and opens the largest of them
//! (by surface area) that has children of its own, until it has four: the grandchildren that a
//! ray is most likely to visit move one level up.

use super::{Node, WIDTH};
use crate::aabb::Aabb;

/// Padding after the last node: an empty leaf whose box no ray enters.
const EMPTY_SLOT: Node = Node {
    min: [f32::INFINITY; 3],
    first: 0,
    max: [f32::NEG_INFINITY; 3],
    count: 0,
};

/// The four-wide tree over the binary tree `binary` (root first, children of an interior node at
/// `first` and `first + 1`). The root stays at index 0; the two to `WIDTH` children of an
/// interior node follow one another from `first`, in depth-first order, with no unused slots
/// between groups. `WIDTH − 1` empty leaves at the end let the traversal load `WIDTH` nodes
/// from any group.
pub(super) fn widen(binary: &[Node]) -> Vec<Node> {
    let mut wide = Vec::with_capacity(binary.len() + WIDTH);
    if let Some(&root) = binary.first() {
        wide.push(root);
        add_children(binary, 0, &mut wide, 0);
        wide.extend([EMPTY_SLOT; WIDTH - 1]);
    }
    wide.shrink_to_fit();
    wide
}

/// Gives slot `at` of `wide`, a copy of binary node `node`, its wide children, and so on down.
fn add_children(binary: &[Node], node: usize, wide: &mut Vec<Node>, at: usize) {
    if binary[node].is_leaf() {
        return;
    }
    let first = binary[node].first as usize;
    let mut children = [0; WIDTH];
    children[..2].copy_from_slice(&[first, first + 1]);
    let mut count = 2;
    while count < WIDTH {
        let Some(largest) = (0..count)
            .filter(|&k| !binary[children[k]].is_leaf())
            .max_by(|&a, &b| area(&binary[children[a]]).total_cmp(&area(&binary[children[b]])))
        else {
            break;
        };
        // Replace the child by its own two children, in place.
        let opened = binary[children[largest]].first as usize;
        children.copy_within(largest + 1..count, largest + 2);
        children[largest] = opened;
        children[largest + 1] = opened + 1;
        count += 1;
    }
    let group = wide.len();
    wide.extend(children[..count].iter().map(|&c| binary[c]));
    wide[at].first = group as u32;
    wide[at].count = Node::INTERIOR | count as u32;
    for (k, &child) in children[..count].iter().enumerate() {
        add_children(binary, child, wide, group + k);
    }
}

fn area(node: &Node) -> f32 {
    Aabb::new(node.min.into(), node.max.into()).surface_area()
}
