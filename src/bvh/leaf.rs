//! What the leaves of the BVH hold and how a ray tests them. A leaf holds one [`LeafKind`] of
//! primitive: mesh triangles, or spheres, open cylinders or small polygons placed in the world,
//! each kind in packs of four tested at once ([`Pack`]), or any other objects, tested one by
//! one through their shape, or instances, which a walk enters (`instances`). Whatever the
//! kind, a ray gets exactly the hits the one-by-one tests would give.

use std::ops::ControlFlow;

use super::Bvh;
use crate::primitive::{Geometry, Hit, Object, PrimId, PrimKind};
use crate::ray::Ray;
use crate::shapes::{
    CylinderPack, LaneHits, ObjectPack, PACK_SIZE, PolygonPack, Shape, ShearedRay, SpherePack,
    TriangleHit, TrianglePack,
};

/// What a leaf holds; the builder never mixes kinds in a leaf. Ordered as the builder splits a
/// node's kinds apart: objects first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum LeafKind {
    /// Any object, one test each.
    Objects,
    /// Spheres placed in the world, in [`SpherePack`]s.
    Spheres,
    /// Open tapered cylinders placed in the world, in [`CylinderPack`]s.
    Cylinders,
    /// Polygons placed in the world that fit a [`PolygonPack`].
    Polygons,
    /// Mesh triangles, in [`TrianglePack`]s.
    Triangles,
    /// Instances of models, each walked into.
    Instances,
}

impl LeafKind {
    /// How many kinds there are.
    pub(super) const COUNT: usize = 6;

    /// The kind of leaf that primitive `id` goes in.
    pub(super) fn of(geometry: &Geometry, id: PrimId) -> LeafKind {
        let object = match id.kind() {
            PrimKind::Object(object) => object,
            PrimKind::Triangle(_) => return LeafKind::Triangles,
            PrimKind::Instance(_) => return LeafKind::Instances,
        };
        match &geometry.objects[object] {
            Object {
                shape: Shape::Sphere(_),
                transform: None,
                ..
            } => LeafKind::Spheres,
            Object {
                shape: Shape::TaperedCylinder(cylinder),
                transform: None,
                ..
            } if CylinderPack::fits(cylinder) => LeafKind::Cylinders,
            Object {
                shape: Shape::Polygon(polygon),
                transform: None,
                ..
            } if PolygonPack::fits(polygon) => LeafKind::Polygons,
            _ => LeafKind::Objects,
        }
    }

    /// How many primitives one test takes.
    pub(super) fn block(self) -> u32 {
        match self {
            LeafKind::Objects | LeafKind::Instances => 1,
            _ => PACK_SIZE as u32,
        }
    }

    /// The kind stored in the top bits of a wide node's `count` (see `Child`).
    pub(super) fn from_bits(bits: u32) -> LeafKind {
        match bits {
            0 => LeafKind::Objects,
            1 => LeafKind::Spheres,
            2 => LeafKind::Cylinders,
            3 => LeafKind::Polygons,
            4 => LeafKind::Triangles,
            _ => LeafKind::Instances,
        }
    }
}

