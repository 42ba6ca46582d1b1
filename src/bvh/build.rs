//! Building the BVH: a binary tree by the surface area heuristic (SAH), top down.
//!
//! A node's primitives are split where the SAH says a ray pays least, among the planes between
//! bins of their centroids on each axis: more bins for large nodes, fewer for small ones. The
//! nodes at the top, fewer than the threads, bin and partition their primitives on all threads;
//! below them, the two halves of a node are built in parallel. A leaf holds only triangles or
//! only objects: where the SAH would make a leaf of both, the node is split by kind instead.
//!
//! The tree does not depend on the thread count: every choice is made from sums, minima and
//! maxima, which come out the same whatever order the threads add them in; primitives are put
//! in an order fixed by where they were; and the parallel halves are stitched together in the
//! order one thread would have written them.

use glam::{Vec3, Vec3A, Vec4, Vec4Swizzles};
use rayon::prelude::*;

use super::{Bvh, Node};
use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId};
use crate::shapes::PACK_SIZE;

/// Most bins per axis, for the largest nodes (a power of two, see [`BinMap::bins`]).
const MAX_BINS: usize = 32;
/// Fewest bins per axis, for the smallest nodes.
const MIN_BINS: usize = 8;
/// Relative cost of visiting a node against testing one primitive.
pub(super) const TRAVERSAL_COST: f32 = 1.0;
/// A leaf never holds more than this unless its primitives cannot be told apart.
const MAX_LEAF_SIZE: usize = 8;
/// Deepest tree the traversal stack allows: a node one level above it is a leaf, or, when it
/// holds both kinds of primitive, split by kind into two leaves.
pub(super) const MAX_DEPTH: usize = 60;
/// Nodes with at least this many primitives build their two halves in parallel; below it,
/// handing work to another thread costs more than it saves.
const PARALLEL_MIN_PRIMS: usize = 1 << 14;
/// Nodes with at least this many primitives bin and partition them on all threads, in pieces
/// of [`CHUNK`]: the top of the tree, where there are fewer nodes than threads.
const DATA_PARALLEL_MIN_PRIMS: usize = 1 << 16;
/// Primitives per piece of a node binned or partitioned on all threads.
const CHUNK: usize = 1 << 13;

/// Bins per axis for a node of `n` primitives: more for large nodes, where a better plane
/// pays for itself many times over, fewer for small ones, where setting up and sweeping the
/// bins would cost more than binning their few primitives.
fn bin_count(n: usize) -> usize {
    (n / 4).clamp(MIN_BINS, MAX_BINS)
}

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

/// A primitive as the builder sees it, in 32 bytes: its box, with its id kept in the fourth
/// lane of the box's min corner (where a [`Vec3A`] has an unused lane anyway).
#[derive(Clone, Copy)]
struct BuildPrim {
    min: Vec4,
    max: Vec4,
}

impl BuildPrim {
    fn new(bounds: Aabb, id: PrimId) -> BuildPrim {
        BuildPrim {
            min: bounds.min.extend(f32::from_bits(id.0)),
            max: bounds.max.extend(0.0),
        }
    }

    fn id(&self) -> PrimId {
        PrimId(self.min.w.to_bits())
    }

    /// The box. Its min corner's fourth lane, the id, is a tiny (denormal) number as a float,
    /// and arithmetic on such numbers is very slow: it is replaced by the third lane.
    #[inline(always)]
    fn bounds(&self) -> Bounds {
        Bounds {
            min: Vec3A::from_vec4(self.min.xyzz()),
            max: Vec3A::from_vec4(self.max),
        }
    }

    /// Twice the centroid (the builder only compares centroids, so it skips the halving).
    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        let b = self.bounds();
        b.min + b.max
    }

    fn is_object(&self) -> bool {
        self.id().kind().is_ok()
    }
}

/// The primitives of a node, with what splitting them needs: their bounds and the bounds of
/// their (doubled) centroids.
#[derive(Clone, Copy)]
struct Extent {
    bounds: Bounds,
    centroids: Bounds,
}

impl Extent {
    const EMPTY: Extent = Extent {
        bounds: Bounds::EMPTY,
        centroids: Bounds::EMPTY,
    };

