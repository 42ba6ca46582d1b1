//! Primitives: what the BVH stores and the tracer hits. An object is an analytic shape placed in
//! the world by a transform, with a material; a triangle belongs to a mesh. [`Geometry`] holds
//! them all and answers, for a hit, the world-space surface point the shading needs. A model
//! placed many times is stored once and placed by instances (`instance`).

use glam::{Vec2, Vec3};

use crate::aabb::Aabb;
use crate::color::Color;
use crate::mesh::{Mesh, NO_VERTEX_COLOR};
use crate::ray::Ray;
use crate::shapes::{LocalSurface, Shape, ShearedRay, Triangle};
use crate::transform::Transform;

pub mod instance;

pub use instance::Instance;

/// An analytic shape in the world.
#[derive(Clone, Debug, PartialEq)]
pub struct Object {
    pub shape: Shape,
    /// `None` when the shape is given directly in world coordinates. Boxed: a transform is
    /// larger than any shape and most objects of large scenes have none, so an object without
    /// one stays small.
    pub transform: Option<Box<Transform>>,
    pub material: u32,
}

impl Object {
    /// The material of the part `part` of the object: a CSG operand's own, or the object's.
    pub fn material_at(&self, part: u32) -> u32 {
        match &self.shape {
            Shape::Csg(csg) => csg.leaf(part).material,
            _ => self.material,
        }
    }
}

/// A reference to one primitive of the BVH: an object, a triangle or an instance, told apart
/// by the top two bits. A hit is always on an object or a triangle: an instance's triangles
/// are numbered after the world's own ([`Geometry::instance_of`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PrimId(pub u32);

/// What a [`PrimId`] names, with its index among its kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrimKind {
    Object(usize),
    Triangle(usize),
    Instance(usize),
}

impl PrimId {
    /// The bit that tells an object's or an instance's id from a triangle's.
    pub const OBJECT_BIT: u32 = 1 << 31;
    /// The bit, beside [`Self::OBJECT_BIT`], that tells an instance's id from an object's.
    pub const INSTANCE_BIT: u32 = 1 << 30;

    pub fn object(index: usize) -> Self {
        PrimId(index as u32 | Self::OBJECT_BIT)
    }

    pub fn triangle(index: usize) -> Self {
        PrimId(index as u32)
    }

    pub fn instance(index: usize) -> Self {
        PrimId(index as u32 | Self::OBJECT_BIT | Self::INSTANCE_BIT)
    }

    /// A key that orders primitives as [`Geometry::prim_ids`] lists them: objects first, in
    /// the order they were added, then instances, then triangles.
    #[inline(always)]
    pub fn scene_order(self) -> u32 {
        self.0 ^ Self::OBJECT_BIT
    }

    #[inline(always)]
    pub fn kind(self) -> PrimKind {
        let index = (self.0 & !(Self::OBJECT_BIT | Self::INSTANCE_BIT)) as usize;
        if self.0 & Self::OBJECT_BIT == 0 {
            PrimKind::Triangle(self.0 as usize)
        } else if self.0 & Self::INSTANCE_BIT == 0 {
            PrimKind::Object(index)
        } else {
            PrimKind::Instance(index)
        }
    }
}

/// The closest hit found so far along a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub prim: PrimId,
    /// Which part of an object was hit (see [`crate::shapes::ShapeHit`]).
    pub part: u32,
    /// Barycentric coordinates of a triangle hit.
    pub bary: Vec2,
}

/// Everything the shading needs to know about the surface at a hit, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub point: Vec3,
    /// The hit point in the object's own space (solid textures follow the object).
    pub object_point: Vec3,
    /// Unit shading normal, pointing out of the surface's front (not necessarily towards the ray).
    pub normal: Vec3,
    /// Unit geometric normal, on the same side as `normal`.
    pub geometric_normal: Vec3,
    /// Texture coordinates; zero where the caller of [`Geometry::surface_with`] did not ask
    /// for them.
    pub uv: Vec2,
    /// The mesh's vertex colour here ([`Mesh::color`]); [`NO_VERTEX_COLOR`] on objects and
    /// meshes without colours.
    pub vertex_color: Color,
    pub material: u32,
}