/// A leaf's primitives.
#[derive(Clone, Copy, Debug)]
pub enum Leaf<'a> {
    Objects(&'a [PrimId]),
    Spheres(&'a [SpherePack]),
    Cylinders(&'a [CylinderPack]),
    Polygons(&'a [PolygonPack]),
    Triangles(&'a [TrianglePack]),
}

/// What a walk reaches at a leaf of the tree: primitives to test, or instances to walk into.
#[derive(Clone, Copy, Debug)]
pub enum Reached<'a> {
    Prims(Leaf<'a>),
    /// Instances, listed in the BVH's `objects`.
    Instances(&'a [PrimId]),
}

impl Reached<'_> {
    /// The leaf of `kind` with `count` entries from `first` in the BVH's array of that kind.
    #[inline(always)]
    pub(super) fn in_bvh(bvh: &Bvh, kind: LeafKind, first: usize, count: usize) -> Reached<'_> {
        let leaf = match kind {
            LeafKind::Objects => Leaf::Objects(&bvh.objects[first..][..count]),
            LeafKind::Spheres => Leaf::Spheres(&bvh.spheres[first..][..count]),
            LeafKind::Cylinders => Leaf::Cylinders(&bvh.cylinders[first..][..count]),
            LeafKind::Polygons => Leaf::Polygons(&bvh.polygons[first..][..count]),
            LeafKind::Triangles => Leaf::Triangles(&bvh.packs[first..][..count]),
            LeafKind::Instances => return Reached::Instances(&bvh.objects[first..][..count]),
        };
        Reached::Prims(leaf)
    }

    /// The primitives (or instances) of the leaf.
    pub fn prims(&self) -> Vec<PrimId> {
        match self {
            Reached::Prims(leaf) => leaf.prims(),
            Reached::Instances(instances) => instances.to_vec(),
        }
    }
}

impl Leaf<'_> {
    /// Primitive tests the leaf takes, for counting: four lanes to a pack.
    pub fn tests(&self) -> usize {
        match self {
            Leaf::Objects(objects) => objects.len(),
            Leaf::Spheres(packs) => packs.len() * PACK_SIZE,
            Leaf::Cylinders(packs) => packs.len() * PACK_SIZE,
            Leaf::Polygons(packs) => packs.len() * PACK_SIZE,
            Leaf::Triangles(packs) => packs.len() * PACK_SIZE,
        }
    }

    /// The primitives of the leaf.
    pub fn prims(&self) -> Vec<PrimId> {
        fn tagged<P: Pack>(packs: &[P]) -> Vec<PrimId> {
            let tags = packs.iter().flat_map(|pack| *pack.tags());
            tags.filter(|&tag| tag != u32::MAX).map(PrimId).collect()
        }
        match self {
            Leaf::Objects(objects) => objects.to_vec(),
            Leaf::Spheres(packs) => tagged(packs),
            Leaf::Cylinders(packs) => tagged(packs),
            Leaf::Polygons(packs) => tagged(packs),
            Leaf::Triangles(packs) => tagged(packs),
        }
    }
}

/// Four primitives of one kind tested against a ray at once; each lane's tag is its
/// [`PrimId`] (`u32::MAX` for an unused lane).
pub(super) trait Pack {
    /// What the test finds, kept until a lane's hit is asked for.
    type Hits;
    /// The lanes `ray` hits with `t` in `(t_min, t_max)`.
    fn test(&self, ray: &Ray, sheared: &ShearedRay, t_min: f32, t_max: f32) -> Self::Hits;
    /// Bit k set where lane k is hit.
    fn mask(hits: &Self::Hits) -> u32;
    /// The hit in lane `k`, which must be in the mask.
    fn hit(&self, hits: &Self::Hits, k: usize) -> Hit;
    fn tags(&self) -> &[u32; PACK_SIZE];
}

impl Pack for TrianglePack {
    type Hits = crate::shapes::PackHits;
    #[inline(always)]
    fn test(&self, _: &Ray, sheared: &ShearedRay, t_min: f32, t_max: f32) -> Self::Hits {
        self.intersect(sheared, t_min, t_max)
    }
    #[inline(always)]
    fn mask(hits: &Self::Hits) -> u32 {
        hits.mask
    }
    #[inline(always)]
    fn hit(&self, hits: &Self::Hits, k: usize) -> Hit {
        let TriangleHit { t, bary } = hits.hit(k);
        Hit {
            t,
            prim: PrimId(self.tags[k]),
            part: 0,
            bary,
        }
    }
    fn tags(&self) -> &[u32; PACK_SIZE] {
        &self.tags
    }
}

/// The packs of objects (spheres, cylinders, polygons): a hit is the object's, at the lane's
/// `t`, as [`Geometry::intersect_prepared`] reports a one-part object's.
impl<P: ObjectPack> Pack for P {
    type Hits = LaneHits;
    #[inline(always)]
    fn test(&self, ray: &Ray, _: &ShearedRay, t_min: f32, t_max: f32) -> LaneHits {
        self.intersect(ray, t_min, t_max)
    }
    #[inline(always)]
    fn mask(hits: &LaneHits) -> u32 {
        hits.mask
    }
    #[inline(always)]
    fn hit(&self, hits: &LaneHits, k: usize) -> Hit {
        Hit {
            t: hits.t[k],
            prim: PrimId(ObjectPack::tags(self)[k]),
            part: 0,
            bary: glam::Vec2::ZERO,
        }
    }
    fn tags(&self) -> &[u32; PACK_SIZE] {
        ObjectPack::tags(self)
    }
}

/// Tests the primitives of `leaf` against `ray` for its closest hit in `(t_min, t_limit)`: a
/// nearer hit (or one at the same `t` from a primitive earlier in the scene) replaces `best`,
/// and `t_limit` shrinks to just past it, so that the search still finds its ties. The answer
/// does not depend on the order of the tests.
#[inline(always)]
pub(super) fn closest_in_leaf(
    geometry: &Geometry,
    leaf: Leaf,
    ray: &Ray,
    sheared: &ShearedRay,
    t_min: f32,
    t_limit: &mut f32,
    best: &mut Option<Hit>,
) {
    match leaf {
        Leaf::Objects(objects) => {
            for &id in objects {
                if let Some(hit) = geometry.intersect_prepared(id, ray, sheared, t_min, *t_limit) {
                    keep_if_closer(hit, t_limit, best);
                }
            }
        }
        Leaf::Spheres(packs) => closest_in_packs(packs, ray, sheared, t_min, t_limit, best),
        Leaf::Cylinders(packs) => closest_in_packs(packs, ray, sheared, t_min, t_limit, best),
        Leaf::Polygons(packs) => closest_in_packs(packs, ray, sheared, t_min, t_limit, best),
        Leaf::Triangles(packs) => closest_in_packs(packs, ray, sheared, t_min, t_limit, best),
    }
}

#[inline(always)]
fn closest_in_packs<P: Pack>(
    packs: &[P],
    ray: &Ray,
    sheared: &ShearedRay,
    t_min: f32,
    t_limit: &mut f32,
    best: &mut Option<Hit>,
) {
    for pack in packs {
        let hits = pack.test(ray, sheared, t_min, *t_limit);
        for k in ones(P::mask(&hits).into()) {
            keep_if_closer(pack.hit(&hits, k), t_limit, best);
        }
    }
}

/// Makes `hit` the best so far if it is nearer than `best` (or as near, from a primitive
/// earlier in the scene) and nearer than `t_limit`, which an earlier lane of the same pack may
/// have lowered since the test; the limit moves to just past it.
#[inline(always)]
pub(super) fn keep_if_closer(hit: Hit, t_limit: &mut f32, best: &mut Option<Hit>) {
    // Below the limit, which lies just past the best so far, `t` is at most the best's.
    let beats = best.is_none_or(|b| hit.t < b.t || hit.prim.scene_order() < b.prim.scene_order());
    if hit.t < *t_limit && beats {
        *t_limit = hit.t.next_up();
        *best = Some(hit);
    }
}

/// Calls `on_hit` for every primitive of `leaf` that `ray` hits in `(t_min, t_max)`, until it
/// breaks.
#[inline(always)]
pub(super) fn each_in_leaf(
    geometry: &Geometry,
    leaf: Leaf,
    ray: &Ray,
    sheared: &ShearedRay,
    (t_min, t_max): (f32, f32),
    on_hit: &mut impl FnMut(&Hit) -> ControlFlow<()>,
) -> ControlFlow<()> {
    match leaf {
        Leaf::Objects(objects) => {
            for &id in objects {
                if let Some(hit) = geometry.intersect_prepared(id, ray, sheared, t_min, t_max) {
                    on_hit(&hit)?;
                }
            }
            ControlFlow::Continue(())
        }
        Leaf::Spheres(packs) => each_in_packs(packs, ray, sheared, (t_min, t_max), on_hit),
        Leaf::Cylinders(packs) => each_in_packs(packs, ray, sheared, (t_min, t_max), on_hit),
        Leaf::Polygons(packs) => each_in_packs(packs, ray, sheared, (t_min, t_max), on_hit),
        Leaf::Triangles(packs) => each_in_packs(packs, ray, sheared, (t_min, t_max), on_hit),
    }
}

#[inline(always)]
fn each_in_packs<P: Pack>(
    packs: &[P],
    ray: &Ray,
    sheared: &ShearedRay,
    (t_min, t_max): (f32, f32),
    on_hit: &mut impl FnMut(&Hit) -> ControlFlow<()>,
) -> ControlFlow<()> {
    for pack in packs {
        let hits = pack.test(ray, sheared, t_min, t_max);
        for k in ones(P::mask(&hits).into()) {
            on_hit(&pack.hit(&hits, k))?;
        }
    }
    ControlFlow::Continue(())
}

/// The positions of the set bits of `mask`, lowest first.
#[inline(always)]
pub(super) fn ones(mut mask: u64) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (mask != 0).then(|| {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            k
        })
    })
}
