//! Building the BVH: a binary tree by the surface area heuristic (SAH), top down.
//!
//! A node's primitives are split where the SAH says a ray pays least, among the planes between
//! bins of their centroids on each axis: more bins for large nodes, fewer for small ones. The
//! nodes at the top, fewer than the threads, bin and partition their primitives on all threads;
//! below them, the two halves of a node are built in parallel. A leaf holds one
//! [`LeafKind`]: where the SAH would make a leaf of several, the node is split by kind instead.
//!
//! The tree does not depend on the thread count: every choice is made from sums, minima and
//! maxima, which come out the same whatever order the threads add them in; primitives are put
//! in an order fixed by where they were; and the parallel halves are stitched together in the
//! order one thread would have written them.
//!
//! Its parts: the primitives as the builder holds them (`prims`), binning them and finding the
//! cheapest plane (`bins`), and moving them to their side of it (`partition`).
mod bins;
mod partition;
mod prims;

use rayon::prelude::*;

pub(super) use self::bins::tests;
use self::bins::{BinMap, Bins, best_bin_plane, bin_count};
use self::partition::{partition, partition_in_parallel};
use self::prims::{BuildPrim, Extent};
use super::leaf::LeafKind;
use super::{Bvh, Node};
use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId, PrimKind};

/// Relative cost of visiting a node against testing one primitive.
pub(super) const TRAVERSAL_COST: f32 = 1.0;
/// A leaf never holds more than this unless its primitives cannot be told apart.
const MAX_LEAF_SIZE: usize = 8;
/// Deepest tree the traversal stack allows: a node [`LeafKind::COUNT`] − 1 levels above it is
/// a leaf, or, when it holds several kinds of primitive, split by kind (once per kind but one,
/// at most).
pub(super) const MAX_DEPTH: usize = 60;
/// Nodes with at least this many primitives build their two halves in parallel. Such a half
/// takes a few hundred microseconds to build, against microseconds to hand it to another
/// thread, so scenes of a few thousand primitives are built on all threads too; below it, the
/// handing over would cost more than it saves.
const PARALLEL_MIN_PRIMS: usize = 1 << 11;
/// Nodes with at least this many primitives bin and partition them on all threads, in pieces
/// of [`CHUNK`]: the top of the tree, where there are fewer nodes than threads.
const DATA_PARALLEL_MIN_PRIMS: usize = 1 << 16;
/// How a node's primitives were split: the first `mid` go left.
struct Split {
    mid: usize,
    left: Extent,
    right: Extent,
}

impl Bvh {
    /// The tree over `geometry`'s primitives, with a tree of its own for each model its
    /// instances place.
    pub fn build(geometry: &Geometry) -> Bvh {
        let models = geometry.models().iter().map(Bvh::build).collect();
        let (mut prims, extent, unbounded) = build_prims(geometry);
        let binary = if prims.is_empty() {
            Vec::new()
        } else {
            subtree(&mut prims, 0, extent, 0)
        };
        let ids: Vec<PrimId> = prims.par_iter().map(BuildPrim::id).collect();
        Bvh::from_binary(geometry, &binary, &ids, unbounded, models)
    }
}

/// The binary tree that [`Bvh::build`] collapses, and the kind of each primitive in the tree's
/// order; `None` when nothing is bounded.
pub(super) fn binary_tree(geometry: &Geometry) -> Option<(Vec<Node>, Vec<LeafKind>)> {
    let (mut prims, extent, _) = build_prims(geometry);
    if prims.is_empty() {
        return None;
    }
    let tree = subtree(&mut prims, 0, extent, 0);
    let kinds = prims.iter().map(BuildPrim::kind).collect();
    Some((tree, kinds))
}

