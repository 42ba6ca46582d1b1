//! The photon map: the photons [`crate::photon`] stored, in a kd-tree, and the irradiance estimate from the
//! photons nearest a point. The tree is implicit: the photons are ordered so that the middle
//! photon of every range splits it along the axis stored beside it, the lower half before it
//! and the upper half after it, so the tree needs no pointers and a search no allocation. A
//! search skips every part of the tree whose region lies farther than the photons found so far
//! (the distance to a region is kept up to date as the search crosses splitting planes, after
//! Arya and Mount), reads 16 bytes a node (the position and the splitting axis, apart from the
//! photons' power and direction), and scans small ranges straight through; a point farther than
//! the largest radius from the box around all the photons costs nothing.

use arrayvec::ArrayVec;
use glam::{Vec3, Vec4};

use crate::aabb::Aabb;
use crate::color::Color;
use crate::settings::MAX_CAUSTIC_GATHER;

/// Ranges of this many photons or fewer are searched one photon after another, without
/// descending further.
pub const LEAF_SIZE: usize = 8;

/// The most photons one estimate may gather.
const MAX_GATHER: usize = MAX_CAUSTIC_GATHER as usize;

/// A photon where it landed: its position, its power (before dividing by the number of photons
/// shot) and the direction it travelled in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {
    pub position: Vec3,
    pub power: Color,
    pub dir: Vec3,
}

/// Photons in a kd-tree, for estimates of the irradiance they bring.
#[derive(Clone, Debug, Default)]
pub struct PhotonMap {
    photons: Vec<Photon>,
    /// The tree as a search reads it, 16 bytes a node: the photon's position at the same index,
    /// and in `w` the axis (0, 1 or 2) its node splits.
    nodes: Vec<Vec4>,
    /// The box around all the photons.
    bounds: Aabb,
    /// How many photons were shot: each stored photon's share of its light's power.
    shot: u64,
    /// How far an estimate looks for photons at most.
    max_radius: f32,
}

impl PhotonMap {
    /// Builds the tree over `photons`, of `shot` photons shot from the lights; estimates look
    /// at most `max_radius` away.
    pub fn build(mut photons: Vec<Photon>, shot: u64, max_radius: f32) -> PhotonMap {
        let mut axes = vec![0; photons.len()];
        split(&mut photons, &mut axes);
        let bounds = Aabb::from_points(photons.iter().map(|p| p.position));
        let nodes = photons
            .iter()
            .zip(&axes)
            .map(|(p, &axis)| p.position.extend(f32::from(axis)))
            .collect();
        PhotonMap {
            photons,
            nodes,
            bounds,
            shot,
            max_radius,
        }
    }

    /// The number of photons stored.
    pub fn len(&self) -> usize {
        self.photons.len()
    }

    pub fn is_empty(&self) -> bool {
        self.photons.is_empty()
    }

    /// The number of photons shot to make the map.
    pub fn shot(&self) -> u64 {
        self.shot
    }

    /// The photons, in the tree's order.
    pub fn photons(&self) -> &[Photon] {
        &self.photons
    }

    /// The tree as a search reads it: each photon's position, with in `w` the axis (0, 1 or 2)
    /// its node splits. The node of the range `lo..hi` is its middle, `(lo + hi) / 2`, splitting
    /// it into `lo..mid` and `mid + 1..hi`; a range of at most [`LEAF_SIZE`] is a leaf.
    pub fn nodes(&self) -> &[Vec4] {
        &self.nodes
    }

    /// The box around all the photons.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// How far an estimate looks for photons at most.
    pub fn max_radius(&self) -> f32 {
        self.max_radius
    }

