//! The ray–box test of the traversal: the slab test ([`Aabb::entry`]) for one box, and the
//! same test for a node's eight child boxes at once, one per SIMD lane.

use glam::Vec3;

use super::WideNode;
use super::simd::{LANES, Lanes};
use crate::aabb::Aabb;
use crate::ray::Ray;

/// A ray prepared for box tests: its origin and inverse direction, and the origin again,
/// moved by the test's slack ([`Self::with_slack`]): every box is tested as if it were that much
/// larger on every side. 36 bytes, so that a packet's 64 of them stay small.
pub(super) struct RayBoxTest {
    /// The origin the boxes' low faces are measured from: the ray's, plus the slack.
    low_origin: Vec3,
    /// The origin the boxes' high faces are measured from: the ray's, less the slack.
    high_origin: Vec3,
    inv_dir: Vec3,
}

impl RayBoxTest {
    pub(super) fn new(ray: &Ray) -> Self {
        // A direction component of ±0 gets the largest finite inverse of its sign rather than
        // ±∞: a ray in a slab's plane then computes 0·MAX = 0 there, entering the slab, where
        // 0·∞ would be NaN (and lose the slab). So no distance is ever NaN.
        let inv_dir = ray.dir.recip().map(|inv| {
            if inv.is_infinite() {
                f32::MAX.copysign(inv)
            } else {
                inv
            }
        });
        RayBoxTest {
            low_origin: ray.origin,
            high_origin: ray.origin,
            inv_dir,
        }
    }

    /// The test of `ray` against boxes grown by `slack` on every side: `lo − slack − origin`
    /// is `lo − (origin + slack)`, so the growth costs the walk nothing.
    pub(super) fn with_slack(ray: &Ray, slack: f32) -> Self {
        let test = RayBoxTest::new(ray);
        RayBoxTest {
            low_origin: ray.origin + slack,
            high_origin: ray.origin - slack,
            ..test
        }
    }

    /// The ray's origin (for a test without slack, which packets of eye rays use).
    pub(super) fn origin(&self) -> Vec3 {
        self.low_origin
    }

    /// The inverse direction, ±0 components replaced as [`Self::new`] says.
    pub(super) fn inv_dir(&self) -> Vec3 {
        self.inv_dir
    }

    /// Entry distance into `bounds` within `[t_min, t_max]`, or +∞ for a miss: the slab test
    /// of [`Aabb::entry`] (for a test without slack, which packets of eye rays use).
    #[inline(always)]
    pub(super) fn enter(&self, bounds: &Aabb, t_min: f32, t_max: f32) -> f32 {
        bounds
            .entry(self.origin(), self.inv_dir, t_min, t_max)
            .unwrap_or(f32::INFINITY)
    }

    /// [`Self::enter`] for the eight child boxes of `node` at once, one per lane, with the same
    /// arithmetic in the same order, so each lane's answer is exactly the one-box answer: the
    /// entry distances, and a bit mask of the boxes entered (bit k for child k). It is written
    /// out rather than built on [`Aabb::slabs`] because it runs the other way round: that goes
    /// through one box's three axes, this through one axis of eight boxes at a time.
    #[inline(always)]
    pub(super) fn enter8<L: Lanes>(
        &self,
        node: &WideNode,
        t_min: f32,
        t_max: f32,
    ) -> ([f32; LANES], u32) {
        // SAFETY: `L` is the lane type of the kernel this runs in, which `simd::dispatch` runs
        // only on a processor with its instructions.
        unsafe {
            let (near, far) = self.near_far::<L>(node, t_min, t_max);
            (near.to_array(), near.le_mask(far))
        }
    }

    /// [`Self::enter8`] with the entry distances left in lanes, +∞ in the lanes of the boxes
    /// not entered, so that a packet can take their minimum over its rays without a branch.
    ///
    /// # Safety
    /// As for [`Lanes`]: only inside a kernel of `L`'s path.
    #[inline(always)]
    pub(super) unsafe fn enter8_lanes<L: Lanes>(
        &self,
        node: &WideNode,
        t_min: f32,
        t_max: f32,
    ) -> (L, u32) {
        unsafe {
            let (near, far) = self.near_far::<L>(node, t_min, t_max);
            (near.le_or(far, L::splat(f32::INFINITY)), near.le_mask(far))
        }
    }

