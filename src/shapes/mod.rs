//! The shapes objects are made of, each in its own object space: a shape answers where a ray
//! first meets it, what the surface looks like there (normal and texture coordinates), and what
//! box bounds it. Placing a shape in the world is the job of [`crate::primitive`].

mod plane;
pub(crate) mod quadratic;
mod sphere;
mod triangle;

pub use plane::Plane;
pub use quadratic::solve_quadratic;
pub use sphere::Sphere;
pub use triangle::{Triangle, TriangleHit};

use glam::{Vec2, Vec3};

use crate::aabb::Aabb;
use crate::ray::Ray;

/// Where a ray meets a shape: the ray parameter `t` and which part of the shape was hit (a face
/// of a box, the side or a cap of a cylinder; 0 for shapes made of one part).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeHit {
    pub t: f32,
    pub part: u32,
}

/// The surface at a hit point, in object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalSurface {
    /// Outward normal (any length; the caller transforms and normalises it).
    pub normal: Vec3,
    /// Texture coordinates, each in [0, 1] for closed shapes; unbounded for planes.
    pub uv: Vec2,
}

/// Every analytic shape raylab knows. Triangle meshes live apart (see [`crate::mesh`]), since
/// they are stored and traversed triangle by triangle.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Plane(Plane),
}

impl Shape {
    /// The nearest hit with `t` in the open interval `(t_min, t_max)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_min, t_max),
            Shape::Plane(s) => s.intersect(ray, t_min, t_max),
        }
    }

    /// Normal and texture coordinates at the object-space point `p` of part `part`.
    pub fn surface(&self, p: Vec3, part: u32) -> LocalSurface {
        match self {
            Shape::Sphere(s) => s.surface(p, part),
            Shape::Plane(s) => s.surface(p, part),
        }
    }

    /// Object-space bounds; `None` for unbounded shapes (planes).
    pub fn bounds(&self) -> Option<Aabb> {
        match self {
            Shape::Sphere(s) => Some(s.bounds()),
            Shape::Plane(_) => None,
        }
    }

    /// Whether the shape encloses a volume, so that a ray can be inside it (refraction needs to
    /// know which side is in).
    pub fn is_closed(&self) -> bool {
        match self {
            Shape::Sphere(_) => true,
            Shape::Plane(_) => false,
        }
    }
}
