//! raylab's own BVH (four-wide, SAH) and watertight triangle test, through the library's public
//! API: a [`Mesh`] added to a [`Geometry`], [`Bvh::build`], [`Bvh::closest_hit_counted`],
//! [`Bvh::any_hit_counted`] (counting nodes and triangles only in the untimed cost run).

use std::ops::ControlFlow;

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::bvh::cost::{BvhCost, TraversalCost};
use raylab::bvh::packet::PACKET_SIZE;
use raylab::mesh::Mesh;
use raylab::primitive::{Geometry, Hit};
use raylab::ray::Ray;

use crate::anchor::{AnchorMesh, AnchorRay, Query};
use crate::tracer::{Tracer, WalkCost};

pub struct RaylabTracer {
    geometry: Geometry,
    bvh: Bvh,
}

fn ray_of(ray: &AnchorRay) -> Ray {
    Ray::new(Vec3::from(ray.origin), Vec3::from(ray.dir))
}

impl Tracer for RaylabTracer {
    const NAME: &'static str = "raylab";

    fn build(mesh: &AnchorMesh) -> Result<Self, String> {
        let mesh = Mesh {
            positions: mesh.positions.iter().map(|&p| Vec3::from(p)).collect(),
            faces: mesh.faces.clone(),
            ..Mesh::default()
        };
        mesh.validate().map_err(|e| e.to_string())?;
        let mut geometry = Geometry::default();
        geometry.add_mesh(mesh);
        let bvh = Bvh::build(&geometry);
        Ok(RaylabTracer { geometry, bvh })
    }

    fn closest(&self, ray: &AnchorRay) -> i32 {
        self.closest_counted(ray, &mut ())
    }

    fn occluded(&self, ray: &AnchorRay) -> bool {
        self.occluded_counted(ray, &mut ())
    }

    fn closest_in_packet(&self, rays: &[AnchorRay], answers: &mut [i32]) {
        let mut hits = [None; PACKET_SIZE];
        for (rays, answers) in rays
            .chunks(PACKET_SIZE)
            .zip(answers.chunks_mut(PACKET_SIZE))
        {
            let packet: [Ray; PACKET_SIZE] =
                std::array::from_fn(|k| ray_of(&rays[k.min(rays.len() - 1)]));
            let hits = &mut hits[..rays.len()];
            // The camera rays share one far limit (infinity).
            let t_max = rays[0].tfar;
            self.bvh
                .closest_hits(&self.geometry, &packet[..rays.len()], 0.0, t_max, hits);
            for (answer, hit) in answers.iter_mut().zip(hits.iter()) {
                *answer = self.triangle_index(*hit);
            }
        }
    }

    fn cost(&self, ray: &AnchorRay, query: Query) -> Option<WalkCost> {
        let mut cost = BvhCost::default();
        match query {
            Query::Closest => {
                self.closest_counted(ray, &mut cost);
            }
            Query::Occluded => {
                self.occluded_counted(ray, &mut cost);
            }
        }
        // The counter hears of interior nodes only (leaves are counted as primitives tested)
        // and not of the root's own box test before the walk.
        Some(WalkCost {
            nodes: cost.nodes as u32,
            triangles: cost.prims as u32,
        })
    }
}

impl RaylabTracer {
    /// [`Tracer::closest`], telling `cost` of the nodes visited and triangles tested; the timed
    /// runs pass `()`, which counts nothing and compiles to the plain walk.
    fn closest_counted(&self, ray: &AnchorRay, cost: &mut impl TraversalCost) -> i32 {
        let hit = self
            .bvh
            .closest_hit_counted(&self.geometry, &ray_of(ray), 0.0, ray.tfar, cost);
        self.triangle_index(hit)
    }

    /// The mesh's index of the triangle `hit` (−1 for none).
    fn triangle_index(&self, hit: Option<Hit>) -> i32 {
        match hit.map(|h| h.prim.kind()) {
            // Degenerate faces make no triangle: the triangle knows its face.
            Some(Err(t)) => self.geometry.triangle_faces[t] as i32,
            _ => -1,
        }
    }

    /// [`Tracer::occluded`], telling `cost` as [`Self::closest_counted`] does.
    fn occluded_counted(&self, ray: &AnchorRay, cost: &mut impl TraversalCost) -> bool {
        let mut blocked = false;
        self.bvh
            .any_hit_counted(&self.geometry, &ray_of(ray), 0.0, ray.tfar, cost, |_| {
                blocked = true;
                ControlFlow::Break(())
            });
        blocked
    }
}