    fn of(prims: &[BuildPrim]) -> Extent {
        prims.iter().fold(Extent::EMPTY, |e, p| e.add(p))
    }

    /// [`Extent::of`] on all threads: minima and maxima come out the same in any order.
    fn of_in_parallel(prims: &[BuildPrim]) -> Extent {
        prims
            .par_chunks(CHUNK)
            .map(Extent::of)
            .reduce(|| Extent::EMPTY, Extent::union)
    }

    #[inline(always)]
    fn add(self, p: &BuildPrim) -> Extent {
        Extent {
            bounds: self.bounds.union(p.bounds()),
            centroids: self.centroids.grow(p.centroid()),
        }
    }

    fn union(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.union(other.bounds),
            centroids: self.centroids.union(other.centroids),
        }
    }
}

/// Which bin a centroid falls in on each axis: `count` equal slices of a node's centroid box.
#[derive(Clone, Copy)]
struct BinMap {
    lo: Vec3A,
    scale: Vec3A,
    count: usize,
}

impl BinMap {
    fn new(centroids: &Bounds, count: usize) -> BinMap {
        let size = centroids.max - centroids.min;
        BinMap {
            lo: centroids.min,
            scale: Vec3A::splat(count as f32) / size,
            count,
        }
    }

    /// The centroid's bin on each axis: its place in the centroid box, 0 to `count`, cut down
    /// to a whole number, the far side going into the last bin. Binning and partitioning both
    /// call this, so they put each primitive on the same side.
    #[inline(always)]
    fn bins(&self, p: &BuildPrim) -> [usize; 3] {
        // Rounding in SIMD, all three axes at once: 2²³ added to a number from 0 to 2²² leaves
        // it rounded to the nearest whole number in the float's low bits, which the mask keeps
        // (`MAX_BINS` is a power of two). Half a bin less first makes that rounding down (but
        // for exact halves, which go to the even neighbour). A flat axis has scale ∞ and gives
        // NaN, which `max` makes 0; it is never split.
        let slot = ((p.centroid() - self.lo) * self.scale - Vec3A::splat(0.5))
            .max(Vec3A::ZERO)
            .min(Vec3A::splat((self.count - 1) as f32))
            + Vec3A::splat(8_388_608.0);
        slot.to_array()
            .map(|x| (x.to_bits() as usize) & (MAX_BINS - 1))
    }
}

/// A node's primitives sorted by centroid into bins along each axis: for each axis and bin, the
/// box around its primitives and their number. One set of bins serves a whole subtree, node
/// after node.
#[derive(Clone)]
struct Bins {
    bounds: [[Bounds; MAX_BINS]; 3],
    counts: [[u32; MAX_BINS]; 3],
}

impl Bins {
    fn new() -> Box<Bins> {
        Box::new(Bins {
            bounds: [[Bounds::EMPTY; MAX_BINS]; 3],
            counts: [[0; MAX_BINS]; 3],
        })
    }

    /// Empties the first `count` bins of each axis and bins the primitives, on all three axes
    /// in one pass.
    fn fill(&mut self, prims: &[BuildPrim], map: &BinMap) {
        for axis in 0..3 {
            self.bounds[axis][..map.count].fill(Bounds::EMPTY);
            self.counts[axis][..map.count].fill(0);
        }
        for p in prims {
            let [x, y, z] = map.bins(p);
            let bounds = p.bounds();
            self.add(0, x, bounds);
            self.add(1, y, bounds);
            self.add(2, z, bounds);
        }
    }

    #[inline(always)]
    fn add(&mut self, axis: usize, bin: usize, bounds: Bounds) {
        self.counts[axis][bin] += 1;
        self.bounds[axis][bin] = self.bounds[axis][bin].union(bounds);
    }

