//! Walking into instances ([`crate::primitive::instance`]): the ray, moved into the model's
//! space, walks the model's own tree, and the triangles of each leaf it reaches are moved into
//! the world and tested there, against the world's ray, exactly as a copy's triangles would
//! be. The model's boxes are grown by a bound on the rounding of the two moves
//! ([`crate::transform::Transform::rounding_slack`]), so that no triangle the world's test
//! hits is left unvisited, and the hits are a copy's hits to the last bit.

use std::ops::ControlFlow;

use glam::Vec4;

use super::cost::TraversalCost;
use super::leaf::{Leaf, keep_if_closer, ones};
use super::ray_box::RayBoxTest;
use super::simd::Lanes;
use super::walk::VisitLeaf;
use super::{Bvh, Reached};
use crate::primitive::{Geometry, Hit, Instance, PrimId, PrimKind};
use crate::ray::Ray;
use crate::shapes::{PACK_SIZE, ShearedRay, TriangleHit, TrianglePack};

/// An instance a walk enters: which one, its model's tree, and the test of the ray moved into
/// the model's space against that tree's boxes.
struct Entered<'a> {
    index: usize,
    instance: &'a Instance,
    tree: &'a Bvh,
    test: RayBoxTest,
}

impl<'a> Entered<'a> {
    #[inline(always)]
    fn new(geometry: &'a Geometry, models: &'a [Bvh], id: PrimId, ray: &Ray) -> Entered<'a> {
        let PrimKind::Instance(index) = id.kind() else {
            unreachable!("a leaf of instances holds only instances")
        };
        let instance = &geometry.instances()[index];
        let model = instance.model as usize;
        let bounds = geometry.model_bounds(model);
        let extent = bounds.min.abs().max(bounds.max.abs()).max_element();
        let slack = instance.transform.rounding_slack(ray.origin, extent);
        let object_ray = instance.transform.ray_to_object(ray);
        Entered {
            index,
            instance,
            tree: &models[model],
            test: RayBoxTest::with_slack(&object_ray, slack),
        }
    }
}

/// The triangles of a model's leaf: a tree of a model holds nothing else.
#[inline(always)]
fn model_triangles<'a>(reached: Reached<'a>) -> &'a [TrianglePack] {
    let Reached::Prims(Leaf::Triangles(packs)) = reached else {
        unreachable!("a model's tree holds triangles alone")
    };
    packs
}

/// A model's pack of triangles moved into the world by `instance`, corner by corner as
/// [`Instance::place`] moves a triangle, four lanes at once: each coordinate is
/// `((x_axis·x + y_axis·y) + z_axis·z) + translation`, the products and sums of glam's
/// `Affine3A::transform_point3` in its order, so each lane's corner is that function's to the
/// last bit. The tags stay the model's triangle numbers.
#[inline(always)]
fn placed(pack: &TrianglePack, instance: &Instance) -> TrianglePack {
    let m = &instance.transform.world_from_object;
    let (x, y, z, t) = (
        m.matrix3.x_axis,
        m.matrix3.y_axis,
        m.matrix3.z_axis,
        m.translation,
    );
    let mut placed = *pack;
    for (corner, out) in pack.p.iter().zip(&mut placed.p) {
        let [px, py, pz] = corner.map(Vec4::from_array);
        for axis in 0..3 {
            let along = |column: glam::Vec3A, p: Vec4| Vec4::splat(column[axis]) * p;
            let sum = along(x, px) + along(y, py) + along(z, pz) + Vec4::splat(t[axis]);
            out[axis] = sum.to_array();
        }
    }
    placed
}

/// The hits of the ray `sheared` with a pack of placed triangles, named as hits name them.
#[inline(always)]
fn placed_hits(
    geometry: &Geometry,
    entered: &Entered,
    pack: &TrianglePack,
    sheared: &ShearedRay,
    (t_min, t_max): (f32, f32),
) -> impl Iterator<Item = Hit> {
    let placed = placed(pack, entered.instance);
    let hits = placed.intersect(sheared, t_min, t_max);
    let first = geometry.placed_triangle(entered.index, 0).0;
    ones(hits.mask.into()).map(move |k| {
        let TriangleHit { t, bary } = hits.hit(k);
        Hit {
            t,
            prim: PrimId(first + placed.tags[k]),
            part: 0,
            bary,
        }
    })
}

