//! Partitioning a node's primitives around a plane: those that go left to the front, on one
//! thread ([`partition`]) or on all of them with the same result ([`partition_in_parallel`]).
//!
//! Both know beforehand how many go left (the bins counted them), so both work the same way:
//! list the primitives on the wrong side of that count (those before it that go right, those
//! after it that go left: as many of each), then trade the k-th of one list with the k-th of
//! the other. Neither branches on a primitive's side, which is as good as random: a processor
//! guessing it would be wrong half the time, and each wrong guess costs more than the test.

use rayon::prelude::*;

use super::prims::{Bounds, BuildPrim, CHUNK};

/// Moves the primitives that go left to the front, when `mid` of them do, and gives the boxes
/// around the centroids of those that go right and of those that go left. `scratch` is room
/// for the lists, kept from one call to the next.
pub(super) fn partition(
    prims: &mut [BuildPrim],
    mid: usize,
    goes_left: impl Fn(&BuildPrim) -> bool,
    scratch: &mut Vec<u32>,
) -> [Bounds; 2] {
    // Grown, never cleared: the lists are written before they are read.
    if scratch.len() < prims.len() {
        scratch.resize(prims.len(), 0);
    }
    let (to_right, to_left) = scratch[..prims.len()].split_at_mut(mid);
    let (front, back) = prims.split_at_mut(mid);
    let (n, [fr, fl]) = list_misplaced(front, false, &goes_left, to_right);
    let (m, [br, bl]) = list_misplaced(back, true, &goes_left, to_left);
    for (&a, &b) in to_right[..n].iter().zip(&to_left[..m]) {
        std::mem::swap(&mut front[a as usize], &mut back[b as usize]);
    }
    [fr.union(br), fl.union(bl)]
}

/// Lists in `list` the places in `part` of the primitives that go left (`left_is_misplaced`)
/// or right, and says how many there are, with the boxes around the centroids of the
/// primitives that go right and that go left. `list` is as long as `part`.
fn list_misplaced(
    part: &[BuildPrim],
    left_is_misplaced: bool,
    goes_left: impl Fn(&BuildPrim) -> bool,
    list: &mut [u32],
) -> (usize, [Bounds; 2]) {
    let mut centroids = [Bounds::EMPTY; 2];
    let mut count = 0;
    for (i, p) in part.iter().enumerate() {
        let left = goes_left(p);
        centroids[left as usize] = centroids[left as usize].grow(p.centroid());
        // Written every time, kept only when misplaced: `count` ≤ `i`, so it is in bounds.
        list[count] = i as u32;
        count += (left == left_is_misplaced) as usize;
    }
    (count, centroids)
}

/// [`partition`] on all threads, with the same result whatever their number: pieces of the
/// primitives are listed in parallel, and the trades are made in parallel, piece by piece of
/// the front.
pub(super) fn partition_in_parallel(
    prims: &mut [BuildPrim],
    mid: usize,
    goes_left: impl Fn(&BuildPrim) -> bool + Sync,
) -> [Bounds; 2] {
    let (front, back) = prims.split_at_mut(mid);
    let pieces = |part: &[BuildPrim], left_is_misplaced: bool| -> Vec<(Vec<u32>, [Bounds; 2])> {
        part.par_chunks(CHUNK)
            .enumerate()
            .map(|(c, chunk)| {
                let mut list = vec![0; chunk.len()];
                let (count, centroids) =
                    list_misplaced(chunk, left_is_misplaced, &goes_left, &mut list);
                list.truncate(count);
                list.iter_mut().for_each(|i| *i += (c * CHUNK) as u32);
                (list, centroids)
            })
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
    use glam::Vec3;

    use super::*;
    use crate::aabb::Aabb;
    use crate::bvh::leaf::LeafKind;
    use crate::primitive::PrimId;

    #[test]
    fn both_partitions_move_every_primitive_to_its_side_in_the_same_order() {
        // Unit boxes along x in a scrambled order, every third one going left.
        let n = 3 * CHUNK + 123;
        let prims: Vec<BuildPrim> = (0..n)
            .map(|i| {
                let x = ((i * 7919) % n) as f32;
                let min = Vec3::new(x, 0.0, 0.0);
                let bounds = Aabb::new(min, min + Vec3::ONE);
                BuildPrim::new(bounds, PrimId::triangle(i), LeafKind::Triangles)
            })
            .collect();
        let goes_left = |p: &BuildPrim| p.id().0 % 3 == 1;
        let mid = prims.iter().filter(|p| goes_left(p)).count();
        let (mut one, mut all) = (prims.clone(), prims.clone());
        let centroids_one = partition(&mut one, mid, goes_left, &mut Vec::new());
        let centroids_all = partition_in_parallel(&mut all, mid, goes_left);

        let ids = |prims: &[BuildPrim]| prims.iter().map(|p| p.id()).collect::<Vec<_>>();
        assert_eq!(ids(&one), ids(&all));
        assert!(one[..mid].iter().all(goes_left));
        assert!(!one[mid..].iter().any(goes_left));
        let mut sorted = ids(&one);
        sorted.sort();
        assert_eq!(sorted, ids(&prims));
        // The centroid boxes of each side, against a plain fold.
        let side = |left: bool| {
            let on_side = prims.iter().filter(|p| goes_left(p) == left);
            Aabb::from(on_side.fold(Bounds::EMPTY, |b, p| b.grow(p.centroid())))
        };
        for centroids in [centroids_one, centroids_all] {
            assert_eq!(centroids.map(Aabb::from), [side(false), side(true)]);
        }
    }
}
