//! The `bvh` crate: its binary SAH tree (built in parallel with `build_par`) walked with its
//! stack-based iterator, which yields every triangle whose box the ray enters (the crate's rays
//! carry no `t` range, so boxes beyond the nearest hit are not pruned). Triangles are tested
//! with `obvhs`'s Möller–Trumbore test, the same as for `obvhs`.

use std::cell::Cell;

use bvh::aabb::{Aabb, Bounded, IntersectsAabb};
use bvh::bounding_hierarchy::{BHShape, BoundingHierarchy};
use bvh::bvh::Bvh;
use glam::Vec3A;
use nalgebra::{Point3, Vector3};

use crate::anchor::{AnchorMesh, AnchorRay, Query};
use crate::obvhs_tracer::triangles_of;
use crate::tracer::{Tracer, WalkCost};

type CrateRay = bvh::ray::Ray<f32, 3>;

/// A triangle as the crate wants it: with its bounds and the index of its leaf.
struct Shape {
    triangle: obvhs::triangle::Triangle,
    face: u32,
    node_index: usize,
}

impl Bounded<f32, 3> for Shape {
    fn aabb(&self) -> Aabb<f32, 3> {
        let point = |v: Vec3A| Point3::new(v.x, v.y, v.z);
        let t = &self.triangle;
        Aabb::with_bounds(
            point(t.v0.min(t.v1).min(t.v2)),
            point(t.v0.max(t.v1).max(t.v2)),
        )
    }
}

impl BHShape<f32, 3> for Shape {
    fn set_bh_node_index(&mut self, index: usize) {
        self.node_index = index;
    }

    fn bh_node_index(&self) -> usize {
        self.node_index
    }
}

pub struct BvhCrateTracer {
    bvh: Bvh<f32, 3>,
    shapes: Vec<Shape>,
}

/// The crate's ray, counting the boxes it is tested against.
struct CountingRay {
    ray: CrateRay,
    boxes: Cell<u32>,
}

impl IntersectsAabb<f32, 3> for CountingRay {
    fn intersects_aabb(&self, aabb: &Aabb<f32, 3>) -> bool {
        self.boxes.set(self.boxes.get() + 1);
        self.ray.intersects_aabb(aabb)
    }
}

fn crate_ray(ray: &AnchorRay) -> CrateRay {
    CrateRay::new(Point3::from(ray.origin), Vector3::from(ray.dir))
}

fn obvhs_ray(ray: &AnchorRay) -> obvhs::ray::Ray {
    obvhs::ray::Ray::new(Vec3A::from(ray.origin), Vec3A::from(ray.dir), 0.0, ray.tfar)
}

impl BvhCrateTracer {
    /// Tests the candidates `query` yields: the nearest hit's face, or (`any`) the first hit's;
    /// and how many triangles it tested.
    fn trace(&self, query: &impl IntersectsAabb<f32, 3>, ray: &AnchorRay, any: bool) -> (i32, u32) {
        let mut test_ray = obvhs_ray(ray);
        let mut face = -1;
        let mut tested = 0;
        for shape in self.bvh.traverse_iterator(query, &self.shapes) {
            tested += 1;
            let t = shape.triangle.intersect(&test_ray);
            if t < test_ray.tmax {
                test_ray.tmax = t;
                face = shape.face as i32;
                if any {
                    break;
                }
            }
        }
        (face, tested)
    }
}

impl Tracer for BvhCrateTracer {
    const NAME: &'static str = "bvh";

    fn build(mesh: &AnchorMesh) -> Result<Self, String> {
        let mut shapes: Vec<Shape> = triangles_of(mesh)?
            .into_iter()
            .enumerate()
            .map(|(face, triangle)| Shape {
                triangle,
                face: face as u32,
                node_index: 0,
            })
            .collect();
        let bvh = Bvh::build_par(&mut shapes);
        Ok(BvhCrateTracer { bvh, shapes })
    }

    fn closest(&self, ray: &AnchorRay) -> i32 {
        self.trace(&crate_ray(ray), ray, false).0
    }

    fn occluded(&self, ray: &AnchorRay) -> bool {
        self.trace(&crate_ray(ray), ray, true).0 >= 0
    }

    fn cost(&self, ray: &AnchorRay, query: Query) -> Option<WalkCost> {
        let counting = CountingRay {
            ray: crate_ray(ray),
            boxes: Cell::new(0),
        };
        let (_, triangles) = self.trace(&counting, ray, query == Query::Occluded);
        // Every interior node reached has both its children's boxes tested, once each (the
        // root's own box is never tested), so the nodes visited are half the boxes.
        Some(WalkCost {
            nodes: counting.boxes.get() / 2,
            triangles,
        })
    }
}
