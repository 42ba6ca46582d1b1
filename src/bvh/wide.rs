//! From a binary tree to an eight-wide one with its leaves laid out for the tests. The builder
//! makes a binary tree (the surface area heuristic splits a set in two); traversal prefers
//! eight children per node, tested at once with SIMD, which divides the depth of the tree, and
//! the number of dependent memory loads a ray waits for, by about three. Each wide node takes
//! its binary node's two children and opens the largest of them (by surface area) that has
//! children of its own, until it has eight: the grandchildren that a ray is most likely to
//! visit move up.
//!
//! A binary leaf becomes one wide child per kind of primitive in it: its triangles, copied
//! into [`TrianglePack`]s of four in leaf order, and its objects, listed in leaf order.

use arrayvec::ArrayVec;

use super::{Child, Node, WIDTH, WideNode};
use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId};
use crate::shapes::{PACK_SIZE, TrianglePack};

/// A node with no children yet. An unused slot's box lies at +∞ on every axis: the slab test
/// never enters it for a ray that stops at a finite distance (the traversal clamps its far
/// limit to `f32::MAX`).
const EMPTY: WideNode = WideNode {
    min: [[f32::INFINITY; WIDTH]; 3],
    max: [[f32::INFINITY; WIDTH]; 3],
    first: [0; WIDTH],
    count: [0; WIDTH],
};

/// The eight-wide tree and its leaves.
pub(super) struct Collapsed {
    pub nodes: Vec<WideNode>,
    pub packs: Vec<TrianglePack>,
    pub objects: Vec<PrimId>,
}

/// The eight-wide tree over the binary tree `binary` (root first, children of an interior node
/// at `first` and `first + 1`, leaves pointing into `prims`). The root is node 0; when the
/// binary root is a leaf it is the wide root's only child. The interior children of a node
/// follow one another, and each child's subtree comes before the next child's children (depth
/// first), as do the leaves' packs and objects.
pub(super) fn collapse(binary: &[Node], prims: &[PrimId], geometry: &Geometry) -> Collapsed {
    let mut out = Collapsed {
        nodes: Vec::new(),
        packs: Vec::with_capacity(prims.len().div_ceil(PACK_SIZE)),
        objects: Vec::new(),
    };
    if !binary.is_empty() {
        let mut collapse = Collapse {
            binary,
            prims,
            geometry,
            out: &mut out,
        };
        collapse.out.nodes.push(EMPTY);
        collapse.fill(0, 0);
    }
    out.nodes.shrink_to_fit();
    out.packs.shrink_to_fit();
    out.objects.shrink_to_fit();
    out
}

struct Collapse<'a> {
    binary: &'a [Node],
    prims: &'a [PrimId],
    geometry: &'a Geometry,
    out: &'a mut Collapsed,
}

impl Collapse<'_> {
    /// Writes into wide node `at` the children of binary node `node`, and their subtrees after.
    fn fill(&mut self, node: usize, at: usize) {
        let mut slots: ArrayVec<(Aabb, Child), WIDTH> = ArrayVec::new();
        let mut interior: ArrayVec<(usize, usize), WIDTH> = ArrayVec::new();
        for c in self.wide_children(node) {
            let child = &self.binary[c];
            let bounds = Aabb::new(child.min.into(), child.max.into());
            if child.is_leaf() {
                for leaf in self.leaf(child) {
                    slots.push((bounds, leaf));
                }
            } else {
                self.out.nodes.push(EMPTY);
                let index = self.out.nodes.len() - 1;
                interior.push((c, index));
                slots.push((bounds, Child::node(index as u32)));
            }
        }
        let wide = &mut self.out.nodes[at];
        for (k, (bounds, child)) in slots.into_iter().enumerate() {
            for axis in 0..3 {
                wide.min[axis][k] = bounds.min[axis];
                wide.max[axis][k] = bounds.max[axis];
            }
            wide.first[k] = child.first;
            wide.count[k] = child.count;
        }
        for (c, index) in interior {
            self.fill(c, index);
        }
    }

    /// The one or two wide children of a binary leaf: its triangles in packs, its objects.
    fn leaf(&mut self, leaf: &Node) -> ArrayVec<Child, 2> {
        let prims = &self.prims[leaf.first as usize..][..leaf.count as usize];
        let mut children = ArrayVec::new();
        let triangles: Vec<_> = prims
            .iter()
            .filter_map(|&id| id.kind().err().map(|t| (self.geometry.triangle(t), id.0)))
            .collect();
        if !triangles.is_empty() {
            let first = self.out.packs.len() as u32;
            let packs = triangles.chunks(PACK_SIZE).map(TrianglePack::new);
            self.out.packs.extend(packs);
            children.push(Child::triangles(first, self.out.packs.len() as u32 - first));
        }
        let objects = prims.iter().filter(|id| id.kind().is_ok());
        let first = self.out.objects.len() as u32;
        self.out.objects.extend(objects);
        if self.out.objects.len() as u32 > first {
            children.push(Child::objects(first, self.out.objects.len() as u32 - first));
        }
        children
    }

    /// The binary nodes that become the wide children of binary node `node`: its children,
    /// with the largest interior one replaced by its own two children while the slots they
    /// take (a leaf with triangles and objects takes two) fit in [`WIDTH`]. A leaf `node` is
    /// its own only child.
    fn wide_children(&self, node: usize) -> ArrayVec<usize, WIDTH> {
        let binary = self.binary;
        let mut children = ArrayVec::new();
        if binary[node].is_leaf() {
            children.push(node);
            return children;
        }
        let first = binary[node].first as usize;
        children.extend([first, first + 1]);
        let mut used: usize = children.iter().map(|&c| self.slots(c)).sum();
        loop {
            let opens = |&k: &usize| {
                let c = &binary[children[k]];
                !c.is_leaf() && used - 1 + self.slots_of_children(c) <= WIDTH
            };
            let Some(largest) = (0..children.len())
                .filter(opens)
                .max_by(|&a, &b| area(&binary[children[a]]).total_cmp(&area(&binary[children[b]])))
            else {
                break;
            };
            // Replace the child by its own two children, in place.
            let opened = &binary[children[largest]];
            used = used - 1 + self.slots_of_children(opened);
            children[largest] = opened.first as usize;
            children.insert(largest + 1, opened.first as usize + 1);
        }
        children
    }

    /// Wide slots binary node `c` takes: two for a leaf of triangles and objects, else one.
    fn slots(&self, c: usize) -> usize {
        let node = &self.binary[c];
        if !node.is_leaf() {
            return 1;
        }
        let prims = &self.prims[node.first as usize..][..node.count as usize];
        let objects = prims.iter().filter(|id| id.kind().is_ok()).count();
        1 + usize::from(objects > 0 && objects < prims.len())
    }

    fn slots_of_children(&self, interior: &Node) -> usize {
        let first = interior.first as usize;
        self.slots(first) + self.slots(first + 1)
    }
}

fn area(node: &Node) -> f32 {
    Aabb::new(node.min.into(), node.max.into()).surface_area()
}