    /// Where the ray enters and leaves each child box of `node`, clamped to `[t_min, t_max]`:
    /// a box is entered where the first is at most the second.
    ///
    /// # Safety
    /// As for [`Lanes`]: only inside a kernel of `L`'s path.
    #[inline(always)]
    unsafe fn near_far<L: Lanes>(&self, node: &WideNode, t_min: f32, t_max: f32) -> (L, L) {
        unsafe {
            let (near_x, far_x) = self.slab::<L>(node, 0);
            let (near_y, far_y) = self.slab::<L>(node, 1);
            let (near_z, far_z) = self.slab::<L>(node, 2);
            let near = near_x.max(near_y).max(near_z).max(L::splat(t_min));
            let far = far_x.min(far_y).min(far_z).min(L::splat(t_max));
            (near, far)
        }
    }

    /// Where the ray enters and leaves the slabs of the children's boxes along `axis`. A
    /// function rather than a closure, so that it is always inlined: a closure would be
    /// compiled apart, without its kernel's instruction set.
    ///
    /// # Safety
    /// As for [`Lanes`]: only inside a kernel of `L`'s path.
    #[inline(always)]
    unsafe fn slab<L: Lanes>(&self, node: &WideNode, axis: usize) -> (L, L) {
        unsafe {
            let (lo, hi) = (L::load(&node.min[axis]), L::load(&node.max[axis]));
            // The ray's components copied into all lanes.
            let low_origin = L::splat(self.low_origin[axis]);
            let high_origin = L::splat(self.high_origin[axis]);
            let inv_dir = L::splat(self.inv_dir[axis]);
            let t0 = lo.sub(low_origin).mul(inv_dir);
            let t1 = hi.sub(high_origin).mul(inv_dir);
            (t0.min(t1), t0.max(t1))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Simd;
    use super::super::simd::{Kernel, dispatch};
    use super::*;

    /// A node whose children are `boxes`, the rest of its slots unused.
    fn node_of(boxes: &[([f32; 3], [f32; 3])]) -> WideNode {
        let mut node = WideNode {
            min: [[f32::INFINITY; LANES]; 3],
            max: [[f32::INFINITY; LANES]; 3],
            first: [0; LANES],
            count: [0; LANES],
        };
        for (k, (min, max)) in boxes.iter().enumerate() {
            for axis in 0..3 {
                node.min[axis][k] = min[axis];
                node.max[axis][k] = max[axis];
            }
            node.count[k] = 1;
        }
        node
    }

    /// The box test on one path, as a kernel.
    struct Enter8<'a>(&'a RayBoxTest, &'a WideNode, f32);

    impl Kernel for Enter8<'_> {
        type Output = ([f32; LANES], u32);
        #[inline(always)]
        fn run<L: Lanes>(self) -> Self::Output {
            self.0.enter8::<L>(self.1, 0.0, self.2)
        }
    }

    /// The packet's box test on one path, as a kernel: its lanes and mask.
    struct Enter8Lanes<'a>(&'a RayBoxTest, &'a WideNode, f32);

    impl Kernel for Enter8Lanes<'_> {
        type Output = ([f32; LANES], u32);
        #[inline(always)]
        fn run<L: Lanes>(self) -> Self::Output {
            // SAFETY: run by `dispatch`, on a processor with `L`'s instructions.
            unsafe {
                let (t, mask) = self.0.enter8_lanes::<L>(self.1, 0.0, self.2);
                (t.to_array(), mask)
            }
        }
    }

