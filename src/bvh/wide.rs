//! From a binary tree to an eight-wide one with its leaves laid out for the tests. The builder
//! makes a binary tree (the surface area heuristic splits a set in two); traversal prefers
//! eight children per node, tested at once with SIMD, which divides the depth of the tree, and
//! the number of dependent memory loads a ray waits for, by about three. Each wide node takes
//! its binary node's two children and opens the largest of them (by surface area) that has
//! children of its own, until it has eight: the grandchildren that a ray is most likely to
//! visit move up.
//!
//! A binary leaf holds one [`LeafKind`] of primitive (the builder makes sure of it): triangles,
//! spheres, cylinders or polygons, copied into packs of four in leaf order, or other objects, listed in
//! leaf order. The walk down the tree only counts out the triangle packs; they are filled
//! afterwards on all threads, since a large mesh's copy of its triangles is most of the work.

use std::ops::Range;

use arrayvec::ArrayVec;
use rayon::prelude::*;

use super::leaf::LeafKind;
use super::{Child, Node, WIDTH, WideNode};
use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId};
use crate::shapes::{CylinderPack, PACK_SIZE, PolygonPack, Shape, SpherePack, TrianglePack};

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
    pub spheres: Vec<SpherePack>,
    pub cylinders: Vec<CylinderPack>,
    pub polygons: Vec<PolygonPack>,
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
        packs: Vec::new(),
        spheres: Vec::new(),
        cylinders: Vec::new(),
        polygons: Vec::new(),
        objects: Vec::new(),
    };
    let mut triangle_packs = Vec::new();
    if !binary.is_empty() {
        let mut collapse = Collapse {
            binary,
            prims,
            geometry,
            out: &mut out,
            triangle_packs: &mut triangle_packs,
        };
        collapse.out.nodes.push(EMPTY);
        collapse.fill(0, 0);
    }
    // An indexed parallel iterator collects into one allocation of the exact size.
    out.packs = triangle_packs
        .into_par_iter()
        .map(|range| {
            let ids = &prims[range];
            // A pack's triangles are read together; a pack of fewer reads its last one again.
            let triangle = |k: usize| {
                let id = ids[k.min(ids.len() - 1)];
                id.kind()
                    .expect_err("a leaf of triangles holds only triangles")
            };
            let triangles = geometry.triangles(std::array::from_fn::<_, PACK_SIZE, _>(triangle));
            let lanes: ArrayVec<_, PACK_SIZE> = triangles
                .into_iter()
                .zip(ids)
                .map(|(triangle, id)| (triangle, id.0))
                .collect();
            TrianglePack::new(&lanes)
        })
        .collect();
    out.nodes.shrink_to_fit();
    out.spheres.shrink_to_fit();
    out.cylinders.shrink_to_fit();
    out.polygons.shrink_to_fit();
    out.objects.shrink_to_fit();
    out
}

struct Collapse<'a> {
    binary: &'a [Node],
    prims: &'a [PrimId],
    geometry: &'a Geometry,
    out: &'a mut Collapsed,
    /// Where in `prims` the primitives of each triangle pack are, in pack order: the packs
    /// are filled once the tree is done.
    triangle_packs: &'a mut Vec<Range<usize>>,
}

impl Collapse<'_> {
    /// Writes into wide node `at` the children of binary node `node`, and their subtrees after.
    fn fill(&mut self, node: usize, at: usize) {
        let mut interior: ArrayVec<(usize, usize), WIDTH> = ArrayVec::new();
        for (k, c) in self.wide_children(node).into_iter().enumerate() {
            let child = &self.binary[c];
            let slot = if child.is_leaf() {
                self.leaf(child)
            } else {
                self.out.nodes.push(EMPTY);
                let index = self.out.nodes.len() - 1;
                interior.push((c, index));
                Child::node(index as u32)
            };
            let wide = &mut self.out.nodes[at];
            for axis in 0..3 {
                wide.min[axis][k] = child.min[axis];
                wide.max[axis][k] = child.max[axis];
            }
            wide.first[k] = slot.first;
            wide.count[k] = slot.count;
        }
        for (c, index) in interior {
            self.fill(c, index);
        }
    }

    /// The wide child of a binary leaf: its primitives in packs, or its objects.
    fn leaf(&mut self, leaf: &Node) -> Child {
        let prims = &self.prims[leaf.first as usize..][..leaf.count as usize];
        let geometry = self.geometry;
        let out = &mut *self.out;
        let kind = LeafKind::of(geometry, prims[0]);
        // The shape of object `id`, which the builder put in a leaf of its kind.
        let shape = |id: PrimId| {
            let object = id
                .kind()
                .expect("a leaf of packed objects holds only objects");
            &geometry.objects[object].shape
        };
        let mixed = || unreachable!("a leaf holds one kind of primitive");
        let (first, count) = match kind {
            LeafKind::Objects => {
                out.objects.extend_from_slice(prims);
                (out.objects.len() - prims.len(), prims.len())
            }
            LeafKind::Spheres => add_packs(&mut out.spheres, prims, SpherePack::new, |id| {
                let Shape::Sphere(sphere) = shape(id) else {
                    mixed()
                };
                sphere
            }),
            LeafKind::Cylinders => add_packs(&mut out.cylinders, prims, CylinderPack::new, |id| {
                let Shape::TaperedCylinder(cylinder) = shape(id) else {
                    mixed()
                };
                cylinder
            }),
            LeafKind::Polygons => add_packs(&mut out.polygons, prims, PolygonPack::new, |id| {
                let Shape::Polygon(polygon) = shape(id) else {
                    mixed()
                };
                polygon
            }),
            LeafKind::Triangles => {
                let first = self.triangle_packs.len();
                let start = leaf.first as usize;
                let end = start + prims.len();
                let packs = (start..end).step_by(PACK_SIZE);
                let ranges = packs.map(|pack| pack..(pack + PACK_SIZE).min(end));
                self.triangle_packs.extend(ranges);
                (first, self.triangle_packs.len() - first)
            }
        };
        Child::leaf_of(kind, first as u32, count as u32)
    }

    /// The binary nodes that become the wide children of binary node `node`: its children,
    /// with the largest interior one replaced by its own two children until there are
    /// [`WIDTH`] or only leaves. A leaf `node` is its own only child.
    fn wide_children(&self, node: usize) -> ArrayVec<usize, WIDTH> {
        let binary = self.binary;
        let mut children = ArrayVec::new();
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
}

/// Appends to `packs` the primitives `prims` in packs of four, each lane made by `pack` from
/// what `lane` gives for a primitive and tagged with its id. Where they start in `packs`, and
/// how many.
fn add_packs<P, T>(
    packs: &mut Vec<P>,
    prims: &[PrimId],
    pack: impl Fn(&[(T, u32)]) -> P,
    lane: impl Fn(PrimId) -> T,
) -> (usize, usize) {
    let first = packs.len();
    for four in prims.chunks(PACK_SIZE) {
        let lanes: ArrayVec<(T, u32), PACK_SIZE> =
            four.iter().map(|&id| (lane(id), id.0)).collect();
        packs.push(pack(&lanes));
    }
    (first, packs.len() - first)
}

fn area(node: &Node) -> f32 {
    Aabb::new(node.min.into(), node.max.into()).surface_area()
}
