//! Instances: a model (meshes in their own space) stored once and placed in the world by a
//! transform as often as the scene uses it: a chessboard's pawns, a forest's trees, a glTF mesh
//! under several nodes. The BVH holds each instance as one primitive over its model's own tree.
//!
//! An instance's triangle is tested in the world: its corners are moved there as they are
//! read, with the same arithmetic that moves a copied mesh's vertices into the world, so a
//! placed triangle is, to the last bit, the triangle a copy would hold, and an image of a
//! hundred instances is the image of a hundred copies. Its triangles are numbered after the
//! world's own, instance after instance, in the order they were placed: the number a hit
//! names, and the order in which ties go to the first.

use super::{Geometry, Hit, PrimId};
use crate::aabb::Aabb;
use crate::shapes::{ShearedRay, Triangle};
use crate::transform::Transform;

/// Most instances a scene may place.
pub const MAX_INSTANCES: usize = 1 << 20;

/// Most triangles the instances of a scene may place, all together: their numbers must fit
/// beside the world's own in a [`PrimId`].
pub const MAX_PLACED_TRIANGLES: usize = 1 << 30;

/// A model placed in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Which of the geometry's models it places ([`Geometry::models`]).
    pub model: u32,
    pub transform: Transform,
    /// The material of all its triangles; `None` keeps each mesh's own.
    pub material: Option<u32>,
}

impl Instance {
    /// A triangle of the model, in the model's space, moved into the world.
    #[inline(always)]
    pub fn place(&self, triangle: &Triangle) -> Triangle {
        let corners = [triangle.p0, triangle.p1, triangle.p2];
        Triangle::new(
            corners.map(|p| self.transform.point_to_world(p)),
            triangle.face,
        )
    }
}

impl Geometry {
    /// Adds a model to be placed by instances: a geometry of meshes alone, in its own space.
    /// Returns its index.
    pub fn add_model(&mut self, model: Geometry) -> u32 {
        assert!(
            model.objects.is_empty() && model.models.is_empty(),
            "a model holds meshes alone"
        );
        self.model_bounds.push(model.finite_bounds());
        self.models.push(model);
        self.models.len() as u32 - 1
    }

    /// The models instances place, each in its own space.
    pub fn models(&self) -> &[Geometry] {
        &self.models
    }

    /// The model `model`'s bounds in its own space.
    pub fn model_bounds(&self, model: usize) -> Aabb {
        self.model_bounds[model]
    }

    /// Places a model in the world, or says which limit that would pass.
    pub fn add_instance(&mut self, instance: Instance) -> Result<(), String> {
        let model = &self.models[instance.model as usize];
        if self.instances.len() >= MAX_INSTANCES {
            return Err(format!(
                "more than {MAX_INSTANCES} instances: raylab places a model at most \
                 {MAX_INSTANCES} times in a scene"
            ));
        }
        let start = self.placed_triangle_count();
        if start + model.triangle_count() > MAX_PLACED_TRIANGLES {
            return Err(format!(
                "the instances would place more than {MAX_PLACED_TRIANGLES} triangles, the most \
                 a scene numbers"
            ));
        }
        self.instance_starts.push(start as u32);
        self.instances.push(instance);
        Ok(())
    }

    /// The instances, in the order they were placed.
    pub fn instances(&self) -> &[Instance] {
        &self.instances
    }

    /// How many triangles the instances place, all together.
    pub fn placed_triangle_count(&self) -> usize {
        match (self.instances.last(), self.instance_starts.last()) {
            (Some(last), Some(&start)) => {
                start as usize + self.models[last.model as usize].triangle_count()
            }
            _ => 0,
        }
    }

    /// For a triangle numbered after the world's own, the instance that places it and the
    /// triangle's number in that instance's model; `None` for the world's own.
    #[inline]
    pub fn instance_of(&self, t: usize) -> Option<(usize, usize)> {
        let placed = t.checked_sub(self.triangle_faces.len())?;
        let i = self
            .instance_starts
            .partition_point(|&start| start as usize <= placed)
            - 1;
        Some((i, placed - self.instance_starts[i] as usize))
    }

    /// The id a hit gives the triangle `local` of instance `i`'s model.
    #[inline(always)]
    pub fn placed_triangle(&self, i: usize, local: u32) -> PrimId {
        let first = self.triangle_faces.len() + self.instance_starts[i] as usize;
        PrimId::triangle(first + local as usize)
    }

    /// Instance `i`'s bounds in the world: its model's box, moved there.
    pub fn instance_bounds(&self, i: usize) -> Aabb {
        let instance = &self.instances[i];
        let bounds = self.model_bounds[instance.model as usize];
        instance.transform.bounds_to_world(&bounds)
    }

    /// The closest hit of the ray `sheared` with instance `i`'s triangles in `(t_min, t_max)`,
    /// each tested in turn (the first in the model wins a tie).
    pub(super) fn intersect_instance(
        &self,
        i: usize,
        sheared: &ShearedRay,
        t_min: f32,
        mut t_max: f32,
    ) -> Option<Hit> {
        let instance = &self.instances[i];
        let model = &self.models[instance.model as usize];
        let mut best = None;
        for local in 0..model.triangle_count() {
            let triangle = instance.place(&model.own_triangle(local));
            if let Some(h) = triangle.intersect_sheared(sheared, t_min, t_max) {
                t_max = h.t;
                best = Some(Hit {
                    t: h.t,
                    prim: self.placed_triangle(i, local as u32),
                    part: 0,
                    bary: h.bary,
                });
            }
        }
        best
    }
}