/// The bounded primitives as the builder sees them with their extent, and the ids of the
/// unbounded ones, all in scene order.
fn build_prims(geometry: &Geometry) -> (Vec<BuildPrim>, Extent, Vec<PrimId>) {
    let objects = geometry.objects.len();
    let triangles = objects + geometry.triangle_count();
    // Nearly every primitive is bounded: make them all (an unbounded one with the empty box),
    // straight into place, and take out the few unbounded ones after.
    let mut prims: Vec<BuildPrim> = (0..geometry.len())
        .into_par_iter()
        .map(|i| {
            let id = if i < objects {
                PrimId::object(i)
            } else if i < triangles {
                PrimId::triangle(i - objects)
            } else {
                PrimId::instance(i - triangles)
            };
            // A triangle's box is made in SIMD registers, unless a corner is not finite.
            if let PrimKind::Triangle(t) = id.kind()
                && let Some(prim) = BuildPrim::of_triangle(&geometry.triangle(t), id)
            {
                return prim;
            }
            let bounds = geometry.bounds(id).filter(Aabb::is_finite);
            BuildPrim::new(
                bounds.unwrap_or(Aabb::EMPTY),
                id,
                LeafKind::of(geometry, id),
            )
        })
        .collect();
    let is_bounded = |p: &BuildPrim| p.bounds().min.x.is_finite();
    let unbounded: Vec<PrimId> = prims
        .par_iter()
        .filter(|p| !is_bounded(p))
        .map(BuildPrim::id)
        .collect();
    if !unbounded.is_empty() {
        prims.retain(is_bounded);
    }
    let extent = Extent::of_in_parallel(&prims);
    (prims, extent, unbounded)
}

fn leaf(extent: &Extent, first: usize, count: usize) -> Node {
    Node {
        min: extent.bounds.min.to_array(),
        first: first as u32,
        max: extent.bounds.max.to_array(),
        count: count as u32,
    }
}

/// The subtree over `prims` (which start at `first` in the final primitive list) as its own
/// node array, root first, children indices relative to it.
fn subtree(prims: &mut [BuildPrim], first: usize, extent: Extent, depth: usize) -> Vec<Node> {
    // A binary tree over n primitives has at most 2n − 1 nodes. Reserving them all only takes
    // address space: the memory behind it is used as nodes are written, so the array never
    // moves while it grows. The binary tree only lives until it is collapsed, so the unused
    // reserve is never trimmed.
    let mut nodes = Vec::with_capacity(2 * prims.len() - 1);
    nodes.push(leaf(&extent, first, prims.len()));
    let mut builder = SubtreeBuilder {
        nodes,
        bins: Bins::new(),
        scratch: Vec::new(),
    };
    builder.subdivide(prims, 0, first, extent, depth);
    builder.nodes
}

/// One thread's part of the build: the nodes it has made so far, and its bins.
struct SubtreeBuilder {
    nodes: Vec<Node>,
    bins: Box<Bins>,
    /// Room for the partition's lists.
    scratch: Vec<u32>,
}

impl SubtreeBuilder {
    /// Splits node `index`, which covers `prims` (starting at `first` in the final primitive
    /// list), while the SAH says it pays. Children go at the end of `nodes`, left then right,
    /// and each child's subtree follows in full before the next: depth-first order.
    fn subdivide(
        &mut self,
        prims: &mut [BuildPrim],
        index: usize,
        first: usize,
        extent: Extent,
        depth: usize,
    ) {
        if prims.len() <= 1 {
            return;
        }
        // The deepest nodes are leaves; a few levels above, only splits by kind are left.
        let split = if depth + LeafKind::COUNT > MAX_DEPTH {
            None
        } else {
            split(prims, &extent, &mut self.bins, &mut self.scratch)
        };
        let Some(split) = split.or_else(|| split_by_kind(prims, &mut self.scratch)) else {
            return;
        };
        let nodes = &mut self.nodes;
        let left = nodes.len();
        nodes.push(leaf(&split.left, first, split.mid));
        nodes.push(leaf(
            &split.right,
            first + split.mid,
            prims.len() - split.mid,
        ));
        nodes[index].first = left as u32;
        nodes[index].count = Node::INTERIOR | 2;
        let parallel = prims.len() >= PARALLEL_MIN_PRIMS;
        let (left_prims, right_prims) = prims.split_at_mut(split.mid);
        let right_first = first + split.mid;
        if parallel {
            // The left half goes on here while another thread may build the right half into
            // an array of its own, appended after the left half's nodes.
            let ((), right_nodes) = rayon::join(
                || self.subdivide(left_prims, left, first, split.left, depth + 1),
                || subtree(right_prims, right_first, split.right, depth + 1),
            );
            append_subtree(&mut self.nodes, left + 1, right_nodes);
        } else {
            self.subdivide(left_prims, left, first, split.left, depth + 1);
            self.subdivide(right_prims, left + 1, right_first, split.right, depth + 1);
        }
    }
}

/// Puts a subtree built on its own (root first, indices relative to it) into `nodes`: the root
/// replaces node `at`, the rest goes at the end, and the interior nodes' child indices move
/// with them. Leaves point into the primitive list, which does not move.
fn append_subtree(nodes: &mut Vec<Node>, at: usize, mut subtree: Vec<Node>) {
    // The subtree's node k ≥ 1 lands at `nodes.len() + k − 1`.
    let shift = nodes.len() as u32 - 1;
    for node in subtree.iter_mut().filter(|node| !node.is_leaf()) {
        node.first += shift;
    }
    nodes[at] = subtree[0];
    nodes.extend_from_slice(&subtree[1..]);
}

