//! Building the BVH: binned surface area heuristic (SAH) splits, top down, the two halves of a
//! large node built in parallel.
//!
//! The builder keeps each primitive's box in SIMD registers ([`Vec3A`]: four lanes, the fourth
//! unused), bins the centroids on all three axes in one pass over the primitives, and gathers
//! the children's boxes while it partitions, so a node costs two passes over its primitives.
//! The tree does not depend on the thread count: a subtree is the same whichever thread
//! builds it, and the parallel halves are stitched together in the order one thread would
//! have written them.

use glam::{Vec3, Vec3A};

use super::{Bvh, Node};
use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId};

/// Bins per axis when searching for a split.
const BINS: usize = 16;
/// Relative cost of visiting a node against testing one primitive.
pub(super) const TRAVERSAL_COST: f32 = 1.0;
/// A leaf never holds more than this unless its primitives cannot be told apart.
const MAX_LEAF_SIZE: usize = 8;
/// Deepest tree the traversal stack allows; subtrees deeper than this become leaves.
pub(super) const MAX_DEPTH: usize = 60;
/// Nodes with at least this many primitives build their two halves in parallel; below it,
/// handing work to another thread costs more than it saves.
const PARALLEL_MIN_PRIMS: usize = 1 << 14;

/// An axis-aligned box held in SIMD registers, for the builder's inner loops.
#[derive(Clone, Copy)]
struct Bounds {
    min: Vec3A,
    max: Vec3A,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    fn union(self, other: Bounds) -> Bounds {
        Bounds {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    #[inline(always)]
    fn grow(self, p: Vec3A) -> Bounds {
        Bounds {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    #[inline(always)]
    fn center(&self) -> Vec3A {
        (self.min + self.max) * 0.5
    }

    /// [`Aabb::surface_area`] of a non-empty box, with the same arithmetic, in SIMD.
    #[inline(always)]
    fn surface_area(&self) -> f32 {
        let e = (self.max - self.min).max(Vec3A::ZERO);
        let products = e * Vec3A::new(e.y, e.z, e.x);
        2.0 * (products.x + products.y + products.z)
    }
}

impl From<Bounds> for Aabb {
    fn from(b: Bounds) -> Aabb {
        Aabb::new(Vec3::from(b.min), Vec3::from(b.max))
    }
}

/// A primitive as the builder sees it: its id and box.
#[derive(Clone, Copy)]
struct BuildPrim {
    bounds: Bounds,
    id: PrimId,
}

/// The primitives of a node, with what splitting them needs: their bounds and the bounds of
/// their centroids.
#[derive(Clone, Copy)]
struct Extent {
    bounds: Bounds,
    centroids: Bounds,
}

impl Extent {
    fn of(prims: &[BuildPrim]) -> Extent {
        prims.iter().fold(Extent::EMPTY, |e, p| e.add(p))
    }

    const EMPTY: Extent = Extent {
        bounds: Bounds::EMPTY,
        centroids: Bounds::EMPTY,
    };

    #[inline(always)]
    fn add(self, p: &BuildPrim) -> Extent {
        Extent {
            bounds: self.bounds.union(p.bounds),
            centroids: self.centroids.grow(p.bounds.center()),
        }
    }
}

/// A node's primitives sorted by centroid into `BINS` equal slices of the centroid box along
/// each axis: for each axis and bin, the box around its primitives and their number. Bin `b`
/// of axis `a` is entry `a * BINS + b`. One set of bins serves a whole subtree, node after
/// node: setting up 1.5 KiB of fresh bins for each of a million nodes would cost more than
/// binning their few primitives.
struct Bins {
    bounds: [Bounds; 3 * BINS],
    counts: [u32; 3 * BINS],
}

/// How a node's primitives were split: the first `mid` go left.
struct Split {
    mid: usize,
    left: Extent,
    right: Extent,
}

impl Bvh {
    pub fn build(geometry: &Geometry) -> Bvh {
        let (mut prims, unbounded) = build_prims(geometry);
        let nodes = if prims.is_empty() {
            Vec::new()
        } else {
            let extent = Extent::of(&prims);
            super::widen::widen(&subtree(&mut prims, 0, extent, 0))
        };
        Bvh {
            nodes,
            prims: prims.iter().map(|p| p.id).collect(),
            unbounded,
        }
    }

    /// The binary tree that [`Bvh::build`] widens: root first, the children of an interior
    /// node at `first` and `first + 1`, a leaf's primitives counted from `first` in leaf order.
    /// For measuring the builder ([`super::cost::sah_cost`]); empty when nothing is bounded.
    pub fn binary_tree(geometry: &Geometry) -> Vec<Node> {
        let (mut prims, _) = build_prims(geometry);
        if prims.is_empty() {
            return Vec::new();
        }
        let extent = Extent::of(&prims);
        subtree(&mut prims, 0, extent, 0)
    }
}

/// The bounded primitives as the builder sees them, and the ids of the unbounded ones.
fn build_prims(geometry: &Geometry) -> (Vec<BuildPrim>, Vec<PrimId>) {
    use rayon::prelude::*;
    let ids: Vec<PrimId> = geometry.prim_ids().collect();
    let bounds = |id: PrimId| geometry.bounds(id).filter(Aabb::is_finite);
    let prims: Vec<BuildPrim> = ids
        .par_iter()
        .filter_map(|&id| {
            let b = bounds(id)?;
            Some(BuildPrim {
                bounds: Bounds {
                    min: b.min.into(),
                    max: b.max.into(),
                },
                id,
            })
        })
        .collect();
    let unbounded = ids
        .into_par_iter()
        .filter(|&id| bounds(id).is_none())
        .collect();
    (prims, unbounded)
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
    // moves while it grows. The binary tree only lives until it is widened, so the unused
    // reserve is never trimmed.
    let mut nodes = Vec::with_capacity(2 * prims.len() - 1);
    nodes.push(leaf(&extent, first, prims.len()));
    let mut builder = SubtreeBuilder {
        nodes,
        bins: Bins::new(),
    };
    builder.subdivide(prims, 0, first, extent, depth);
    builder.nodes
}

/// One thread's part of the build: the nodes it has made so far, and its bins.
struct SubtreeBuilder {
    nodes: Vec<Node>,
    bins: Box<Bins>,
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
        if prims.len() <= 1 || depth >= MAX_DEPTH {
            return;
        }
        let Some(split) = partition(prims, &extent, &mut self.bins) else {
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
/// cheaper (and small enough).
fn partition(prims: &mut [BuildPrim], extent: &Extent, bins: &mut Bins) -> Option<Split> {
    let centroids = Aabb::from(extent.centroids);
    let size = centroids.extent();
    let lo = extent.centroids.min;
    let scale = Vec3A::splat(BINS as f32) / Vec3A::from(size);
    bins.fill(prims, lo, scale);
    let mut best: Option<(f32, usize, f32)> = None; // (cost, axis, split position)
    for axis in 0..3 {
        if size[axis] <= 0.0 {
            continue;
        }
        let on_axis = axis * BINS..(axis + 1) * BINS;
        if let Some((cost, bin)) = best_plane(&bins.bounds[on_axis.clone()], &bins.counts[on_axis])
            && best.is_none_or(|(c, _, _)| cost < c)
        {
            best = Some((cost, axis, lo[axis] + (bin + 1) as f32 / scale[axis]));
        }
    }
    let area = extent.bounds.surface_area().max(f32::MIN_POSITIVE);
    let leaf_cost = prims.len() as f32;
    match best {
        Some((cost, axis, split)) => {
            let split_cost = TRAVERSAL_COST + cost / area;
            if split_cost >= leaf_cost && prims.len() <= MAX_LEAF_SIZE {
                return None;
            }
            let split = partition_in_place(prims, |p| p.bounds.center()[axis] < split);
            // Float rounding can put every centroid on one side: fall back to a median split.
            Some(if split.mid == 0 || split.mid == prims.len() {
                median_split(prims, axis)
            } else {
                split
            })
        }
        // All centroids coincide: no plane separates them. Halve large sets anyway.
        None if prims.len() > MAX_LEAF_SIZE => Some(split_at(prims, prims.len() / 2)),
        None => None,
    }
}

impl Bins {
    fn new() -> Box<Bins> {
        Box::new(Bins {
            bounds: [Bounds::EMPTY; 3 * BINS],
            counts: [0; 3 * BINS],
        })
    }

    /// Empties the bins and bins the primitives, on all three axes in one pass.
    fn fill(&mut self, prims: &[BuildPrim], lo: Vec3A, scale: Vec3A) {
        self.bounds.fill(Bounds::EMPTY);
        self.counts.fill(0);
        for p in prims {
            // The centroid's bin: its place in the centroid box, 0 to `BINS`, cut down to a
            // whole number, the far side going into the last bin. (A flat axis has scale ∞ and
            // gives NaN here, and then some bin in range; such an axis is never split.)
            let slot = ((p.bounds.center() - lo) * scale).min(Vec3A::splat((BINS - 1) as f32));
            for axis in 0..3 {
                let bin = axis * BINS + slot[axis] as u32 as usize;
                self.counts[bin] += 1;
                self.bounds[bin] = self.bounds[bin].union(p.bounds);
            }
        }
    }
}

/// The cheapest plane between bins on one axis by the SAH: its cost (without the node's own
/// area, the same for every plane) and the bin on its left.
///
/// A plane between two empty bins splits like the plane after the last non-empty bin before
/// it, at the same cost, and the first plane wins a tie; so only planes right after non-empty
/// bins are looked at. Small nodes have few of them.
fn best_plane(bounds: &[Bounds], counts: &[u32]) -> Option<(f32, usize)> {
    let mut filled = [0; BINS];
    let mut n = 0;
    for (i, &count) in counts.iter().enumerate() {
        filled[n] = i;
        n += (count > 0) as usize;
    }
    let filled = &filled[..n];
    // Sweep from the right: `right[k]` is the area and count of the filled bins `k..`.
    let mut right = [(0.0, 0); BINS];
    let mut acc = Bounds::EMPTY;
    let mut right_count = 0;
    for (k, &i) in filled.iter().enumerate().skip(1).rev() {
        acc = acc.union(bounds[i]);
        right_count += counts[i];
        right[k] = (acc.surface_area(), right_count);
    }
    let mut best: Option<(f32, usize)> = None;
    let (mut acc, mut left_count) = (Bounds::EMPTY, 0);
    for (k, &i) in filled.iter().enumerate().take(n.saturating_sub(1)) {
        acc = acc.union(bounds[i]);
        left_count += counts[i];
        let (right_area, right_count) = right[k + 1];
        let cost = left_count as f32 * acc.surface_area() + right_count as f32 * right_area;
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, i));
        }
    }
    best
}

fn median_split(prims: &mut [BuildPrim], axis: usize) -> Split {
    let mid = prims.len() / 2;
    prims.select_nth_unstable_by(mid, |a, b| {
        a.bounds.center()[axis].total_cmp(&b.bounds.center()[axis])
    });
    split_at(prims, mid)
}

fn split_at(prims: &[BuildPrim], mid: usize) -> Split {
    Split {
        mid,
        left: Extent::of(&prims[..mid]),
        right: Extent::of(&prims[mid..]),
    }
}

/// Moves the primitives satisfying `left` to the front, keeping count of both sides' extents.
fn partition_in_place(prims: &mut [BuildPrim], left: impl Fn(&BuildPrim) -> bool) -> Split {
    let (mut left_extent, mut right_extent) = (Extent::EMPTY, Extent::EMPTY);
    let mut i = 0;
    for j in 0..prims.len() {
        if left(&prims[j]) {
            left_extent = left_extent.add(&prims[j]);
            prims.swap(i, j);
            i += 1;
        } else {
            right_extent = right_extent.add(&prims[j]);
        }
    }
    Split {
        mid: i,
        left: left_extent,
        right: right_extent,
    }
}
