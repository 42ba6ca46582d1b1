//! Tracing a packet of coherent rays together: a tile of eye rays, which start at the eye and
//! point almost the same way, visits almost the same nodes. The packet walks the tree once,
//! carrying the set of its rays that entered the current node as a bit mask: each node is
//! fetched once for all of them, each ray is tested only against the children of nodes whose
//! box it entered itself (so rays that part ways cost no more than traced alone), and the
//! sorting and stack work is shared. When the rays start at one point (eye rays), a node's
//! children that no ray can enter are found for the whole packet with one test, and the rest
//! are tested eight rays at a time (`SharedOrigin`). At a leaf each ray tests the primitives
//! with the same code as [`Bvh::closest_hit`], so each ray gets exactly the hit that it would
//! get alone.

use std::array;

use arrayvec::ArrayVec;
use glam::{Vec3, Vec4};

use super::instances::closest_in_instances;
use super::leaf::{closest_in_leaf, ones};
use super::ray_box::RayBoxTest;
use super::simd::{Kernel, LANES, Lanes, dispatch};
use super::walk::STACK_SIZE;
use super::{Bvh, Child, Leaf, Reached, WIDTH, WideNode};
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
        let limits = [t_max; PACKET_SIZE];
        self.closest_hits_within(
            geometry,
            rays,
            t_min,
            &limits[..rays.len().min(PACKET_SIZE)],
            hits,
        );
    }

    /// [`Self::closest_hits`] with a far limit of its own for each ray: ray r's closest hit with
    /// `t` in `(t_min, t_max[r])`.
    ///
    /// # Panics
    /// When there are more than [`PACKET_SIZE`] rays, or `t_max` or `hits` is not as long as
    /// `rays`.
    pub fn closest_hits_within(
        &self,
        geometry: &Geometry,
        rays: &[Ray],
        t_min: f32,
        t_max: &[f32],
        hits: &mut [Option<Hit>],
    ) {
        assert!(
            rays.len() <= PACKET_SIZE,
            "a packet holds {PACKET_SIZE} rays"
        );
        assert_eq!(rays.len(), hits.len(), "one hit per ray");
        assert_eq!(rays.len(), t_max.len(), "one far limit per ray");
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
    t_max: &'a [f32],
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
        let mut t_limit = [f32::MAX; PACKET_SIZE];
        for (limit, &t_max) in t_limit.iter_mut().zip(t_max) {
            *limit = t_max.min(f32::MAX);
        }
        for r in 0..n {
            let (limit, best) = (&mut t_limit[r], &mut hits[r]);
            let unbounded = Leaf::Objects(&bvh.unbounded);
            closest_in_leaf(geometry, unbounded, ray(r), &sheared[r], t_min, limit, best);
        }
        let Some(bounds) = &bvh.root_bounds else {
            return;
        };
        let tests: [RayBoxTest; PACKET_SIZE] = array::from_fn(|r| RayBoxTest::new(ray(r)));
        let shared = SharedOrigin::of(&tests);
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
                for r in ones(active) {
                    let (ray, sheared) = (&rays[r], &sheared[r]);
                    let (limit, best) = (&mut t_limit[r], &mut hits[r]);
                    match child.leaf(bvh) {
                        Reached::Prims(leaf) => {
                            closest_in_leaf(geometry, leaf, ray, sheared, t_min, limit, best);
                        }
                        Reached::Instances(ids) => closest_in_instances::<L, ()>(
                            geometry,
                            &bvh.models,
                            ids,
                            ray,
                            sheared,
                            t_min,
                            limit,
                            best,
                            &mut (),
                        ),
                    }
                }
                continue;
            }
            let node = &bvh.nodes[child.first as usize];
            // SAFETY: `L` is this kernel's lane type, which `dispatch` runs only on a
            // processor with its instructions.
            let (child_rays, nearest) = unsafe {
                match &shared {
                    Some(shared) => shared.children::<L>(node, active, t_min, &t_limit),
                    None => each_ray::<L>(&tests, node, active, t_min, &t_limit),
                }
            };
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

/// Which of the `active` rays enter each child of `node` (bit r of entry k for ray r), and the
/// nearest entry among them for each child: each ray tests the eight boxes at once.
///
/// # Safety
/// As for [`Lanes`]: only inside a kernel of `L`'s path.
#[inline(always)]
unsafe fn each_ray<L: Lanes>(
    tests: &[RayBoxTest; PACKET_SIZE],
    node: &WideNode,
    active: u64,
    t_min: f32,
    t_limit: &[f32; PACKET_SIZE],
) -> ([u64; WIDTH], [f32; WIDTH]) {
    // A lane-wise minimum and a bit per child and ray, without a branch.
    let mut children_by_ray = [0u8; PACKET_SIZE];
    unsafe {
        let mut nearest = L::splat(f32::INFINITY);
        for r in ones(active) {
            let (t, entered) = tests[r].enter8_lanes::<L>(node, t_min, t_limit[r]);
            nearest = nearest.min(t);
            children_by_ray[r] = entered as u8;
        }
        (rays_by_child(&children_by_ray), nearest.to_array())
    }
}