    #[test]
    fn eight_boxes_at_once_answer_as_one_box_at_a_time_on_every_path() {
        let boxes = [
            ([0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
            ([2.0, -1.0, 0.0], [3.0, 0.0, 1.0]),
            ([-1.0, -1.0, -1.0], [-0.5, 5.0, 2.0]),
            ([0.0, 1.0, 0.0], [1.0, 2.0, 1.0]),
            ([-3.0, -3.0, -3.0], [3.0, 3.0, 3.0]),
            ([5.0, 5.0, 5.0], [5.0, 5.0, 5.0]),
        ];
        let node = node_of(&boxes);
        let rays = [
            Ray::new(Vec3::new(-5.0, 0.5, 0.5), Vec3::X),
            // From inside the first box, up into the fourth.
            Ray::new(Vec3::splat(0.5), Vec3::Y),
            Ray::new(Vec3::new(2.5, -5.0, 0.5), Vec3::Y),
            Ray::new(Vec3::splat(-5.0), Vec3::ONE),
            // In the plane y = 0 of the first two boxes' faces.
            Ray::new(Vec3::new(-5.0, 0.0, 0.5), Vec3::X),
            Ray::new(Vec3::new(0.5, 1.5, 5.0), -Vec3::Z),
            Ray::new(Vec3::new(9.0, 9.0, 9.0), Vec3::X),
            // Through the point box, and away from everything along +x, +y, +z.
            Ray::new(Vec3::new(4.0, 4.0, 4.0), Vec3::ONE),
            Ray::new(Vec3::new(10.0, 10.0, 10.0), Vec3::ONE),
        ];
        let mut entered = 0;
        for simd in Simd::supported() {
            for ray in &rays {
                let test = RayBoxTest::new(ray);
                for t_max in [100.0, f32::MAX] {
                    let (t, mask) = dispatch(simd, Enter8(&test, &node, t_max));
                    // The packet's lanes: the same entries, +∞ where a box is not entered.
                    let (lanes, lanes_mask) = dispatch(simd, Enter8Lanes(&test, &node, t_max));
                    assert_eq!(lanes_mask, mask, "{simd}: {ray:?}");
                    for (k, (t_k, lane)) in t.iter().zip(lanes).enumerate() {
                        let expected = if mask >> k & 1 == 1 {
                            *t_k
                        } else {
                            f32::INFINITY
                        };
                        assert_eq!(lane.to_bits(), expected.to_bits(), "{simd}: lane {k}");
                    }
                    for (k, t_k) in t.into_iter().enumerate() {
                        let one = match boxes.get(k) {
                            Some(&(min, max)) => {
                                test.enter(&Aabb::new(min.into(), max.into()), 0.0, t_max)
                            }
                            None => f32::INFINITY,
                        };
                        let hit = one != f32::INFINITY;
                        assert_eq!(mask >> k & 1 == 1, hit, "{simd}: box {k}, {ray:?}");
                        if hit {
                            assert_eq!(t_k.to_bits(), one.to_bits(), "{simd}: box {k}");
                            entered += 1;
                        }
                    }
                }
            }
        }
        assert!(entered >= 12, "the rays enter boxes: {entered}");
    }

    #[test]
    fn a_ray_in_the_plane_of_a_face_enters_the_box_on_every_path() {
        // Along +x in the plane y = 0 of the box's bottom face, and along −z in its plane
        // x = 1: with an infinite 1/dir these were 0·∞ = NaN, and missed.
        let node = node_of(&[([0.0, 0.0, 0.0], [1.0, 1.0, 1.0])]);
        let rays = [
            (Ray::new(Vec3::new(-5.0, 0.0, 0.5), Vec3::X), 5.0),
            (Ray::new(Vec3::new(1.0, 0.5, 3.0), -Vec3::Z), 2.0),
        ];
        for simd in Simd::supported() {
            for (ray, t_enter) in &rays {
                let (t, mask) = dispatch(simd, Enter8(&RayBoxTest::new(ray), &node, 100.0));
                assert_eq!((mask, t[0]), (1, *t_enter), "{simd}: {ray:?}");
            }
        }
    }
}
