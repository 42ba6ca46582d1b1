//! From a binary tree to an eight-wide one with its leaves laid out for the tests. The builder
//! makes a binary tree (the surface area heuristic splits a set in two); traversal prefers
//! eight children per node, tested at once with SIMD, which divides the depth of the tree, and
//! the number of dependent memory loads a ray waits for, by about three. Each wide node takes
//! its binary node's two children and opens the largest of them (by surface area) that has
//! children of its own, until it has eight: the grandchildren that a ray is most likely to
//! visit move up.
//!
//! A binary leaf holds one [`LeafKind`] of primitive (the builder makes sure of it): triangles,
//! spheres, cylinders or polygons, copied into packs of four in leaf order, or other objects or
//! instances, listed in leaf order. The walk down the tree only counts out the triangle packs; they are
//! filled afterwards on all threads, since a large mesh's copy of its triangles is most of the
//! work. Below the root, the subtrees are walked on all threads, each into arrays of its own
//! ([`Part`]), joined in order afterwards.

use std::ops::Range;

use arrayvec::ArrayVec;
use rayon::prelude::*;

use super::leaf::LeafKind;
use super::{Child, Node, WIDTH, WideNode};
use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId, PrimKind};
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
    let tree = if binary.is_empty() {
        Part::default()
    } else {
        Collapse {
            binary,
            prims,
            geometry,
        }
        .tree()
    };
    // An indexed parallel iterator collects into one allocation of the exact size.
    let packs = tree
        .triangle_packs
        .into_par_iter()
        .map(|range| {
            let ids = &prims[range];
            // A pack's triangles are read together; a pack of fewer reads its last one again.
            let triangle = |k: usize| {
                let PrimKind::Triangle(t) = ids[k.min(ids.len() - 1)].kind() else {
                    unreachable!("a leaf of triangles holds only triangles")
                };
                t
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
    Collapsed {
        nodes: tree.nodes,
        packs,
        spheres: tree.spheres,
        cylinders: tree.cylinders,
        polygons: tree.polygons,
        objects: tree.objects,
    }
}

/// A subtree of the wide tree and its leaves, collapsed on its own: its root is its node 0, and
/// its children point into its own arrays.
#[derive(Default)]
struct Part {
    nodes: Vec<WideNode>,
    spheres: Vec<SpherePack>,
    cylinders: Vec<CylinderPack>,
    polygons: Vec<PolygonPack>,
    objects: Vec<PrimId>,
    /// Where in `prims` the primitives of each triangle pack are, in pack order: the packs
    /// are filled once the whole tree is done.
    triangle_packs: Vec<Range<usize>>,
}

impl Part {
    /// A part whose root is still to be written.
    fn new() -> Part {
        Part {
            nodes: vec![EMPTY],
            ..Part::default()
        }
    }

    /// How many entries it has in the array of each [`LeafKind`] (objects and instances share
    /// one).
    fn lengths(&self) -> [usize; LeafKind::COUNT] {
        let mut lengths = [0; LeafKind::COUNT];
        lengths[LeafKind::Objects as usize] = self.objects.len();
        lengths[LeafKind::Instances as usize] = self.objects.len();
        lengths[LeafKind::Spheres as usize] = self.spheres.len();
        lengths[LeafKind::Cylinders as usize] = self.cylinders.len();
        lengths[LeafKind::Polygons as usize] = self.polygons.len();
        lengths[LeafKind::Triangles as usize] = self.triangle_packs.len();
        lengths
    }

    /// Appends `parts`, the subtrees of this part's interior nodes 1, 2, … in order, which
    /// stand in for their roots: each part's root replaces its stand-in, the rest of its
    /// nodes and its leaves go at the end, and the indices move with them. The result is
    /// what collapsing the whole on one thread writes.
    fn join(&mut self, parts: Vec<Part>) {
        let total = |length: fn(&Part) -> usize| parts.iter().map(length).sum::<usize>();
        self.nodes.reserve_exact(total(|p| p.nodes.len() - 1));
        self.objects.reserve_exact(total(|p| p.objects.len()));
        self.spheres.reserve_exact(total(|p| p.spheres.len()));
        self.cylinders.reserve_exact(total(|p| p.cylinders.len()));
        self.polygons.reserve_exact(total(|p| p.polygons.len()));
        self.triangle_packs
            .reserve_exact(total(|p| p.triangle_packs.len()));
        for (j, part) in parts.into_iter().enumerate() {
            // The part's node i ≥ 1 lands at `self.nodes.len() + i − 1`; its interior
            // children are never its root.
            let shift = self.nodes.len() as u32 - 1;
            let starts = self.lengths();
            for (i, mut node) in part.nodes.into_iter().enumerate() {
                for k in 0..WIDTH {
                    match node.count[k] {
                        0 => {}
                        WideNode::INTERIOR => node.first[k] += shift,
                        count => {
                            let kind = (count >> Child::KIND_SHIFT) as usize;
                            node.first[k] += starts[kind] as u32;
                        }
                    }
                }
                if i == 0 {
                    self.nodes[1 + j] = node;
                } else {
                    self.nodes.push(node);
                }
            }
            self.objects.extend(part.objects);
            self.spheres.extend(part.spheres);
            self.cylinders.extend(part.cylinders);
            self.polygons.extend(part.polygons);
            self.triangle_packs.extend(part.triangle_packs);
        }
    }
}

struct Collapse<'a> {
    binary: &'a [Node],
    prims: &'a [PrimId],
    geometry: &'a Geometry,
}

impl Collapse<'_> {
    /// The whole tree. The wide root is written here; the subtrees of its interior children
    /// are collapsed in parallel, each on its own, and joined in order.
    fn tree(&self) -> Part {
        let mut tree = Part::new();
        let interior = self.write_children(&mut tree, 0, 0);
        let parts = interior
            .par_iter()
            .map(|&(c, _)| {
                let mut part = Part::new();
                self.fill(&mut part, c, 0);
                part
            })
            .collect();
        tree.join(parts);
        tree
    }

    /// Writes into wide node `at` of `out` the children of binary node `node`, and their
    /// subtrees after.
    fn fill(&self, out: &mut Part, node: usize, at: usize) {
        for (c, index) in self.write_children(out, node, at) {
            self.fill(out, c, index);
        }
    }

    /// Writes into wide node `at` of `out` the children of binary node `node`: the leaves'
    /// contents, and a node for each interior child, whose binary and wide indices it returns.
    fn write_children(
        &self,
        out: &mut Part,
        node: usize,
        at: usize,
    ) -> ArrayVec<(usize, usize), WIDTH> {
        let mut interior = ArrayVec::new();
        for (k, c) in self.wide_children(node).into_iter().enumerate() {
            let child = &self.binary[c];
            let slot = if child.is_leaf() {
                self.leaf(out, child)
            } else {
                out.nodes.push(EMPTY);
                let index = out.nodes.len() - 1;
                interior.push((c, index));
                Child::node(index as u32)
            };
            let wide = &mut out.nodes[at];
            for axis in 0..3 {
                wide.min[axis][k] = child.min[axis];
                wide.max[axis][k] = child.max[axis];
            }
            wide.first[k] = slot.first;
            wide.count[k] = slot.count;
        }
        interior
    }

    /// The wide child of a binary leaf: its primitives in packs, or its objects.
    fn leaf(&self, out: &mut Part, leaf: &Node) -> Child {
        let prims = &self.prims[leaf.first as usize..][..leaf.count as usize];
        let geometry = self.geometry;
        let kind = LeafKind::of(geometry, prims[0]);
        // The shape of object `id`, which the builder put in a leaf of its kind.
        let shape = |id: PrimId| {
            let PrimKind::Object(object) = id.kind() else {
                unreachable!("a leaf of packed objects holds only objects")
            };
            &geometry.objects[object].shape
        };
        let mixed = || unreachable!("a leaf holds one kind of primitive");
        let (first, count) = match kind {
            LeafKind::Objects | LeafKind::Instances => {
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
                let first = out.triangle_packs.len();
                let start = leaf.first as usize;
                let end = start + prims.len();
                let packs = (start..end).step_by(PACK_SIZE);
                let ranges = packs.map(|pack| pack..(pack + PACK_SIZE).min(end));
                out.triangle_packs.extend(ranges);
                (first, out.triangle_packs.len() - first)
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
