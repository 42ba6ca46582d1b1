//! Building the BVH: binned surface area heuristic (SAH) splits, top down.

use glam::Vec3;

use super::{Bvh, Node};
use crate::aabb::Aabb;
use crate::primitive::{Geometry, PrimId};

/// Bins per axis when searching for a split.
const BINS: usize = 16;
/// Relative cost of visiting a node against testing one primitive.
const TRAVERSAL_COST: f32 = 1.0;
/// A leaf never holds more than this unless its primitives cannot be told apart.
const MAX_LEAF_SIZE: usize = 8;
/// Deepest tree the traversal stack allows; subtrees deeper than this become leaves.
pub(super) const MAX_DEPTH: usize = 60;

/// A primitive as the builder sees it: its box and the box's centre.
#[derive(Clone, Copy)]
struct BuildPrim {
    id: PrimId,
    bounds: Aabb,
    centroid: Vec3,
}

#[derive(Clone, Copy, Default)]
struct Bin {
    bounds: Aabb,
    count: usize,
}

impl Bvh {
    pub fn build(geometry: &Geometry) -> Bvh {
        let mut prims = Vec::new();
        let mut unbounded = Vec::new();
        for id in geometry.prim_ids() {
            match geometry.bounds(id).filter(Aabb::is_finite) {
                Some(bounds) => prims.push(BuildPrim {
                    id,
                    bounds,
                    centroid: bounds.center(),
                }),
                None => unbounded.push(id),
            }
        }
        let mut nodes = Vec::with_capacity(2 * prims.len());
        if !prims.is_empty() {
            nodes.push(leaf(&prims, 0));
            subdivide(&mut nodes, &mut prims, 0, 0, 1);
        }
        Bvh {
            nodes,
            prims: prims.into_iter().map(|p| p.id).collect(),
            unbounded,
        }
    }
}

fn bounds_of(prims: &[BuildPrim]) -> Aabb {
    prims.iter().fold(Aabb::EMPTY, |b, p| b.union(p.bounds))
}

fn leaf(prims: &[BuildPrim], first: usize) -> Node {
    let b = bounds_of(prims);
    Node {
        min: b.min.to_array(),
        first: first as u32,
        max: b.max.to_array(),
        count: prims.len() as u32,
    }
}

/// Splits node `index`, which covers `all[first..first + count]`, while the SAH says it pays.
fn subdivide(
    nodes: &mut Vec<Node>,
    all: &mut [BuildPrim],
    index: usize,
    first: usize,
    depth: usize,
) {
    let count = nodes[index].count as usize;
    let prims = &mut all[first..first + count];
    if count <= 1 || depth >= MAX_DEPTH {
        return;
    }
    let node_bounds = Aabb::new(nodes[index].min.into(), nodes[index].max.into());
    let Some(mid) = partition(prims, node_bounds) else {
        return;
    };
    let left = nodes.len();
    nodes.push(leaf(&prims[..mid], first));
    nodes.push(leaf(&prims[mid..], first + mid));
    nodes[index].first = left as u32;
    nodes[index].count = 0;
    subdivide(nodes, all, left, first, depth + 1);
    subdivide(nodes, all, left + 1, first + mid, depth + 1);
}

/// Reorders `prims` around the best SAH split and returns the split index, or `None` when a
/// leaf is cheaper (and small enough).
fn partition(prims: &mut [BuildPrim], node_bounds: Aabb) -> Option<usize> {
    let centroids = Aabb::from_points(prims.iter().map(|p| p.centroid));
    let extent = centroids.extent();
    let mut best: Option<(f32, usize, f32)> = None; // (cost, axis, split position)
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let lo = centroids.min[axis];
        let scale = BINS as f32 / extent[axis];
        let bin_of = |c: f32| (((c - lo) * scale) as usize).min(BINS - 1);
        let mut bins = [Bin::default(); BINS];
        for p in prims.iter() {
            let b = &mut bins[bin_of(p.centroid[axis])];
            b.count += 1;
            b.bounds = b.bounds.union(p.bounds);
        }
        // Sweep from the right to know, for each plane, the right side's area and count.
        let mut right_area = [0.0; BINS];
        let mut right_count = [0; BINS];
        let (mut acc, mut n) = (Aabb::EMPTY, 0);
        for i in (1..BINS).rev() {
            acc = acc.union(bins[i].bounds);
            n += bins[i].count;
            right_area[i] = acc.surface_area();
            right_count[i] = n;
        }
        let (mut acc, mut n) = (Aabb::EMPTY, 0);
        for i in 0..BINS - 1 {
            acc = acc.union(bins[i].bounds);
            n += bins[i].count;
            let cost =
                n as f32 * acc.surface_area() + right_count[i + 1] as f32 * right_area[i + 1];
            if n > 0 && right_count[i + 1] > 0 && best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, lo + (i + 1) as f32 / scale));
            }
        }
    }
    let area = node_bounds.surface_area().max(f32::MIN_POSITIVE);
    let leaf_cost = prims.len() as f32;
    match best {
        Some((cost, axis, split)) => {
            let split_cost = TRAVERSAL_COST + cost / area;
            if split_cost >= leaf_cost && prims.len() <= MAX_LEAF_SIZE {
                return None;
            }
            let mid = partition_in_place(prims, |p| p.centroid[axis] < split);
            // Float rounding can put every centroid on one side: fall back to a median split.
            Some(if mid == 0 || mid == prims.len() {
                median_split(prims, axis)
            } else {
                mid
            })
        }
        // All centroids coincide: no plane separates them. Halve large sets anyway.
        None if prims.len() > MAX_LEAF_SIZE => Some(prims.len() / 2),
        None => None,
    }
}

fn median_split(prims: &mut [BuildPrim], axis: usize) -> usize {
    let mid = prims.len() / 2;
    prims.select_nth_unstable_by(mid, |a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
    mid
}

/// Moves the elements satisfying `left` to the front; returns how many there are.
fn partition_in_place(prims: &mut [BuildPrim], left: impl Fn(&BuildPrim) -> bool) -> usize {
    let mut i = 0;
    for j in 0..prims.len() {
        if left(&prims[j]) {
            prims.swap(i, j);
            i += 1;
        }
    }
    i
}