/// All primitives of a scene.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Geometry {
    pub objects: Vec<Object>,
    /// The world's own meshes, each stored in world space where it stands.
    pub meshes: Vec<Mesh>,
    /// The triangles of the world's own meshes, mesh after mesh, as the face of their mesh
    /// each one is (degenerate faces have no triangle). The vertices stay in the mesh:
    /// [`Self::triangle`].
    pub triangle_faces: Vec<u32>,
    /// Where each mesh's triangles start in `triangle_faces`.
    pub mesh_starts: Vec<u32>,
    /// Models stored once, in their own space: geometries of meshes alone, each placed in the
    /// world by one or more instances ([`instance`]).
    models: Vec<Geometry>,
    /// Each model's bounds in its own space.
    model_bounds: Vec<Aabb>,
    instances: Vec<Instance>,
    /// Where each instance's triangles start, counted from the end of the world's own.
    instance_starts: Vec<u32>,
}

impl Geometry {
    /// Adds a mesh (already in world space) and its triangles.
    pub fn add_mesh(&mut self, mesh: Mesh) {
        self.mesh_starts.push(self.triangle_faces.len() as u32);
        // Reserve first: the iterator skips degenerate faces, so it cannot tell `extend` its
        // length, and growing by doubling would leave up to half the array unused.
        self.triangle_faces.reserve_exact(mesh.faces.len());
        self.triangle_faces
            .extend(mesh.triangles().map(|triangle| triangle.face));
        self.meshes.push(mesh);
    }

    /// Number of primitives the BVH holds: objects, the world's own triangles and instances.
    pub fn len(&self) -> usize {
        self.objects.len() + self.triangle_faces.len() + self.instances.len()
    }

    /// Number of the world's own triangles, all meshes together (instances' not counted:
    /// [`Self::placed_triangle_count`]).
    pub fn triangle_count(&self) -> usize {
        self.triangle_faces.len()
    }

    /// Triangle `t` in world space: one of the world's own, read from its mesh, or one an
    /// instance places ([`Self::instance_of`]), moved into the world.
    pub fn triangle(&self, t: usize) -> Triangle {
        match self.instance_of(t) {
            None => self.own_triangle(t),
            Some((i, local)) => {
                let instance = &self.instances[i];
                instance.place(&self.models[instance.model as usize].own_triangle(local))
            }
        }
    }

    /// The world's own triangle `t`, read from its mesh.
    fn own_triangle(&self, t: usize) -> Triangle {
        let mesh = self.mesh_of(t);
        let face = self.triangle_faces[t];
        let corners = mesh.faces[face as usize].map(|v| mesh.positions[v as usize]);
        Triangle::new(corners, face)
    }