/// A packet whose rays all start at one point, as eye rays do: a box's planes are then the
/// same distance from every ray's origin, and the slab distances of the rays are those
/// distances times each ray's inverse direction. Rounding keeps products in order (a larger
/// factor never gives a smaller rounded product), so the products with the least and the
/// greatest inverse direction of the packet bound every ray's, exactly: a child box outside
/// those bounds is one that no ray enters, found with one test for the whole packet. The
/// children left are tested eight rays at a time, with each ray's own arithmetic.
struct SharedOrigin {
    origin: Vec3,
    /// Each ray's inverse direction, axis by axis: `inv_dir[axis][r]`.
    inv_dir: [[f32; PACKET_SIZE]; 3],
    /// The least and greatest inverse direction of the packet's rays, per axis.
    inv_min: Vec3,
    inv_max: Vec3,
}

impl SharedOrigin {
    /// The packet's rays as one, when they start at the same point (bit for bit).
    fn of(tests: &[RayBoxTest; PACKET_SIZE]) -> Option<SharedOrigin> {
        let origin = tests[0].origin();
        let same = |o: Vec3| o.to_array().map(f32::to_bits) == origin.to_array().map(f32::to_bits);
        if !tests.iter().all(|test| same(test.origin())) {
            return None;
        }
        let inv_dir = array::from_fn(|axis| array::from_fn(|r| tests[r].inv_dir()[axis]));
        let inv = |r: usize| tests[r].inv_dir();
        let inv_min = (1..PACKET_SIZE).fold(inv(0), |m, r| m.min(inv(r)));
        let inv_max = (1..PACKET_SIZE).fold(inv(0), |m, r| m.max(inv(r)));
        Some(SharedOrigin {
            origin,
            inv_dir,
            inv_min,
            inv_max,
        })
    }

    /// [`each_ray`]'s answer: the children no ray can enter are left out for the whole packet
    /// at once, and the rest are tested eight rays at a time.
    ///
    /// # Safety
    /// As for [`Lanes`]: only inside a kernel of `L`'s path.
    #[inline(always)]
    unsafe fn children<L: Lanes>(
        &self,
        node: &WideNode,
        active: u64,
        t_min: f32,
        t_limit: &[f32; PACKET_SIZE],
    ) -> ([u64; WIDTH], [f32; WIDTH]) {
        // No closures here: one would be compiled apart from this kernel, without its
        // instruction set, and every lane operation in it would become a call.
        unsafe {
            // Each child's planes, measured from the origin as each ray's own test measures
            // them: `planes[axis][side]`, lanes by child.
            let mut planes = [[[0.0; LANES]; 2]; 3];
            // Bounds on every ray's entry and exit along each axis, then on the whole box.
            let (mut near, mut far) = (L::splat(t_min), L::splat(f32::MAX));
            for (axis, sides) in planes.iter_mut().enumerate() {
                let origin = L::splat(self.origin[axis]);
                let lo = L::load(&node.min[axis]).sub(origin);
                let hi = L::load(&node.max[axis]).sub(origin);
                *sides = [lo.to_array(), hi.to_array()];
                let (least, most) = (L::splat(self.inv_min[axis]), L::splat(self.inv_max[axis]));
                let (a, b) = (lo.mul(least), lo.mul(most));
                let (c, d) = (hi.mul(least), hi.mul(most));
                near = near.max(a.min(b).min(c.min(d)));
                far = far.min(a.max(b).max(c.max(d)));
            }
            let maybe = near.le_mask(far);
            // The rays' far limits, −∞ for the rays not active, which then enter nothing.
            let mut limits = [f32::NEG_INFINITY; PACKET_SIZE];
            for r in ones(active) {
                limits[r] = t_limit[r];
            }
            let groups = groups_of(active);
            let mut rays = [0u64; WIDTH];
            let mut nearest = [f32::INFINITY; WIDTH];
            for k in ones(u64::from(maybe)) {
                let mut nearest_k = L::splat(f32::INFINITY);
                for group in ones(groups) {
                    let (near_x, far_x) = self.slab::<L>(&planes, 0, k, group);
                    let (near_y, far_y) = self.slab::<L>(&planes, 1, k, group);
                    let (near_z, far_z) = self.slab::<L>(&planes, 2, k, group);
                    let near = near_x.max(near_y).max(near_z).max(L::splat(t_min));
                    let far = far_x
                        .min(far_y)
                        .min(far_z)
                        .min(L::load(eight(&limits, group)));
                    rays[k] |= u64::from(near.le_mask(far)) << (group * LANES);
                    nearest_k = nearest_k.min(near.le_or(far, L::splat(f32::INFINITY)));
                }
                for t in nearest_k.to_array() {
                    nearest[k] = nearest[k].min(t);
                }
            }
            (rays, nearest)
        }
    }

