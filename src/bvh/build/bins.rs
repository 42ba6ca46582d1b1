//! Binning a node's primitives for the SAH: which bin each centroid falls in on each axis
//! ([`BinMap`]), the box and count of each bin ([`Bins`], on one thread or all), and the
//! cheapest plane between bins ([`best_bin_plane`]).

use glam::{IVec4, Vec3A, Vec4};
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
/// left. `None` when, on every such axis, all primitives are in one bin.
///
/// Planes with nothing on one side are left out. A plane between two empty bins splits like
/// the plane after the last non-empty bin before it, at the same cost; the first plane of an
/// axis, and the first axis, wins a tie. The three axes are swept together, one to a SIMD lane,
/// over every bin, empty or not, choosing without branching, so that the processor need not
/// guess how many bins are filled or which plane wins.
pub(super) fn best_bin_plane(
    bins: &Bins,
    extent: &Extent,
    count: usize,
    block: u32,
) -> Option<(f32, usize, usize)> {
    // The cost of a side: its area times its tests (`tests`, by a shift: a block is one
    // primitive or a pack), +∞ when it is empty.
    debug_assert!(block.is_power_of_two());
    let shift = block.trailing_zeros();
    let side_cost = |side: &LaneBoxes| {
        let tests = ((side.counts + IVec4::splat(block as i32 - 1)) >> shift).as_vec4();
        Vec4::select(tests.cmpeq(Vec4::ZERO), Vec4::INFINITY, tests * side.area())
    };
    // Sweep from the right: `right[i]` is the cost of bins `i..`.
    let mut right = [Vec4::INFINITY; MAX_BINS];
    let mut side = LaneBoxes::EMPTY;
    for i in (1..count).rev() {
        side = side.union(&LaneBoxes::of(bins, i));
        right[i] = side_cost(&side);
    }
    let (mut best_cost, mut best_bin) = (Vec4::INFINITY, Vec4::ZERO);
    let mut side = LaneBoxes::EMPTY;
    for i in 0..count - 1 {
        side = side.union(&LaneBoxes::of(bins, i));
        let cost = side_cost(&side) + right[i + 1];
        let better = cost.cmplt(best_cost);
        best_cost = Vec4::select(better, cost, best_cost);
        best_bin = Vec4::select(better, Vec4::splat(i as f32), best_bin);
    }
    let size = extent.centroids.max - extent.centroids.min;
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        let cost = best_cost[axis];
        if size[axis] > 0.0 && cost < best.map_or(f32::INFINITY, |(c, _, _)| c) {
            best = Some((cost, axis, best_bin[axis] as usize));
        }
    }
    best
}

/// The same bin of each axis, one axis to a lane: each corner coordinate by coordinate, and the
/// counts.
#[derive(Clone, Copy)]
struct LaneBoxes {
    min: [Vec4; 3],
    max: [Vec4; 3],
    counts: IVec4,
}

impl LaneBoxes {
    const EMPTY: LaneBoxes = LaneBoxes {
        min: [Vec4::INFINITY; 3],
        max: [Vec4::NEG_INFINITY; 3],
        counts: IVec4::ZERO,
    };

    /// Bin `i` of the three axes (the fourth lane repeats the third).
    #[inline(always)]
    fn of(bins: &Bins, i: usize) -> LaneBoxes {
        let [x, y, z] = [0, 1, 2].map(|axis| bins.bounds[axis][i]);
        let lanes = |a: Vec3A, b: Vec3A, c: Vec3A| {
            [
                Vec4::new(a.x, b.x, c.x, c.x),
                Vec4::new(a.y, b.y, c.y, c.y),
                Vec4::new(a.z, b.z, c.z, c.z),
            ]
        };
        let counts = [0, 1, 2].map(|axis| bins.counts[axis][i] as i32);
        LaneBoxes {
            min: lanes(x.min, y.min, z.min),
            max: lanes(x.max, y.max, z.max),
            counts: IVec4::new(counts[0], counts[1], counts[2], counts[2]),
        }
    }