/// Reorders `prims` around the best SAH split and returns it, or `None` when a leaf is
/// cheaper (and small enough), or the primitives cannot be told apart and are few enough for
/// a leaf.
fn split(
    prims: &mut [BuildPrim],
    extent: &Extent,
    bins: &mut Bins,
    scratch: &mut Vec<u32>,
) -> Option<Split> {
    let n = prims.len();
    let area = extent.bounds.surface_area().max(f32::MIN_POSITIVE);
    // Packed primitives (triangles, spheres, open cylinders, small polygons) are tested four at
    // a time: a leaf of up to four costs one test; a leaf with other objects, one per object.
    let holds_objects =
        extent.may_hold_objects && prims.iter().any(|p| p.kind() == LeafKind::Objects);
    let block = if holds_objects {
        LeafKind::Objects
    } else {
        LeafKind::Triangles
    }
    .block();
    let pays =
        |cost: f32| TRAVERSAL_COST + cost / area < tests(n as u32, block) || n > MAX_LEAF_SIZE;
    if let [a, b] = prims {
        return split_pair(a, b)
            .filter(|&cost| pays(cost))
            .map(|_| split_at(prims, 1));
    }
    let map = BinMap::new(&extent.centroids, bin_count(n));
    let parallel = n >= DATA_PARALLEL_MIN_PRIMS;
    if parallel {
        bins.fill_in_parallel(prims, &map);
    } else {
        bins.fill(prims, &map);
    }
    let split = best_bin_plane(bins, extent, map.count, block)
        .filter(|&(cost, _, _)| pays(cost))
        .map(|(_, axis, bin)| {
            // The bins know the sides' sizes and boxes; the partition finds their centroids'.
            let (mid, left, right) = bins.sides(axis, bin, map.count);
            let goes_left = |p: &BuildPrim| map.bins(p)[axis] <= bin;
            let centroids = if parallel {
                partition_in_parallel(prims, mid, goes_left)
            } else {
                partition(prims, mid, goes_left, scratch)
            };
            Split {
                mid,
                left: Extent {
                    bounds: left,
                    centroids: centroids[1],
                    may_hold_objects: holds_objects,
                },
                right: Extent {
                    bounds: right,
                    centroids: centroids[0],
                    may_hold_objects: holds_objects,
                },
            }
        });
    // All centroids coincide: no plane separates them. Halve large sets anyway.
    split.or_else(|| (n > MAX_LEAF_SIZE).then(|| split_at(prims, n / 2)))
}

/// Two primitives can only be split one way: one on each side. The SAH cost of that (without
/// the node's own area), with the two put in the order the bins would (by centroid, along the
/// first axis on which the centroids differ); `None` when the centroids are the same.
fn split_pair(a: &mut BuildPrim, b: &mut BuildPrim) -> Option<f32> {
    let (ca, cb) = (a.centroid(), b.centroid());
    let axis = (0..3).find(|&axis| ca[axis] != cb[axis])?;
    if cb[axis] < ca[axis] {
        std::mem::swap(a, b);
    }
    Some(a.bounds().surface_area() + b.bounds().surface_area())
}

/// A leaf's primitives, when they are of several [`LeafKind`]s, split by kind: the first kind
/// (in [`LeafKind`]'s order) left, the others right. `None` when they are all of one kind.
fn split_by_kind(prims: &mut [BuildPrim], scratch: &mut Vec<u32>) -> Option<Split> {
    let first = prims.iter().map(BuildPrim::kind).min()?;
    let mid = prims.iter().filter(|p| p.kind() == first).count();
    (mid < prims.len()).then(|| {
        partition(prims, mid, |p| p.kind() == first, scratch);
        split_at(prims, mid)
    })
}

