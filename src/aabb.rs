//! Axis-aligned bounding boxes: the volumes the BVH is made of.

use glam::Vec3;

/// An axis-aligned box `[min, max]`. The empty box has `min = +∞`, `max = −∞`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Aabb::EMPTY
    }
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    pub fn new(min: Vec3, max: Vec3) -> Self {
        Aabb { min, max }
    }

    /// The smallest box holding all the points.
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Self {
        points.into_iter().fold(Aabb::EMPTY, |b, p| b.grow(p))
    }

    pub fn grow(self, p: Vec3) -> Self {
        Aabb::new(self.min.min(p), self.max.max(p))
    }

    pub fn union(self, other: Aabb) -> Self {
        Aabb::new(self.min.min(other.min), self.max.max(other.max))
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    pub fn extent(&self) -> Vec3 {
        (self.max - self.min).max(Vec3::ZERO)
    }

    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Surface area, the cost measure of the surface area heuristic (0 for an empty box).
    pub fn surface_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// The eight corners, for transforming a box.
    pub fn corners(&self) -> [Vec3; 8] {
        let (a, b) = (self.min, self.max);
        [
            Vec3::new(a.x, a.y, a.z),
            Vec3::new(b.x, a.y, a.z),
            Vec3::new(a.x, b.y, a.z),
            Vec3::new(b.x, b.y, a.z),
            Vec3::new(a.x, a.y, b.z),
            Vec3::new(b.x, a.y, b.z),
            Vec3::new(a.x, b.y, b.z),
            Vec3::new(b.x, b.y, b.z),
        ]
    }

    /// The slab test, axis by axis: where the ray `origin + t·dir` crosses the box's two planes
    /// on each axis, as the distances `(near, far)` at which it enters and leaves that slab.
    /// `inv_dir` is `1 / dir` per component: a ray parallel to a slab gets ±∞ there (and NaN
    /// when it lies in one of its planes, unless `inv_dir` is the largest finite number there,
    /// as the BVH's walk makes it). The ray is inside the box where it is inside all
    /// three slabs, from the largest `near` to the smallest `far` ([`Self::entry`]).
    #[inline(always)]
    pub fn slabs(&self, origin: Vec3, inv_dir: Vec3) -> (Vec3, Vec3) {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        (t0.min(t1), t0.max(t1))
    }

    /// The slab test: the distance at which the ray enters the box within `[t_min, t_max]`
    /// (`t_min` for a ray that starts inside), or `None` if it misses the box there. See
    /// [`Self::slabs`] for `inv_dir`.
    #[inline(always)]
    pub fn entry(&self, origin: Vec3, inv_dir: Vec3, t_min: f32, t_max: f32) -> Option<f32> {
        let (near, far) = self.slabs(origin, inv_dir);
        let near = near.max_element().max(t_min);
        let far = far.min_element().min(t_max);
        (near <= far).then_some(near)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Aabb {
        Aabb::new(Vec3::ZERO, Vec3::ONE)
    }

    #[test]
    fn slabs_are_ordered_whichever_way_the_ray_goes() {
        let origin = Vec3::new(-1.0, 0.5, 3.0);
        let inv_dir = Vec3::new(1.0, 1.0, -0.5);
        let (near, far) = unit_box().slabs(origin, inv_dir);
        assert_eq!(near, Vec3::new(1.0, -0.5, 1.0));
        assert_eq!(far, Vec3::new(2.0, 0.5, 1.5));
    }

    #[test]
    fn entry_is_where_the_ray_is_inside_all_three_slabs() {
        let b = unit_box();
        let towards = |dir: Vec3| dir.recip();
        // From outside, straight in: enters at x = 0.
        let origin = Vec3::new(-2.0, 0.5, 0.5);
        assert_eq!(
            b.entry(origin, towards(Vec3::X), 0.0, f32::INFINITY),
            Some(2.0)
        );
        // The same ray stopped short of the box, or turned away from it.
        assert_eq!(b.entry(origin, towards(Vec3::X), 0.0, 1.5), None);
        assert_eq!(b.entry(origin, towards(-Vec3::X), 0.0, f32::INFINITY), None);
        // Parallel to the y and z slabs and outside the y one.
        let beside = Vec3::new(-2.0, 1.5, 0.5);
        assert_eq!(b.entry(beside, towards(Vec3::X), 0.0, f32::INFINITY), None);
        // From inside: "entered" at t_min.
        let inside = Vec3::splat(0.5);
        assert_eq!(b.entry(inside, towards(Vec3::Y), 0.25, 9.0), Some(0.25));
        // Diagonally, entering where the last slab is entered.
        let diagonal = Vec3::new(-1.0, -1.5, 0.5);
        assert_eq!(
            b.entry(diagonal, towards(Vec3::new(1.0, 1.0, 0.0)), 0.0, 9.0),
            Some(1.5)
        );
    }
}
