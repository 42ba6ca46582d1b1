//! raylab's own BVH (four-wide, SAH) and watertight triangle test, through the library's public
//! API: a [`Mesh`] added to a [`Geometry`], [`Bvh::build`], [`Bvh::closest_hit`], [`Bvh::any_hit`].

use std::ops::ControlFlow;

use glam::Vec3;
use raylab::bvh::Bvh;
use raylab::mesh::Mesh;
use raylab::primitive::Geometry;
use raylab::ray::Ray;

use crate::anchor::{AnchorMesh, AnchorRay, Query};
use crate::tracer::Tracer;

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
        let hit = self
            .bvh
            .closest_hit(&self.geometry, &ray_of(ray), 0.0, ray.tfar);
        match hit.map(|h| h.prim.kind()) {
            // Degenerate faces make no triangle: the triangle knows its face.
            Some(Err(t)) => self.geometry.triangles[t].face as i32,
            _ => -1,
        }
    }

    fn occluded(&self, ray: &AnchorRay) -> bool {
        let mut blocked = false;
        self.bvh
            .any_hit(&self.geometry, &ray_of(ray), 0.0, ray.tfar, |_| {
                blocked = true;
                ControlFlow::Break(())
            });
        blocked
    }

    fn nodes_visited(&self, _ray: &AnchorRay, _query: Query) -> Option<u32> {
        // raylab's walk counts nothing yet; issue 6's traversal cost counter will tell.
        None
    }
}