fn split_at(prims: &[BuildPrim], mid: usize) -> Split {
    Split {
        mid,
        left: Extent::of(&prims[..mid]),
        right: Extent::of(&prims[mid..]),
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::mesh::Mesh;
    use crate::primitive::Object;
    use crate::shapes::{Ellipsoid, Shape, Sphere};

    /// A soup of `n` small triangles scattered in a cube, from a fixed seed.
    fn soup(n: u32) -> Geometry {
        let mut state = 12345u64;
        let mut random = move || {
            // xorshift64*
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1 << 24) as f32
        };
        let mut mesh = Mesh::default();
        for i in 0..n {
            let c = Vec3::new(random(), random(), random()) * 100.0;
            for _ in 0..3 {
                mesh.positions
                    .push(c + Vec3::new(random(), random(), random()));
            }
            mesh.faces.push([3 * i, 3 * i + 1, 3 * i + 2]);
        }
        let mut geometry = Geometry::default();
        geometry.add_mesh(mesh);
        geometry
    }

    /// The binary tree and the primitives in leaf order.
    fn build(geometry: &Geometry) -> (Vec<Node>, Vec<PrimId>) {
        let (mut prims, extent, _) = build_prims(geometry);
        let nodes = subtree(&mut prims, 0, extent, 0);
        (nodes, prims.iter().map(BuildPrim::id).collect())
    }

    /// The leaves' primitives, reached from the root.
    fn leaves(nodes: &[Node], prims: &[PrimId]) -> Vec<Vec<PrimId>> {
        let mut leaves = Vec::new();
        let mut stack = vec![0];
        while let Some(i) = stack.pop() {
            let node = &nodes[i];
            if node.is_leaf() {
                let first = node.first as usize;
                leaves.push(prims[first..first + node.count as usize].to_vec());
            } else {
                stack.extend([node.first as usize, node.first as usize + 1]);
            }
        }
        leaves
    }

    #[test]
    fn a_leaf_holds_one_kind_of_primitive() {
        // Spheres, other objects and triangles around the same few points: the SAH alone
        // would put them in one leaf (no plane separates equal centroids).
        let mut geometry = soup(0);
        let mut mesh = Mesh::default();
        for k in 0..20 {
            let c = Vec3::new(k as f32 * 10.0, 0.0, 0.0);
            let corners = [Vec3::new(-1.0, -1.0, 0.0), Vec3::new(1.0, -1.0, 0.0)];
            let first = mesh.positions.len() as u32;
            mesh.positions
                .extend([c + corners[0], c + corners[1], c + Vec3::Y * 2.0]);
            mesh.positions
                .extend([c - corners[0], c - corners[1], c - Vec3::Y * 2.0]);
            mesh.faces.extend([
                [first, first + 1, first + 2],
                [first + 3, first + 4, first + 5],
            ]);
            let sphere = Shape::Sphere(Sphere {
                center: c,
                radius: 1.0,
            });
            let ellipsoid = Shape::Ellipsoid(Ellipsoid::new(c, Vec3::ONE).unwrap());
            for shape in [sphere, ellipsoid] {
                geometry.objects.push(Object {
                    shape,
                    transform: None,
                    material: 0,
                });
            }
        }
        geometry.add_mesh(mesh);
        let (nodes, prims) = build(&geometry);
        let leaves = leaves(&nodes, &prims);
        assert_eq!(leaves.iter().map(Vec::len).sum::<usize>(), 80);
        for leaf in &leaves {
            let kind = LeafKind::of(&geometry, leaf[0]);
            assert!(
                leaf.iter().all(|&id| LeafKind::of(&geometry, id) == kind),
                "mixed leaf {leaf:?}"
            );
        }
    }

    #[test]
    fn large_nodes_split_on_all_threads_as_on_one() {
        // Enough primitives for the top nodes to bin and partition on all threads.
        let geometry = soup(3 * DATA_PARALLEL_MIN_PRIMS as u32);
        let build_on = |threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| build(&geometry))
        };
        let (nodes, prims) = build_on(1);
        assert_eq!((nodes.clone(), prims.clone()), build_on(3));
        // Every primitive once, in a leaf whose box holds it; every child inside its parent.
        let mut seen: Vec<PrimId> = leaves(&nodes, &prims).concat();
        seen.sort();
        assert_eq!(seen, geometry.prim_ids().collect::<Vec<_>>());
        let aabb = |node: &Node| Aabb::new(node.min.into(), node.max.into());
        let inside =
            |b: Aabb, outer: Aabb| b.min.cmpge(outer.min).all() && b.max.cmple(outer.max).all();
        for node in &nodes {
            if node.is_leaf() {
                let first = node.first as usize;
                for &id in &prims[first..first + node.count as usize] {
                    assert!(inside(geometry.bounds(id).unwrap(), aabb(node)));
                }
            } else {
                for child in &nodes[node.first as usize..][..2] {
                    assert!(inside(aabb(child), aabb(node)));
                }
            }
        }
    }
}