    /// The world's own triangles `ts`, each as [`Self::triangle`] makes it, read stage by
    /// stage: every face first, then every face's vertex indices, then the positions. Reading a
    /// triangle is three dependent loads, each likely a cache miss when the triangles are far
    /// apart in their mesh; a stage's loads do not wait on one another, so the processor
    /// overlaps their misses.
    pub fn triangles<const N: usize>(&self, ts: [usize; N]) -> [Triangle; N] {
        let meshes = ts.map(|t| self.mesh_of(t));
        let faces = ts.map(|t| self.triangle_faces[t]);
        let indices = std::array::from_fn::<_, N, _>(|k| meshes[k].faces[faces[k] as usize]);
        std::array::from_fn(|k| {
            let corners = indices[k].map(|v| meshes[k].positions[v as usize]);
            Triangle::new(corners, faces[k])
        })
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bytes held by the primitives, meshes, models and instances (not counting textures).
    pub fn memory_bytes(&self) -> usize {
        use std::mem::size_of;
        let meshes: usize = self
            .meshes
            .iter()
            .map(|m| {
                m.positions.capacity() * size_of::<Vec3>()
                    + m.normals.capacity() * size_of::<Vec3>()
                    + m.uvs.capacity() * size_of::<Vec2>()
                    + m.colors.capacity() * size_of::<Color>()
                    + m.faces.capacity() * size_of::<[u32; 3]>()
            })
            .sum();
        // A transform lives apart from its object (see `Object::transform`).
        let transforms = self
            .objects
            .iter()
            .filter(|o| o.transform.is_some())
            .count();
        let models: usize = self.models.iter().map(Geometry::memory_bytes).sum();
        self.objects.capacity() * size_of::<Object>()
            + transforms * size_of::<Transform>()
            + self.triangle_faces.capacity() * size_of::<u32>()
            + self.mesh_starts.capacity() * size_of::<u32>()
            + meshes
            + models
            + self.model_bounds.capacity() * size_of::<Aabb>()
            + self.instances.capacity() * size_of::<Instance>()
            + self.instance_starts.capacity() * size_of::<u32>()
    }

    /// Whether `id` names a primitive of this geometry.
    pub fn contains(&self, id: PrimId) -> bool {
        match id.kind() {
            PrimKind::Object(o) => o < self.objects.len(),
            PrimKind::Triangle(t) => t < self.triangle_faces.len() + self.placed_triangle_count(),
            PrimKind::Instance(i) => i < self.instances.len(),
        }
    }

    /// Every primitive's id, as the BVH holds them: objects, the world's own triangles,
    /// instances.
    pub fn prim_ids(&self) -> impl Iterator<Item = PrimId> + '_ {
        (0..self.objects.len())
            .map(PrimId::object)
            .chain((0..self.triangle_faces.len()).map(PrimId::triangle))
            .chain((0..self.instances.len()).map(PrimId::instance))
    }

    /// World-space bounds, `None` for unbounded primitives.
    pub fn bounds(&self, id: PrimId) -> Option<Aabb> {
        match id.kind() {
            PrimKind::Object(o) => {
                let object = &self.objects[o];
                let b = object.shape.bounds()?;
                Some(match &object.transform {
                    Some(t) => t.bounds_to_world(&b),
                    None => b,
                })
            }
            PrimKind::Triangle(t) => Some(self.triangle(t).bounds()),
            PrimKind::Instance(i) => Some(self.instance_bounds(i)),
        }
    }

    /// The bounds of every bounded primitive, planes left out: what a framing camera shows
    /// ([`crate::camera::frame`]). Empty when there is none.
    pub fn finite_bounds(&self) -> Aabb {
        self.prim_ids()
            .filter_map(|id| self.bounds(id))
            .filter(Aabb::is_finite)
            .fold(Aabb::EMPTY, Aabb::union)
    }

    /// The hit of `ray` with primitive `id` in `(t_min, t_max)`, if any.
    pub fn intersect(&self, id: PrimId, ray: &Ray, t_min: f32, t_max: f32) -> Option<Hit> {
        self.intersect_prepared(id, ray, &ShearedRay::new(ray), t_min, t_max)
    }