    /// Where rays `8 group` to `8 group + 7` enter and leave the slab of child `k` along
    /// `axis`, one ray to a lane: each ray's plane distance times its inverse direction.
    ///
    /// # Safety
    /// As for [`Lanes`]: only inside a kernel of `L`'s path.
    #[inline(always)]
    unsafe fn slab<L: Lanes>(
        &self,
        planes: &[[[f32; LANES]; 2]; 3],
        axis: usize,
        k: usize,
        group: usize,
    ) -> (L, L) {
        unsafe {
            let inv_dir = L::load(eight(&self.inv_dir[axis], group));
            let t0 = L::splat(planes[axis][0][k]).mul(inv_dir);
            let t1 = L::splat(planes[axis][1][k]).mul(inv_dir);
            (t0.min(t1), t0.max(t1))
        }
    }
}

/// The values of rays `8 group` to `8 group + 7`.
#[inline(always)]
fn eight(values: &[f32; PACKET_SIZE], group: usize) -> &[f32; LANES] {
    values[group * LANES..][..LANES]
        .try_into()
        .expect("eight lanes")
}

/// The groups of eight rays that have a ray in `rays` (bit g for rays 8g to 8g + 7).
#[inline(always)]
fn groups_of(rays: u64) -> u64 {
    (0..PACKET_SIZE / LANES).fold(0, |groups, g| {
        groups | u64::from(rays >> (g * LANES) & 0xFF != 0) << g
    })
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
    use super::super::Simd;
    use super::*;

    /// Both ways of finding the rays that enter a node's children, on one path.
    struct BothWays<'a> {
        tests: &'a [RayBoxTest; PACKET_SIZE],
        node: &'a WideNode,
        active: u64,
        t_limit: &'a [f32; PACKET_SIZE],
    }

    impl Kernel for BothWays<'_> {
        type Output = [([u64; WIDTH], [f32; WIDTH]); 2];
        #[inline(always)]
        fn run<L: Lanes>(self) -> Self::Output {
            let shared = SharedOrigin::of(self.tests).expect("one origin");
            // SAFETY: run by `dispatch`, on a processor with `L`'s instructions.
            unsafe {
                [
                    each_ray::<L>(self.tests, self.node, self.active, 1.0, self.t_limit),
                    shared.children::<L>(self.node, self.active, 1.0, self.t_limit),
                ]
            }
        }
    }

    #[test]
    fn rays_from_one_point_enter_the_children_they_enter_one_by_one_on_every_path() {
        let mut rng = fastrand::Rng::with_seed(0x2545_F491_4F6C_DD1D);
        let mut random = move |n: u32| rng.u32(..n) as f32;
        let mut entered = 0;
        for round in 0..300 {
            let origin = Vec3::new(random(9) - 4.0, random(9) - 4.0, random(9) - 4.0);
            // Directions in a cone, or anywhere; some along an axis or in a plane of one.
            let spread = [0.05, 0.5, 4.0][round % 3];
            let tests: [RayBoxTest; PACKET_SIZE] = array::from_fn(|r| {
                let mut dir = Vec3::new(1.0, 0.3, -0.2)
                    + spread * Vec3::new(random(21) - 10.0, random(21) - 10.0, random(21) - 10.0)
                        / 10.0;
                if r % 13 == 0 {
                    dir.y = 0.0;
                }
                RayBoxTest::new(&Ray::new(origin, dir))
            });
            let mut node = WideNode {
                min: [[f32::INFINITY; WIDTH]; 3],
                max: [[f32::INFINITY; WIDTH]; 3],
                first: [0; WIDTH],
                count: [0; WIDTH],
            };
            // Up to eight boxes, some flat, most ahead of the rays; the other slots unused.
            for k in 0..(2 + round % 7) {
                let ahead = origin + random(8) * Vec3::new(1.0, 0.3, -0.2);
                for axis in 0..3 {
                    let lo = ahead[axis] + random(5) - 3.0;
                    node.min[axis][k] = lo;
                    node.max[axis][k] = lo + random(4);
                }
            }
            let t_limit: [f32; PACKET_SIZE] =
                array::from_fn(|_| [f32::MAX, 3.0 + random(10)][(random(2)) as usize]);
            let active = [u64::MAX, 0x00FF_00F0_0F00_0001, 1 << 63][round % 3];
            for simd in Simd::supported() {
                let [one_by_one, shared] = dispatch(
                    simd,
                    BothWays {
                        tests: &tests,
                        node: &node,
                        active,
                        t_limit: &t_limit,
                    },
                );
                assert_eq!(shared.0, one_by_one.0, "{simd}, round {round}: rays");
                assert_eq!(shared.1, one_by_one.1, "{simd}, round {round}: nearest");
                entered += shared.0.iter().filter(|&&rays| rays != 0).count();
            }
        }
        assert!(entered > 1000, "rays enter children: {entered}");
    }

    #[test]
    fn the_rays_of_each_child_are_the_children_of_each_ray_transposed() {
        // Random bytes, with rays that entered no child and rays that entered all eight
        // mixed in.
        let mut rng = fastrand::Rng::with_seed(0x9E37_79B9_7F4A_7C15);
        let mut next_byte = || rng.u8(..);
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