    /// [`Bins::fill`] on all threads, each binning pieces of the primitives into bins of its own,
    /// added together at the end (sums, minima and maxima: the same in any order).
    fn fill_in_parallel(&mut self, prims: &[BuildPrim], map: &BinMap) {
        let merged = prims
            .par_chunks(CHUNK)
            .map(|chunk| {
                let mut bins = Bins::new();
                bins.fill(chunk, map);
                bins
            })
            .reduce_with(|mut a, b| {
                for axis in 0..3 {
                    for bin in 0..map.count {
                        a.counts[axis][bin] += b.counts[axis][bin];
                        a.bounds[axis][bin] = a.bounds[axis][bin].union(b.bounds[axis][bin]);
                    }
                }
                a
            });
        if let Some(merged) = merged {
            *self = *merged;
        }
    }

    /// The plane after bin `bin` of axis `axis` as the bins see it: how many primitives go
    /// left, and the boxes around both sides.
    fn sides(&self, axis: usize, bin: usize, count: usize) -> (usize, Bounds, Bounds) {
        let side = |bins: std::ops::Range<usize>| {
            self.bounds[axis][bins]
                .iter()
                .fold(Bounds::EMPTY, |a, &b| a.union(b))
        };
        let mid = self.counts[axis][..=bin].iter().sum::<u32>();
        (mid as usize, side(0..bin + 1), side(bin + 1..count))
    }
}

/// How a node's primitives were split: the first `mid` go left.
struct Split {
    mid: usize,
    left: Extent,
    right: Extent,
}

impl Bvh {
    pub fn build(geometry: &Geometry) -> Bvh {
        let (mut prims, extent, unbounded) = build_prims(geometry);
        let binary = if prims.is_empty() {
            Vec::new()
        } else {
            subtree(&mut prims, 0, extent, 0)
        };
        let ids: Vec<PrimId> = prims.par_iter().map(BuildPrim::id).collect();
        Bvh::from_binary(geometry, &binary, &ids, unbounded)
    }

    /// The SAH cost (`cost::sah_cost`) of the binary tree that [`Bvh::build`]
    /// collapses, and its number of nodes: for measuring the builder. `(0, 0)` when nothing
    /// is bounded.
    pub fn binary_tree_cost(geometry: &Geometry) -> (f64, usize) {
        let (mut prims, extent, _) = build_prims(geometry);
        if prims.is_empty() {
            return (0.0, 0);
        }
        let tree = subtree(&mut prims, 0, extent, 0);
        let ids: Vec<PrimId> = prims.iter().map(BuildPrim::id).collect();
        (super::cost::sah_cost(&tree, &ids), tree.len())
    }
}