    /// The irradiance at `point` on a surface whose normal (on the side the light is wanted
    /// from) is `normal`, from the `k` photons nearest it (at most [`MAX_CAUSTIC_GATHER`], within the
    /// map's largest radius): their power, over the disc that holds them, each photon weighted
    /// by a cone filter (1 at the point, 0 at the disc's edge) so that caustics keep sharp
    /// edges. Photons that arrived from behind the surface do not count.
    pub fn irradiance(&self, point: Vec3, normal: Vec3, k: usize) -> Color {
        if self.photons.is_empty() || k == 0 {
            return Color::ZERO;
        }
        let mut nearest = Nearest::new(k.min(MAX_GATHER), self.max_radius * self.max_radius);
        // How far outside the photons' box the point is, along each axis.
        let outside = (self.bounds.min - point)
            .max(point - self.bounds.max)
            .max(Vec3::ZERO);
        let distance2 = outside.length_squared();
        if distance2 >= nearest.max_d2 {
            return Color::ZERO;
        }
        self.gather(
            0,
            self.photons.len(),
            point,
            outside,
            distance2,
            &mut nearest,
        );
        let r2 = if nearest.is_full() {
            nearest.max_d2
        } else {
            self.max_radius * self.max_radius
        };
        if r2 <= 0.0 {
            return Color::ZERO;
        }
        let r = r2.sqrt();
        let mut sum = Color::ZERO;
        for &(d2, i) in &nearest.heap {
            let photon = &self.photons[i as usize];
            if photon.dir.dot(normal) < 0.0 {
                sum += photon.power * (1.0 - d2.sqrt() / r);
            }
        }
        // The cone filter keeps a third of the disc's weight: ∫(1 − d/r) dA = πr²/3.
        sum / (std::f32::consts::PI * r2 / 3.0 * self.shot as f32)
    }

    /// Offers the photons of the range `lo..hi` to `nearest`, skipping the half-ranges whose
    /// region lies farther away than its current radius. `offsets` are the distances from the
    /// point to the range's region along each axis (0 where the point lies within its slab), and
    /// `distance2` the sum of their squares: the squared distance to the region.
    fn gather(
        &self,
        lo: usize,
        hi: usize,
        point: Vec3,
        offsets: Vec3,
        distance2: f32,
        nearest: &mut Nearest,
    ) {
        if hi - lo <= LEAF_SIZE {
            for (i, node) in self.nodes[lo..hi].iter().enumerate() {
                nearest.offer(point.distance_squared(node.truncate()), (lo + i) as u32);
            }
            return;
        }
        let mid = (lo + hi) / 2;
        let node = self.nodes[mid];
        let axis = node.w as usize;
        let delta = point[axis] - node[axis];
        let (near, far) = if delta < 0.0 {
            ((lo, mid), (mid + 1, hi))
        } else {
            ((mid + 1, hi), (lo, mid))
        };
        self.gather(near.0, near.1, point, offsets, distance2, nearest);
        nearest.offer(point.distance_squared(node.truncate()), mid as u32);
        // Across the splitting plane, the region is at least |delta| away along its axis.
        let far_distance2 = distance2 - offsets[axis] * offsets[axis] + delta * delta;
        if far_distance2 < nearest.max_d2 {
            let mut far_offsets = offsets;
            far_offsets[axis] = delta.abs();
            self.gather(far.0, far.1, point, far_offsets, far_distance2, nearest);
        }
    }
}

/// Orders `photons` into the implicit tree, with the splitting axis of each node in `axes`: the
/// middle photon splits the range along the axis where the photons spread most.
fn split(photons: &mut [Photon], axes: &mut [u8]) {
    if photons.len() <= 1 {
        return;
    }
    let (lo, hi) = photons.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p.position), hi.max(p.position)),
    );
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = photons.len() / 2;
    photons.select_nth_unstable_by(mid, |a, b| a.position[axis].total_cmp(&b.position[axis]));
    axes[mid] = axis as u8;
    let (left, rest) = photons.split_at_mut(mid);
    let (left_axes, rest_axes) = axes.split_at_mut(mid);
    split(left, left_axes);
    split(&mut rest[1..], &mut rest_axes[1..]);
}

/// The `k` nearest photons found so far, as a max-heap on the squared distance, and the
/// squared radius beyond which no photon can join: the farthest kept once there are `k`.
struct Nearest {
    heap: ArrayVec<(f32, u32), MAX_GATHER>,
    k: usize,
    max_d2: f32,
}