    /// [`Self::intersect`] with the ray's preparation for triangle tests done once, outside.
    /// An instance's hit is the closest of its triangles', each tested in turn.
    #[inline(always)]
    pub fn intersect_prepared(
        &self,
        id: PrimId,
        ray: &Ray,
        sheared: &ShearedRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<Hit> {
        match id.kind() {
            PrimKind::Triangle(t) => self
                .triangle(t)
                .intersect_sheared(sheared, t_min, t_max)
                .map(|h| Hit {
                    t: h.t,
                    prim: id,
                    part: 0,
                    bary: h.bary,
                }),
            PrimKind::Object(o) => {
                let object = &self.objects[o];
                let h = match &object.transform {
                    Some(tr) => object.shape.intersect(&tr.ray_to_object(ray), t_min, t_max),
                    None => object.shape.intersect(ray, t_min, t_max),
                }?;
                Some(Hit {
                    t: h.t,
                    prim: id,
                    part: h.part,
                    bary: Vec2::ZERO,
                })
            }
            PrimKind::Instance(i) => self.intersect_instance(i, sheared, t_min, t_max),
        }
    }

    /// The object a primitive belongs to, numbered for the inspector and the object-id view:
    /// objects `0..n` in the order they were added, then the world's meshes, then instances.
    pub fn object_id(&self, prim: PrimId) -> u32 {
        let instances_from = self.objects.len() + self.meshes.len();
        let id = match prim.kind() {
            PrimKind::Object(o) => o,
            PrimKind::Triangle(t) => match self.instance_of(t) {
                None => self.objects.len() + self.mesh_index(t),
                Some((i, _)) => instances_from + i,
            },
            PrimKind::Instance(i) => instances_from + i,
        };
        id as u32
    }

    /// What the object `object_id` is, e.g. "sphere #2", "mesh #0" or "instance #7"
    /// (numbered as [`Self::object_id`] numbers them), or "no object #k" for an id out of
    /// range.
    pub fn object_label(&self, object_id: u32) -> String {
        let id = object_id as usize;
        let meshes_from = self.objects.len();
        let instances_from = meshes_from + self.meshes.len();
        match self.objects.get(id) {
            Some(object) => format!("{} #{id}", object.shape.name()),
            None if id < instances_from => format!("mesh #{id}"),
            None if id - instances_from < self.instances.len() => format!("instance #{id}"),
            None => format!("no object #{id}"),
        }
    }

    /// [`Self::object_label`] of the object `prim` belongs to, with the triangle for meshes,
    /// e.g. "mesh #3, triangle 812".
    pub fn prim_label(&self, prim: PrimId) -> String {
        let object = self.object_label(self.object_id(prim));
        match prim.kind() {
            PrimKind::Triangle(t) => format!("{object}, triangle {}", self.triangle(t).face),
            PrimKind::Object(_) | PrimKind::Instance(_) => object,
        }
    }

    /// [`Self::prim_label`] of what `hit` met, with the operand for a CSG object, e.g.
    /// "csg #3 › child 2 (sphere)".
    pub fn hit_label(&self, hit: &Hit) -> String {
        let label = self.prim_label(hit.prim);
        match hit.prim.kind() {
            PrimKind::Object(o) => match &self.objects[o].shape {
                Shape::Csg(csg) => format!("{label} › {}", csg.leaf(hit.part).label),
                _ => label,
            },
            PrimKind::Triangle(_) | PrimKind::Instance(_) => label,
        }
    }

    /// A number for what `hit` met that tells apart the operands of a CSG object (for the
    /// object-id view): [`Self::object_id`] for everything else.
    pub fn part_id(&self, hit: &Hit) -> u32 {
        let object = self.object_id(hit.prim);
        match hit.prim.kind() {
            PrimKind::Object(o) => match &self.objects[o].shape {
                Shape::Csg(csg) => object ^ ((csg.leaf_index(hit.part) as u32 + 1) << 20),
                _ => object,
            },
            PrimKind::Triangle(_) | PrimKind::Instance(_) => object,
        }
    }

    /// The mesh that the world's own triangle `t` belongs to (its index in [`Self::meshes`])
    /// and its face there.
    pub fn triangle_face(&self, t: usize) -> (usize, u32) {
        (self.mesh_index(t), self.triangle_faces[t])
    }

    /// The index of the mesh that the world's own triangle `t` belongs to.
    fn mesh_index(&self, t: usize) -> usize {
        let later = self
            .mesh_starts
            .partition_point(|&start| start as usize <= t);
        later - 1
    }

    /// The mesh that the world's own triangle `t` belongs to.
    fn mesh_of(&self, t: usize) -> &Mesh {
        &self.meshes[self.mesh_index(t)]
    }

    /// The mesh that triangle `t` belongs to, with the instance that places it, if any, and
    /// the triangle's material.
    fn triangle_mesh(&self, t: usize) -> (&Mesh, Option<&Instance>, u32) {
        match self.instance_of(t) {
            None => {
                let mesh = self.mesh_of(t);
                (mesh, None, mesh.material)
            }
            Some((i, local)) => {
                let instance = &self.instances[i];
                let mesh = self.models[instance.model as usize].mesh_of(local);
                (
                    mesh,
                    Some(instance),
                    instance.material.unwrap_or(mesh.material),
                )
            }
        }
    }

    /// The material at `hit`.
    pub fn material(&self, hit: &Hit) -> u32 {
        match hit.prim.kind() {
            PrimKind::Object(o) => self.objects[o].material_at(hit.part),
            PrimKind::Triangle(t) => self.triangle_mesh(t).2,
            PrimKind::Instance(_) => unreachable!("a hit names the instance's triangle"),
        }
    }

    /// The surface at `hit` along `ray`.
    pub fn surface(&self, ray: &Ray, hit: &Hit) -> SurfacePoint {
        self.surface_with(ray, hit, true)
    }

    /// [`Self::surface`], with the texture coordinates only when `uv` asks for them (they are
    /// left at zero otherwise): shading an untextured sphere needs no trigonometry.
    pub fn surface_with(&self, ray: &Ray, hit: &Hit, uv: bool) -> SurfacePoint {
        let point = ray.at(hit.t);
        match hit.prim.kind() {
            PrimKind::Object(o) => {
                let object = &self.objects[o];
                let object_point = match &object.transform {
                    Some(tr) => tr.ray_to_object(ray).at(hit.t),
                    None => point,
                };
                let local = if uv {
                    object.shape.surface(object_point, hit.part)
                } else {
                    LocalSurface {
                        normal: object.shape.normal(object_point, hit.part),
                        uv: Vec2::ZERO,
                    }
                };
                let normal = match &object.transform {
                    Some(tr) => tr.normal_to_world(local.normal),
                    None => local.normal.normalize(),
                };
                SurfacePoint {
                    point,
                    object_point,
                    normal,
                    geometric_normal: normal,
                    uv: local.uv,
                    vertex_color: NO_VERTEX_COLOR,
                    material: object.material_at(hit.part),
                }
            }
            PrimKind::Triangle(t) => {
                let tri = self.triangle(t);
                let (mesh, instance, material) = self.triangle_mesh(t);
                let geometric = tri.normal();
                let placement = instance.map(|i| &i.transform);
                let (normal, uv) = mesh.shading(tri.face, hit.bary, geometric, placement);
                // Vertex normals say which side is out; the winding may disagree.
                let geometric_normal = if geometric.dot(normal) < 0.0 {
                    -geometric
                } else {
                    geometric
                };
                SurfacePoint {
                    point,
                    object_point: point,
                    normal,
                    geometric_normal,
                    uv,
                    vertex_color: mesh.color(tri.face, hit.bary),
                    material,
                }
            }
            PrimKind::Instance(_) => unreachable!("a hit names the instance's triangle"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{Sphere, TaperedCylinder};
    use crate::transform::TransformStep;

    #[test]
    fn a_surface_without_texture_coordinates_is_the_same_surface() {
        let sphere = Shape::Sphere(Sphere::new(Vec3::new(0.0, 0.0, -3.0), 1.0).unwrap());
        let cone = TaperedCylinder::new(Vec3::ZERO, Vec3::Y * 2.0, 1.0, 0.5, true).unwrap();
        let turned = Transform::from_steps(&[
            TransformStep::Rotate {
                axis: Vec3::X,
                degrees: 90.0,
            },
            TransformStep::Translate(Vec3::new(0.3, 0.2, -1.0)),
        ])
        .unwrap();
        let mut geometry = Geometry::default();
        for (shape, transform) in [
            (sphere, None),
            (Shape::TaperedCylinder(cone), None),
            (Shape::TaperedCylinder(cone), Some(turned)),
        ] {
            geometry.objects.push(Object {
                shape,
                transform: transform.map(Box::new),
                material: 0,
            });
        }
        let mut hits = 0;
        for i in 0..64 {
            let x = (i % 8) as f32 / 4.0 - 1.0;
            let y = (i / 8) as f32 / 4.0 - 1.0;
            let ray = Ray::new(Vec3::new(0.0, 0.5, 4.0), Vec3::new(x, y, -4.0));
            for id in geometry.prim_ids() {
                let Some(hit) = geometry.intersect(id, &ray, 1e-4, f32::INFINITY) else {
                    continue;
                };
                hits += 1;
                let full = geometry.surface(&ray, &hit);
                let plain = geometry.surface_with(&ray, &hit, false);
                assert_eq!(
                    plain,
                    SurfacePoint {
                        uv: Vec2::ZERO,
                        ..full
                    }
                );
            }
        }
        assert!(hits > 40, "{hits} hits");
    }
}
