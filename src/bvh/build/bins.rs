//! Binning a node's primitives for the SAH: which bin each centroid falls in on each axis
//! ([`BinMap`]), the box and count of each bin ([`Bins`], on one thread or all), and the
//! cheapest plane between bins ([`best_bin_plane`]).

use glam::Vec3A;
use rayon::prelude::*;

use super::prims::{Bounds, BuildPrim, CHUNK, Extent};

/// Most bins per axis, for the largest nodes (a power of two, see [`BinMap::bins`]).
const MAX_BINS: usize = 32;
/// Fewest bins per axis, for the smallest nodes.
const MIN_BINS: usize = 8;

/// Bins per axis for a node of `n` primitives: more for large nodes, where a better plane
/// pays for itself many times over, fewer for small ones, where setting up and sweeping the
/// bins would cost more than binning their few primitives.
pub(super) fn bin_count(n: usize) -> usize {
    (n / 4).clamp(MIN_BINS, MAX_BINS)
}

/// Which bin a centroid falls in on each axis: `count` equal slices of a node's centroid box.
#[derive(Clone, Copy)]
pub(super) struct BinMap {
    lo: Vec3A,
    scale: Vec3A,
    pub(super) count: usize,
}

impl BinMap {
    pub(super) fn new(centroids: &Bounds, count: usize) -> BinMap {
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
    pub(super) fn bins(&self, p: &BuildPrim) -> [usize; 3] {
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
pub(super) struct Bins {
    bounds: [[Bounds; MAX_BINS]; 3],
    counts: [[u32; MAX_BINS]; 3],
}

impl Bins {
    pub(super) fn new() -> Box<Bins> {
        Box::new(Bins {
            bounds: [[Bounds::EMPTY; MAX_BINS]; 3],
            counts: [[0; MAX_BINS]; 3],
        })
    }

    /// Empties the first `count` bins of each axis and bins the primitives, on all three axes
    /// in one pass.
    pub(super) fn fill(&mut self, prims: &[BuildPrim], map: &BinMap) {
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
    pub(super) fn fill_in_parallel(&mut self, prims: &[BuildPrim], map: &BinMap) {
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
    pub(super) fn sides(&self, axis: usize, bin: usize, count: usize) -> (usize, Bounds, Bounds) {
        let side = |bins: std::ops::Range<usize>| {
            self.bounds[axis][bins]
                .iter()
                .fold(Bounds::EMPTY, |a, &b| a.union(b))
        };
        let mid = self.counts[axis][..=bin].iter().sum::<u32>();
        (mid as usize, side(0..bin + 1), side(bin + 1..count))
    }
}

/// The cheapest plane between bins by the SAH, on an axis along which the centroids spread:
/// its cost (without the node's own area, the same for every plane), axis and the bin on its
/// left.
pub(super) fn best_bin_plane(
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
pub(in crate::bvh) fn tests(count: u32, block: u32) -> f32 {
    count.div_ceil(block) as f32
}
