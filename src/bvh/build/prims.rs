//! The primitives as the builder sees them: a box and centroid each, in SIMD registers
//! ([`BuildPrim`], [`Bounds`]), and the extent of a node's primitives ([`Extent`]).

use glam::{Vec3, Vec3A, Vec4, Vec4Swizzles};
use rayon::prelude::*;

use crate::aabb::Aabb;
use crate::bvh::leaf::LeafKind;
use crate::primitive::PrimId;
use crate::shapes::Triangle;

/// Primitives per piece of a node binned or partitioned on all threads.
pub(super) const CHUNK: usize = 1 << 13;

/// An axis-aligned box held in SIMD registers, for the builder's inner loops.
#[derive(Clone, Copy)]
pub(super) struct Bounds {
    pub(super) min: Vec3A,
    pub(super) max: Vec3A,
}

impl Bounds {
    pub(super) const EMPTY: Bounds = Bounds {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    pub(super) fn union(self, other: Bounds) -> Bounds {
        Bounds {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    #[inline(always)]
    pub(super) fn grow(self, p: Vec3A) -> Bounds {
        Bounds {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// [`Aabb::surface_area`] of a non-empty box, with the same arithmetic, in SIMD.
    #[inline(always)]
    pub(super) fn surface_area(&self) -> f32 {
        let e = (self.max - self.min).max(Vec3A::ZERO);
        let products = e * Vec3A::new(e.y, e.z, e.x);
        2.0 * (products.x + products.y + products.z)
    }
}

impl From<Bounds> for Aabb {
    fn from(b: Bounds) -> Aabb {
        Aabb::new(Vec3::from(b.min), Vec3::from(b.max))
    }
}

/// A primitive as the builder sees it, in 32 bytes: its box, with its id kept in the fourth
/// lane of the box's min corner (where a [`Vec3A`] has an unused lane anyway) and its
/// [`LeafKind`] in the max corner's, as a small float.
#[derive(Clone, Copy)]
pub(super) struct BuildPrim {
    min: Vec4,
    max: Vec4,
}

impl BuildPrim {
    pub(super) fn new(bounds: Aabb, id: PrimId, kind: LeafKind) -> BuildPrim {
        BuildPrim {
            min: bounds.min.extend(f32::from_bits(id.0)),
            max: bounds.max.extend(kind as u32 as f32),
        }
    }

    /// A triangle with finite corners, its box made in SIMD registers (the same box as
    /// [`Aabb::from_points`] makes); `None` when a corner is not finite.
    #[inline(always)]
    pub(super) fn of_triangle(triangle: &Triangle, id: PrimId) -> Option<BuildPrim> {
        let [a, b, c] = [triangle.p0, triangle.p1, triangle.p2].map(Vec3A::from);
        (a.is_finite() && b.is_finite() && c.is_finite()).then(|| BuildPrim {
            min: a.min(b).min(c).extend(f32::from_bits(id.0)),
            max: a.max(b).max(c).extend(LeafKind::Triangles as u32 as f32),
        })
    }

    pub(super) fn id(&self) -> PrimId {
        PrimId(self.min.w.to_bits())
    }

    /// The box. Its min corner's fourth lane, the id, is a tiny (denormal) number as a float,
    /// and arithmetic on such numbers is very slow: it is replaced by the third lane.
    #[inline(always)]
    pub(super) fn bounds(&self) -> Bounds {
        Bounds {
            min: Vec3A::from_vec4(self.min.xyzz()),
            max: Vec3A::from_vec4(self.max),
        }
    }

    /// Twice the centroid (the builder only compares centroids, so it skips the halving).
    #[inline(always)]
    pub(super) fn centroid(&self) -> Vec3A {
        let b = self.bounds();
        b.min + b.max
    }

    pub(super) fn kind(&self) -> LeafKind {
        LeafKind::from_bits(self.max.w as u32)
    }
}

/// The primitives of a node, with what splitting them needs: their bounds and the bounds of
/// their (doubled) centroids.
#[derive(Clone, Copy)]
pub(super) struct Extent {
    pub(super) bounds: Bounds,
    pub(super) centroids: Bounds,
    /// Whether some of the primitives may be of [`LeafKind::Objects`]. `false` only where none
    /// is: a node without them has children without them, so a mesh is looked through for
    /// them once, at the root.
    pub(super) may_hold_objects: bool,
}

impl Extent {
    const EMPTY: Extent = Extent {
        bounds: Bounds::EMPTY,
        centroids: Bounds::EMPTY,
        may_hold_objects: true,
    };

    pub(super) fn of(prims: &[BuildPrim]) -> Extent {
        prims.iter().fold(Extent::EMPTY, |e, p| e.add(p))
    }

    /// [`Extent::of`] on all threads: minima and maxima come out the same in any order.
    pub(super) fn of_in_parallel(prims: &[BuildPrim]) -> Extent {
        prims
            .par_chunks(CHUNK)
            .map(Extent::of)
            .reduce(|| Extent::EMPTY, Extent::union)
    }

    #[inline(always)]
    fn add(self, p: &BuildPrim) -> Extent {
        Extent {
            bounds: self.bounds.union(p.bounds()),
            centroids: self.centroids.grow(p.centroid()),
            ..self
        }
    }

    fn union(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.union(other.bounds),
            centroids: self.centroids.union(other.centroids),
            may_hold_objects: self.may_hold_objects || other.may_hold_objects,
        }
    }
}
