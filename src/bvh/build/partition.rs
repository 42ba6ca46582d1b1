//! Partitioning a node's primitives around a plane: those that go left to the front, on one
//! thread ([`partition`]) or on all of them with the same result ([`partition_in_parallel`]).

use rayon::prelude::*;

use super::prims::{Bounds, BuildPrim, CHUNK};

/// Moves the primitives that go left to the front: says how many they are, and the boxes
/// around the centroids of those that go right and of those that go left. From both ends
/// towards the middle, swapping the pairs that are on the wrong side.
pub(super) fn partition(
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
pub(super) fn partition_in_parallel(
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