/// The closest hit of `ray` with the instances `ids` in `(t_min, t_limit)`, as
/// [`super::leaf::closest_in_leaf`] finds it for primitives: a nearer hit (or one as near, from
/// a triangle earlier in the scene) replaces `best` and shrinks `t_limit`.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn closest_in_instances<L: Lanes, C: TraversalCost>(
    geometry: &Geometry,
    models: &[Bvh],
    ids: &[PrimId],
    ray: &Ray,
    sheared: &ShearedRay,
    t_min: f32,
    t_limit: &mut f32,
    best: &mut Option<Hit>,
    cost: &mut C,
) {
    for &id in ids {
        let entered = Entered::new(geometry, models, id, ray);
        let mut closest = Closest {
            geometry,
            entered: &entered,
            sheared,
            t_min,
            best,
        };
        entered
            .tree
            .walk::<L, C, true>(&entered.test, t_min, t_limit, cost, &mut closest);
    }
}

/// The closest hit's tests at a model's leaf.
struct Closest<'a, 'b> {
    geometry: &'a Geometry,
    entered: &'a Entered<'a>,
    sheared: &'a ShearedRay,
    t_min: f32,
    best: &'b mut Option<Hit>,
}

impl<C: TraversalCost> VisitLeaf<C> for Closest<'_, '_> {
    #[inline(always)]
    fn visit<L: Lanes>(
        &mut self,
        reached: Reached,
        t_limit: &mut f32,
        cost: &mut C,
    ) -> ControlFlow<()> {
        let packs = model_triangles(reached);
        cost.prims_tested(packs.len() * PACK_SIZE);
        for pack in packs {
            let range = (self.t_min, *t_limit);
            for hit in placed_hits(self.geometry, self.entered, pack, self.sheared, range) {
                keep_if_closer(hit, t_limit, self.best);
            }
        }
        ControlFlow::Continue(())
    }
}

/// Calls `on_hit` for every triangle of the instances `ids` that `ray` hits in
/// `(t_min, t_max)`, until it breaks, as [`super::leaf::each_in_leaf`] does for primitives.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn each_in_instances<L: Lanes, C: TraversalCost>(
    geometry: &Geometry,
    models: &[Bvh],
    ids: &[PrimId],
    ray: &Ray,
    sheared: &ShearedRay,
    (t_min, t_max): (f32, f32),
    on_hit: &mut impl FnMut(&Hit) -> ControlFlow<()>,
    cost: &mut C,
) -> ControlFlow<()> {
    for &id in ids {
        let entered = Entered::new(geometry, models, id, ray);
        let mut each = Each {
            geometry,
            entered: &entered,
            sheared,
            range: (t_min, t_max),
            on_hit: &mut *on_hit,
            stopped: false,
        };
        let mut limit = t_max;
        entered
            .tree
            .walk::<L, C, false>(&entered.test, t_min, &mut limit, cost, &mut each);
        if each.stopped {
            return ControlFlow::Break(());
        }
    }
    ControlFlow::Continue(())
}

/// The any-hit search's tests at a model's leaf: every hit goes to `on_hit`.
struct Each<'a, F> {
    geometry: &'a Geometry,
    entered: &'a Entered<'a>,
    sheared: &'a ShearedRay,
    range: (f32, f32),
    on_hit: F,
    /// Whether `on_hit` broke off the search.
    stopped: bool,
}

impl<C: TraversalCost, F: FnMut(&Hit) -> ControlFlow<()>> VisitLeaf<C> for Each<'_, F> {
    #[inline(always)]
    fn visit<L: Lanes>(&mut self, reached: Reached, _: &mut f32, cost: &mut C) -> ControlFlow<()> {
        let packs = model_triangles(reached);
        cost.prims_tested(packs.len() * PACK_SIZE);
        for pack in packs {
            for hit in placed_hits(self.geometry, self.entered, pack, self.sheared, self.range) {
                if (self.on_hit)(&hit).is_break() {
                    self.stopped = true;
                    return ControlFlow::Break(());
                }
            }
        }
        ControlFlow::Continue(())
    }
}