/// The bounded primitives as the builder sees them with their extent, and the ids of the
/// unbounded ones, all in scene order.
fn build_prims(geometry: &Geometry) -> (Vec<BuildPrim>, Extent, Vec<PrimId>) {
    let objects = geometry.objects.len();
    // Nearly every primitive is bounded: make them all (an unbounded one with the empty box),
    // straight into place, and take out the few unbounded ones after.
    let mut prims: Vec<BuildPrim> = (0..geometry.len())
        .into_par_iter()
        .map(|i| {
            let id = if i < objects {
                PrimId::object(i)
            } else {
                PrimId::triangle(i - objects)
            };
            let bounds = geometry.bounds(id).filter(Aabb::is_finite);
            BuildPrim::new(bounds.unwrap_or(Aabb::EMPTY), id)
        })
        .collect();
    let is_bounded = |p: &BuildPrim| p.min.x.is_finite();
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
        if prims.len() <= 1 {
            return;
        }
        // The deepest nodes are leaves; one level above, only a split by kind is left to make.
        let split = if depth + 1 >= MAX_DEPTH {
            None
        } else {
            split(prims, &extent, &mut self.bins)
        };
        let Some(split) = split.or_else(|| split_by_kind(prims)) else {
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
fn split(prims: &mut [BuildPrim], extent: &Extent, bins: &mut Bins) -> Option<Split> {
    let n = prims.len();
    let area = extent.bounds.surface_area().max(f32::MIN_POSITIVE);
    // Triangles are tested four at a time: a leaf of up to four costs one test.
    let block = if prims.iter().any(BuildPrim::is_object) {
        1
    } else {
        PACK_SIZE as u32
    };
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
                partition(prims, goes_left).1
            };
            Split {
                mid,
                left: Extent {
                    bounds: left,
                    centroids: centroids[1],
                },
                right: Extent {
                    bounds: right,
                    centroids: centroids[0],
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

/// A leaf's primitives, when they are of both kinds, split by kind: objects left, triangles
/// right. `None` when they are all of one kind.
fn split_by_kind(prims: &mut [BuildPrim]) -> Option<Split> {
    let objects = prims.iter().filter(|p| p.is_object()).count();
    (objects != 0 && objects != prims.len()).then(|| {
        let (mid, _) = partition(prims, BuildPrim::is_object);
        split_at(prims, mid)
    })
}

/// The cheapest plane between bins by the SAH, on an axis along which the centroids spread:
/// its cost (without the node's own area, the same for every plane), axis and the bin on its
/// left.
fn best_bin_plane(
    bins: &Bins,
    extent: &Extent,
    count: usize,
    block: u32,
) -> Option<(f32, usize, usize)> {
    let size = extent.centroids.max - extent.centroids.min;
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        if size[axis] <= 0.0 {
            continue;
        }
        if let Some((cost, bin)) = best_plane(
            &bins.bounds[axis][..count],
            &bins.counts[axis][..count],
            block,
        ) && best.is_none_or(|(c, _, _)| cost < c)
        {
            best = Some((cost, axis, bin));
        }
    }
    best
}

/// The cheapest plane between bins on one axis by the SAH: its cost (without the node's own
/// area, the same for every plane) and the bin on its left; `None` when all primitives are in
/// one bin.
///
/// Planes with nothing on one side are left out. A plane between two empty bins splits like
/// the plane after the last non-empty bin before it, at the same cost, and the first plane
/// wins a tie. The loops run over every bin, empty or not, and choose without branching, so
/// that the processor need not guess how many bins are filled or which plane wins.
fn best_plane(bounds: &[Bounds], counts: &[u32], block: u32) -> Option<(f32, usize)> {
    let bins = bounds.len();
    // Sweep from the right: `right[i]` is the area and count of bins `i..`.
    let mut right = [(0.0, 0); MAX_BINS];
    let (mut acc, mut count) = (Bounds::EMPTY, 0);
    for i in (1..bins).rev() {
        acc = acc.union(bounds[i]);
        count += counts[i];
        right[i] = (acc.surface_area(), count);
    }
    let (mut best_cost, mut best_bin) = (f32::INFINITY, 0);
    let (mut acc, mut left_count) = (Bounds::EMPTY, 0);
    for i in 0..bins - 1 {
        acc = acc.union(bounds[i]);
        left_count += counts[i];
        let (right_area, right_count) = right[i + 1];
        let cost = if left_count == 0 || right_count == 0 {
            f32::INFINITY
        } else {
            tests(left_count, block) * acc.surface_area() + tests(right_count, block) * right_area
        };
        if cost < best_cost {
            (best_cost, best_bin) = (cost, i);
        }
    }
    (best_cost < f32::INFINITY).then_some((best_cost, best_bin))
}

/// Tests a leaf of `count` primitives takes when they are tested `block` at a time.
pub(super) fn tests(count: u32, block: u32) -> f32 {
    count.div_ceil(block) as f32
}

fn split_at(prims: &[BuildPrim], mid: usize) -> Split {
    Split {
        mid,
        left: Extent::of(&prims[..mid]),
        right: Extent::of(&prims[mid..]),
    }
}

/// Moves the primitives that go left to the front: says how many they are, and the boxes
/// around the centroids of those that go right and of those that go left. From both ends
/// towards the middle, swapping the pairs that are on the wrong side.
fn partition(
    prims: &mut [BuildPrim],
    goes_left: impl Fn(&BuildPrim) -> bool,
) -> (usize, [Bounds; 2]) {
    let (mut left, mut right) = (Bounds::EMPTY, Bounds::EMPTY);
    let (mut i, mut j) = (0, prims.len());
    loop {
        while i < j && goes_left(&prims[i]) {
            left = left.grow(prims[i].centroid());
            i += 1;
        }
        while i < j && !goes_left(&prims[j - 1]) {
            j -= 1;
            right = right.grow(prims[j].centroid());
        }
        if i == j {
            break;
        }
        // prims[i] goes right and prims[j − 1] goes left.
        j -= 1;
        prims.swap(i, j);
        left = left.grow(prims[i].centroid());
        right = right.grow(prims[j].centroid());
        i += 1;
    }
    (i, [right, left])
}

/// [`partition`] on all threads, with the same result whatever their number, when `mid` of
/// the primitives go left: the boxes around the centroids of those that go right and left.
/// Pieces of the primitives are looked at in parallel, each listing those on the wrong side of
/// `mid` and growing the centroid boxes; then the k-th primitive that must move right trades
/// places with the k-th that must move left.
fn partition_in_parallel(
    prims: &mut [BuildPrim],
    mid: usize,
    goes_left: impl Fn(&BuildPrim) -> bool + Sync,
) -> [Bounds; 2] {
    let (front, back) = prims.split_at_mut(mid);
    let look = |start: usize, chunk: &[BuildPrim], left_is_misplaced: bool| {
        let mut centroids = [Bounds::EMPTY; 2];
        let mut misplaced = Vec::new();
        for (k, p) in chunk.iter().enumerate() {
            let left = goes_left(p);
            centroids[left as usize] = centroids[left as usize].grow(p.centroid());
            if left == left_is_misplaced {
                misplaced.push((start + k) as u32);
            }
        }
        (misplaced, centroids)
    };
    let pieces = |part: &[BuildPrim], left_is_misplaced: bool| -> Vec<(Vec<u32>, [Bounds; 2])> {
        part.par_chunks(CHUNK)
            .enumerate()
            .map(|(c, chunk)| look(c * CHUNK, chunk, left_is_misplaced))
            .collect()
    };
    let (front_pieces, back_pieces) = rayon::join(|| pieces(front, false), || pieces(back, true));
    // The trades, in parallel, piece by piece of the front: the partners of a piece's
    // misplaced primitives lie in one stretch of the back, after those of the piece before.
    let to_left: Vec<u32> = back_pieces.iter().flat_map(|(m, _)| m).copied().collect();
    let mut trades = Vec::with_capacity(front_pieces.len());
    let (mut rest, mut rest_start, mut partners) = (back, 0, &to_left[..]);
    for (piece, (to_right, _)) in front.chunks_mut(CHUNK).zip(&front_pieces) {
        let (mine, others) = partners.split_at(to_right.len());
        let end = mine.last().map_or(rest_start, |&b| b as usize + 1);
        let (stretch, tail) = std::mem::take(&mut rest).split_at_mut(end - rest_start);
        trades.push((piece, to_right, mine, stretch, rest_start));
        (rest, rest_start, partners) = (tail, end, others);
    }
    trades.into_par_iter().enumerate().for_each(
        |(c, (piece, to_right, partners, stretch, stretch_start))| {
            for (&a, &b) in to_right.iter().zip(partners) {
                std::mem::swap(
                    &mut piece[a as usize - c * CHUNK],
                    &mut stretch[b as usize - stretch_start],
                );
            }
        },
    );
    front_pieces
        .iter()
        .chain(&back_pieces)
        .fold([Bounds::EMPTY; 2], |[r, l], (_, [pr, pl])| {
            [r.union(*pr), l.union(*pl)]
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::primitive::Object;
    use crate::shapes::{Shape, Sphere};

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
    fn a_leaf_holds_only_triangles_or_only_objects() {
        // Spheres and triangles around the same few points: the SAH alone would put a sphere
        // and the triangles around it in one leaf (no plane separates equal centroids).
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
            geometry.objects.push(Object {
                shape: Shape::Sphere(Sphere {
                    center: c,
                    radius: 1.0,
                }),
                transform: None,
                material: 0,
            });
        }
        geometry.add_mesh(mesh);
        let (nodes, prims) = build(&geometry);
        let leaves = leaves(&nodes, &prims);
        assert_eq!(leaves.iter().map(Vec::len).sum::<usize>(), 60);
        for leaf in &leaves {
            let objects = leaf.iter().filter(|id| id.kind().is_ok()).count();
            assert!(objects == 0 || objects == leaf.len(), "mixed leaf {leaf:?}");
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