impl Nearest {
    fn new(k: usize, max_d2: f32) -> Nearest {
        Nearest {
            heap: ArrayVec::new(),
            k,
            max_d2,
        }
    }

    fn is_full(&self) -> bool {
        self.heap.len() == self.k
    }

    fn offer(&mut self, d2: f32, index: u32) {
        if d2 >= self.max_d2 {
            return;
        }
        if self.is_full() {
            // Replace the farthest, then let it sink to its place.
            self.heap[0] = (d2, index);
            let mut i = 0;
            loop {
                let (a, b) = (2 * i + 1, 2 * i + 2);
                let mut largest = i;
                for c in [a, b] {
                    if c < self.heap.len() && self.heap[c].0 > self.heap[largest].0 {
                        largest = c;
                    }
                }
                if largest == i {
                    break;
                }
                self.heap.swap(i, largest);
                i = largest;
            }
        } else {
            // Add at the end, then let it rise to its place.
            self.heap.push((d2, index));
            let mut i = self.heap.len() - 1;
            while i > 0 && self.heap[(i - 1) / 2].0 < self.heap[i].0 {
                self.heap.swap(i, (i - 1) / 2);
                i = (i - 1) / 2;
            }
        }
        if self.is_full() {
            self.max_d2 = self.heap[0].0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::hash;

    fn unit(i: u32) -> f32 {
        (hash(i) >> 8) as f32 / (1u32 << 24) as f32
    }

    fn random_photons(n: u32) -> Vec<Photon> {
        (0..n)
            .map(|i| Photon {
                position: Vec3::new(unit(3 * i), unit(3 * i + 1), unit(3 * i + 2)),
                power: Color::ONE,
                dir: -Vec3::Y,
            })
            .collect()
    }

    #[test]
    fn the_k_nearest_are_those_a_brute_force_search_finds() {
        let photons = random_photons(2000);
        let map = PhotonMap::build(photons.clone(), 1, 10.0);
        for q in 0..50 {
            let point = Vec3::new(unit(9000 + q), unit(9100 + q), unit(9200 + q));
            let mut nearest = Nearest::new(20, 100.0);
            map.gather(0, map.len(), point, Vec3::ZERO, 0.0, &mut nearest);
            let mut found: Vec<f32> = nearest.heap.iter().map(|&(d2, _)| d2).collect();
            found.sort_by(f32::total_cmp);
            let mut all: Vec<f32> = photons
                .iter()
                .map(|p| p.position.distance_squared(point))
                .collect();
            all.sort_by(f32::total_cmp);
            assert_eq!(found, all[..20]);
        }
    }

    #[test]
    fn a_uniform_density_gives_its_irradiance() {
        // Photons of power 1 on a 300 × 300 grid over the unit square at z = 0, arriving from
        // above, 8 photons shot: the irradiance is 90 000 / 8 per unit area.
        let n = 300;
        let photons: Vec<Photon> = (0..n * n)
            .map(|i| Photon {
                position: Vec3::new(
                    ((i % n) as f32 + 0.5) / n as f32,
                    ((i / n) as f32 + 0.5) / n as f32,
                    0.0,
                ),
                power: Color::ONE,
                dir: -Vec3::Z,
            })
            .collect();
        let map = PhotonMap::build(photons, 8, 1.0);
        let e = map.irradiance(Vec3::new(0.5, 0.5, 0.0), Vec3::Z, 400);
        let expected = (n * n) as f32 / 8.0;
        assert!((e.x / expected - 1.0).abs() < 0.03, "{e} vs {expected}");
        // Seen from below, the photons arrived from behind.
        assert_eq!(
            map.irradiance(Vec3::new(0.5, 0.5, 0.0), -Vec3::Z, 400),
            Color::ZERO
        );
    }

    #[test]
    fn no_photons_within_reach_is_no_light() {
        let map = PhotonMap::build(random_photons(100), 1, 0.1);
        assert_eq!(map.irradiance(Vec3::splat(5.0), Vec3::Y, 10), Color::ZERO);
        assert_eq!(
            PhotonMap::default().irradiance(Vec3::ZERO, Vec3::Y, 10),
            Color::ZERO
        );
    }
}