    #[inline(always)]
    fn union(&self, other: &LaneBoxes) -> LaneBoxes {
        LaneBoxes {
            min: std::array::from_fn(|k| self.min[k].min(other.min[k])),
            max: std::array::from_fn(|k| self.max[k].max(other.max[k])),
            counts: self.counts + other.counts,
        }
    }

    /// [`Bounds::surface_area`] of each lane's box, with the same arithmetic.
    #[inline(always)]
    fn area(&self) -> Vec4 {
        let [x, y, z] = std::array::from_fn(|k| (self.max[k] - self.min[k]).max(Vec4::ZERO));
        2.0 * (x * y + y * z + z * x)
    }
}

/// Tests a leaf of `count` primitives takes when they are tested `block` at a time.
pub(in crate::bvh) fn tests(count: u32, block: u32) -> f32 {
    count.div_ceil(block) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cheapest plane on one axis, plane by plane in plain arithmetic: the reference the
    /// three-lane sweep must match, bit for bit.
    fn best_plane_on(bins: &Bins, axis: usize, count: usize, block: u32) -> Option<(f32, usize)> {
        let side = |range: std::ops::Range<usize>| {
            let bounds = bins.bounds[axis][range.clone()]
                .iter()
                .fold(Bounds::EMPTY, |a, &b| a.union(b));
            (bounds, bins.counts[axis][range].iter().sum::<u32>())
        };
        let mut best: Option<(f32, usize)> = None;
        for bin in 0..count - 1 {
            let ((left, l), (right, r)) = (side(0..bin + 1), side(bin + 1..count));
            if l == 0 || r == 0 {
                continue;
            }
            let cost =
                tests(l, block) * left.surface_area() + tests(r, block) * right.surface_area();
            if best.is_none_or(|(c, _)| cost < c) {
                best = Some((cost, bin));
            }
        }
        best
    }

    #[test]
    fn the_three_lane_sweep_picks_the_plane_each_axis_alone_would() {
        let mut rng = fastrand::Rng::with_seed(0x9e37_79b9_7f4a_7c15);
        let mut random = move |n: u64| rng.u64(..n);
        for round in 0..2000 {
            let count = [MIN_BINS, 12, MAX_BINS][round % 3];
            let block = [1, 4][round % 2];
            let mut bins = Bins::new();
            for axis in 0..3 {
                for bin in 0..count {
                    // Some bins empty, some boxes of equal area (ties).
                    let n = random(4) as u32 * random(3) as u32;
                    let corner = Vec3A::new(random(8) as f32, random(8) as f32, random(8) as f32);
                    let size = Vec3A::new(1.0 + random(3) as f32, 1.0, 1.0 + random(2) as f32);
                    bins.counts[axis][bin] = n;
                    bins.bounds[axis][bin] = if n == 0 {
                        Bounds::EMPTY
                    } else {
                        Bounds {
                            min: corner,
                            max: corner + size,
                        }
                    };
                }
            }
            // One axis in seven is flat: never split.
            let size = Vec3A::from_array([0, 1, 2].map(|_| (random(7) != 0) as u32 as f32));
            let extent = Extent {
                bounds: Bounds::EMPTY,
                centroids: Bounds {
                    min: Vec3A::ZERO,
                    max: size,
                },
                may_hold_objects: true,
            };
            let mut expected: Option<(f32, usize, usize)> = None;
            for axis in (0..3).filter(|&axis| size[axis] > 0.0) {
                if let Some((cost, bin)) = best_plane_on(&bins, axis, count, block)
                    && expected.is_none_or(|(c, _, _)| cost < c)
                {
                    expected = Some((cost, axis, bin));
                }
            }
            let found = best_bin_plane(&bins, &extent, count, block);
            assert_eq!(
                found.map(|(c, a, b)| (c.to_bits(), a, b)),
                expected.map(|(c, a, b)| (c.to_bits(), a, b)),
                "round {round}"
            );
        }
    }
}
