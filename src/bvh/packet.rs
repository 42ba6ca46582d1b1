//! Tracing a packet of coherent rays together: a tile of eye rays, which start at the eye and
//! point almost the same way, visits almost the same nodes. The packet walks the tree once,
//! carrying the set of its rays that entered the current node as a bit mask: each node is
//! fetched once for all of them, each ray is tested only against the children of nodes whose
//! box it entered itself (so rays that part ways cost no more than traced alone), and the
//! sorting and stack work is shared. At a leaf each ray tests the primitives with the same code as
//! [`Bvh::closest_hit`], so each ray gets exactly the hit that it would get alone.

use std::array;

use arrayvec::ArrayVec;
use glam::Vec4;

use super::ray_box::RayBoxTest;
use super::traverse::{STACK_SIZE, closest_among};
use super::{Bvh, WIDTH};
use crate::primitive::{Geometry, Hit};
use crate::ray::Ray;
use crate::shapes::ShearedRay;

/// Most rays in one packet: an 8 × 8 tile.
pub const PACKET_SIZE: usize = 64;

/// A node still to visit, with the rays that entered its box (bit r for ray r) and the
/// nearest distance at which one of them did.
#[derive(Clone, Copy)]
struct Entry {
    node: u32,
    rays: u64,
    lower: f32,
}

impl Bvh {
    /// [`Self::closest_hit`] of each of up to [`PACKET_SIZE`] rays, into `hits`: the same
    /// answers, faster when the rays are coherent (neighbouring eye rays in tile order).
    ///
    /// # Panics
    /// When there are more than [`PACKET_SIZE`] rays, or `hits` is not as long as `rays`.
    pub fn closest_hits(
        &self,
        geometry: &Geometry,
        rays: &[Ray],
        t_min: f32,
        t_max: f32,
        hits: &mut [Option<Hit>],
    ) {
        assert!(
            rays.len() <= PACKET_SIZE,
            "a packet holds {PACKET_SIZE} rays"
        );
        assert_eq!(rays.len(), hits.len(), "one hit per ray");
        hits.fill(None);
        let n = rays.len();
        if n == 0 {
            return;
        }
        // Per-ray state lives in fixed arrays; the slots past the last ray copy it, unused.
        let ray = |r: usize| &rays[r.min(n - 1)];
        let sheared: [ShearedRay; PACKET_SIZE] = array::from_fn(|r| ShearedRay::new(ray(r)));
        let mut t_limit = [t_max; PACKET_SIZE];
        for r in 0..n {
            let (limit, best) = (&mut t_limit[r], &mut hits[r]);
            closest_among(
                geometry,
                &self.unbounded,
                ray(r),
                &sheared[r],
                t_min,
                limit,
                best,
            );
        }
        let Some(root) = self.nodes.first() else {
            return;
        };
        let tests: [RayBoxTest; PACKET_SIZE] = array::from_fn(|r| RayBoxTest::new(ray(r)));
        let all = u64::MAX >> (PACKET_SIZE - n);
        let entered_root =
            ones(all).filter(|&r| tests[r].enter(root, t_min, t_limit[r]) != f32::INFINITY);
        let mut stack: ArrayVec<Entry, STACK_SIZE> = ArrayVec::new();
        stack.push(Entry {
            node: 0,
            rays: entered_root.fold(0, |m, r| m | 1 << r),
            lower: t_min,
        });
        while let Some(Entry {
            node,
            rays: entered,
            lower,
        }) = stack.pop()
        {
            // A ray whose closest hit so far is nearer than where the rays enter the node has
            // nothing more to find in it.
            let active = entered & looking_beyond(&t_limit, lower);
            if active == 0 {
                continue;
            }
            let node = &self.nodes[node as usize];
            if node.is_leaf() {
                let prims = &self.prims[node.first as usize..][..node.count as usize];
                for r in ones(active) {
                    let best = &mut hits[r];
                    let limit = &mut t_limit[r];
                    closest_among(geometry, prims, &rays[r], &sheared[r], t_min, limit, best);
                }
                continue;
            }
            let group = &self.nodes[node.first as usize..][..WIDTH];
            let children = (1u32 << node.children().len()) - 1;
            let mut child_rays = [0u64; WIDTH];
            let mut nearest = Vec4::INFINITY;
            for r in ones(active) {
                let (t, entered) = tests[r].enter4(group, t_min, t_limit[r]);
                let entered = entered & children;
                for (k, rays) in child_rays.iter_mut().enumerate() {
                    *rays |= u64::from(entered >> k & 1) << r;
                }
                nearest = nearest.min(Vec4::select(lanes(entered), t, Vec4::INFINITY));
            }
            // The children entered go on the stack farthest first, so the nearest comes off
            // next.
            let nearest = nearest.to_array();
            let base = stack.len();
            for (k, &rays) in child_rays.iter().enumerate() {
                if rays == 0 {
                    continue;
                }
                stack.push(Entry {
                    node: node.first + k as u32,
                    rays,
                    lower: nearest[k],
                });
                let mut i = stack.len() - 1;
                while i > base && stack[i - 1].lower < stack[i].lower {
                    stack.swap(i - 1, i);
                    i -= 1;
                }
            }
        }
    }
}

/// The positions of the set bits of `mask`, lowest first.
fn ones(mut mask: u64) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let r = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            r
        })
    })
}

/// A lane mask with lane k set where bit k of `bits` is.
fn lanes(bits: u32) -> glam::BVec4A {
    glam::BVec4A::new(bits & 1 != 0, bits & 2 != 0, bits & 4 != 0, bits & 8 != 0)
}

/// The rays whose limit `t_limit` lies beyond `t` (bit r for ray r), four at a time.
#[inline(always)]
fn looking_beyond(t_limit: &[f32; PACKET_SIZE], t: f32) -> u64 {
    let t = Vec4::splat(t);
    t_limit
        .chunks_exact(4)
        .enumerate()
        .fold(0, |mask, (k, four)| {
            let beyond = Vec4::from_slice(four).cmpgt(t).bitmask();
            mask | u64::from(beyond) << (4 * k)
        })
}
