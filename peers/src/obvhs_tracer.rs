//! The `obvhs` crate: its compressed eight-wide BVH (CWBVH, built by PLOC with reinsertion,
//! `medium_build`, which its author tunes to Embree's build time) and its own Möller–Trumbore
//! triangle test, triangles stored in leaf order.

use std::time::Duration;

use glam::{UVec2, Vec3A}; // UVec2: named inside obvhs::traverse!
use obvhs::BvhBuildParams;
use obvhs::cwbvh::CwBvh;
use obvhs::cwbvh::builder::build_cwbvh_from_tris;
use obvhs::ray::Ray;
use obvhs::triangle::Triangle;

use crate::anchor::{AnchorMesh, AnchorRay, Query};
use crate::tracer::{Tracer, WalkCost};

pub struct ObvhsTracer {
    bvh: CwBvh,
    /// The triangles in the BVH's primitive order.
    triangles: Vec<Triangle>,
}

/// `mesh`'s triangles, face by face, as `obvhs` stores them (the `bvh` crate's tracer uses them
/// too).
pub fn triangles_of(mesh: &AnchorMesh) -> Result<Vec<Triangle>, String> {
    let vertex = |i: u32| {
        mesh.positions
            .get(i as usize)
            .map(|&p| Vec3A::from(p))
            .ok_or_else(|| format!("vertex {i} does not exist"))
    };
    mesh.faces
        .iter()
        .map(|f| {
            Ok(Triangle {
                v0: vertex(f[0])?,
                v1: vertex(f[1])?,
                v2: vertex(f[2])?,
            })
        })
        .collect()
}

fn ray_of(ray: &AnchorRay) -> Ray {
    Ray::new(Vec3A::from(ray.origin), Vec3A::from(ray.dir), 0.0, ray.tfar)
}

impl Tracer for ObvhsTracer {
    const NAME: &'static str = "obvhs";

    fn build(mesh: &AnchorMesh) -> Result<Self, String> {
        let triangles = triangles_of(mesh)?;
        let bvh = build_cwbvh_from_tris(
            &triangles,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| triangles[i as usize])
            .collect();
        Ok(ObvhsTracer { bvh, triangles })
    }

    fn closest(&self, ray: &AnchorRay) -> i32 {
        let mut hit = obvhs::ray::RayHit::none();
        let found = self.bvh.ray_traverse(ray_of(ray), &mut hit, |r, id| {
            self.triangles[id].intersect(r)
        });
        if found {
            self.bvh.primitive_indices[hit.primitive_id as usize] as i32
        } else {
            -1
        }
    }

    fn occluded(&self, ray: &AnchorRay) -> bool {
        !self
            .bvh
            .ray_traverse_miss(ray_of(ray), |r, id| self.triangles[id].intersect(r))
    }

    fn cost(&self, ray: &AnchorRay, query: Query) -> Option<WalkCost> {
        // The crate's own traversal macro, with counts added to its node and triangle tests.
        // Each node it visits is an interior node: its (up to eight) children's boxes are
        // tested at once, the triangles of its leaf children are listed in it.
        let mut traverse_ray = ray_of(ray);
        let mut state = self.bvh.new_traversal(traverse_ray.direction);
        let mut node;
        let mut cost = WalkCost::default();
        'walk: {
            obvhs::traverse!(
                self.bvh,
                node,
                state,
                {
                    cost.nodes += 1;
                    node.intersect_ray(&traverse_ray, state.oct_inv4)
                },
                {
                    cost.triangles += 1;
                    let t = self.triangles[state.primitive_id as usize].intersect(&traverse_ray);
                    if t < traverse_ray.tmax {
                        traverse_ray.tmax = t;
                        if query == Query::Occluded {
                            break 'walk; // out of the whole walk, as `ray_traverse_miss` does
                        }
                    }
                }
            );
        }
        Some(cost)
    }
}
