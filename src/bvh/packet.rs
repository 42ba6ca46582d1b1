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

use super::leaf::{closest_in_leaf, ones};
use super::ray_box::RayBoxTest;
use super::simd::{Kernel, Lanes, dispatch};
use super::traverse::STACK_SIZE;
use super::{Bvh, Child, Leaf, WIDTH};
use crate::primitive::{Geometry, Hit};
use crate::ray::Ray;
use crate::shapes::ShearedRay;

/// Most rays in one packet: an 8 × 8 tile.
pub const PACKET_SIZE: usize = 64;

/// A child still to visit, with the rays that entered its box (bit r for ray r) and the
/// nearest distance at which one of them did.
#[derive(Clone, Copy)]
struct Entry {
    child: Child,
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
        if !rays.is_empty() {
            let packet = Packet {
                bvh: self,
                geometry,
                rays,
                t_min,
                t_max,
                hits,
            };
            dispatch(self.simd, packet);
        }
    }
}

/// The packet query as a [`Kernel`].
struct Packet<'a> {
    bvh: &'a Bvh,
    geometry: &'a Geometry,
    rays: &'a [Ray],
    t_min: f32,
    t_max: f32,
    hits: &'a mut [Option<Hit>],
}

impl Kernel for Packet<'_> {
    type Output = ();

    #[inline(always)]
    fn run<L: Lanes>(self) {
        let Packet {
            bvh,
            geometry,
            rays,
            t_min,
            t_max,
            hits,
        } = self;
        let n = rays.len();
        // Per-ray state lives in fixed arrays; the slots past the last ray copy it, unused.
        let ray = |r: usize| &rays[r.min(n - 1)];
        let sheared: [ShearedRay; PACKET_SIZE] = array::from_fn(|r| ShearedRay::new(ray(r)));
        // A finite far limit keeps the unused slots of a node, whose boxes lie at +∞, shut.
        let mut t_limit = [t_max.min(f32::MAX); PACKET_SIZE];
        for r in 0..n {
            let (limit, best) = (&mut t_limit[r], &mut hits[r]);
            let unbounded = Leaf::Objects(&bvh.unbounded);
            closest_in_leaf(geometry, unbounded, ray(r), &sheared[r], t_min, limit, best);
        }
        let Some(bounds) = &bvh.root_bounds else {
            return;
        };
        let tests: [RayBoxTest; PACKET_SIZE] = array::from_fn(|r| RayBoxTest::new(ray(r)));
        let all = u64::MAX >> (PACKET_SIZE - n);
        let entered_root =
            ones(all).filter(|&r| tests[r].enter(bounds, t_min, t_limit[r]) != f32::INFINITY);
        let mut stack: ArrayVec<Entry, STACK_SIZE> = ArrayVec::new();
        stack.push(Entry {
            child: Child::node(0),
            rays: entered_root.fold(0, |m, r| m | 1 << r),
            lower: t_min,
        });
        while let Some(Entry {
            child,
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
            if child.is_leaf() {
                let leaf = child.leaf(bvh);
                for r in ones(active) {
                    let (limit, best) = (&mut t_limit[r], &mut hits[r]);
                    closest_in_leaf(geometry, leaf, &rays[r], &sheared[r], t_min, limit, best);
                }
                continue;
            }
            let node = &bvh.nodes[child.first as usize];
            // Which rays enter each child, and the nearest entry among them: a lane-wise
            // minimum and a bit per child and ray, without a branch.
            let mut children_by_ray = [0u8; PACKET_SIZE];
            // SAFETY: `L` is this kernel's lane type, which `dispatch` runs only on a
            // processor with its instructions.
            let nearest = unsafe {
                let mut nearest = L::splat(f32::INFINITY);
                for r in ones(active) {
                    let (t, entered) = tests[r].enter8_lanes::<L>(node, t_min, t_limit[r]);
                    nearest = nearest.min(t);
                    children_by_ray[r] = entered as u8;
                }
                nearest.to_array()
            };
            let child_rays = rays_by_child(&children_by_ray);
            // The children entered go on the stack farthest first, so the nearest comes off
            // next.
            let base = stack.len();
            for (k, &rays) in child_rays.iter().enumerate() {
                if rays == 0 {
                    continue;
                }
                stack.push(Entry {
                    child: Child {
                        first: node.first[k],
                        count: node.count[k],
                    },
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

/// The rays that entered each child (bit r of entry k for ray r) from the children each ray
/// entered (bit k of byte r): a 64 × 8 matrix of bits transposed, eight rays at a time, where
/// moving the bits one by one would take eight shifts and ors per ray at every node.
#[inline(always)]
fn rays_by_child(children_by_ray: &[u8; PACKET_SIZE]) -> [u64; WIDTH] {
    let mut rays_by_child = [0u64; WIDTH];
    for (group, eight) in children_by_ray.chunks_exact(8).enumerate() {
        let rows = u64::from_le_bytes(eight.try_into().expect("eight rays"));
        if rows == 0 {
            continue;
        }
        // Byte k of the transpose holds bit k of each of the eight rays' bytes.
        let columns = transpose_8x8(rows);
        for (k, rays) in rays_by_child.iter_mut().enumerate() {
            *rays |= (columns >> (8 * k) & 0xFF) << (8 * group);
        }
    }
    rays_by_child
}

/// The 8 × 8 matrix of bits whose row i is byte i of `x` and column j bit j of each byte,
/// transposed: bit j of byte i goes to bit i of byte j. Three rounds swap the off-diagonal
/// halves of the 2 × 2, then 4 × 4, then 8 × 8 blocks (Hacker's Delight, §7–3).
#[inline(always)]
fn transpose_8x8(mut x: u64) -> u64 {
    let t = (x ^ (x >> 7)) & 0x00AA_00AA_00AA_00AA;
    x ^= t ^ (t << 7);
    let t = (x ^ (x >> 14)) & 0x0000_CCCC_0000_CCCC;
    x ^= t ^ (t << 14);
    let t = (x ^ (x >> 28)) & 0x0000_0000_F0F0_F0F0;
    x ^ t ^ (t << 28)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rays_of_each_child_are_the_children_of_each_ray_transposed() {
        // Bytes from a xorshift generator, with rays that entered no child and rays that
        // entered all eight mixed in.
        let mut state = 0x9E37_79B9_7F4A_7C15_u64;
        let mut next_byte = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state as u8
        };
        for round in 0..200 {
            let by_ray: [u8; PACKET_SIZE] = array::from_fn(|r| match (round + r) % 5 {
                0 => 0,
                1 => 0xFF,
                _ => next_byte(),
            });
            let by_child = rays_by_child(&by_ray);
            for (k, rays) in by_child.iter().enumerate() {
                for (r, children) in by_ray.iter().enumerate() {
                    assert_eq!(
                        rays >> r & 1,
                        u64::from(children >> k & 1),
                        "ray {r}, child {k}"
                    );
                }
            }
        }
    }
}
