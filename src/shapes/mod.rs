//! The shapes objects are made of, each in its own object space: a shape answers where a ray
//! first meets it, what the surface looks like there (normal and texture coordinates), and what
//! box bounds it. Placing a shape in the world is the job of [`crate::primitive`].

mod csg;
mod cuboid;
mod cylinder_pack;
mod edge_bands;
mod ellipsoid;
mod pack;
mod paraboloid;
mod plane;
mod polygon;
mod polygon_pack;
pub(crate) mod quadratic;
mod sphere;
mod sphere_pack;
mod tapered_cylinder;
#[cfg(test)]
mod test_support;
mod torus;
mod triangle;
mod triangle_pack;

pub use csg::{
    Csg, CsgOperation, Leaf, MAX_DEPTH as MAX_CSG_DEPTH, MAX_OPERANDS as MAX_CSG_OPERANDS, Operand,
    PART_BITS as CSG_PART_BITS, Step as CsgStep,
};
pub use cuboid::Cuboid;
pub use cylinder_pack::CylinderPack;
pub use ellipsoid::Ellipsoid;
pub use pack::{LaneHits, ObjectPack, PACK_SIZE};
pub use paraboloid::Paraboloid;
pub use plane::Plane;
pub use polygon::Polygon;
pub use polygon_pack::PolygonPack;
pub use quadratic::solve_quadratic;
pub use sphere::Sphere;
pub use sphere_pack::SpherePack;
pub use tapered_cylinder::TaperedCylinder;
pub use torus::Torus;
pub use triangle::{ShearedRay, Triangle, TriangleHit};
pub use triangle_pack::{PackHits, TrianglePack};

use arrayvec::ArrayVec;
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

/// Where a ray crosses the surface of a closed solid, along the whole line, in increasing `t`:
/// entry, exit, entry, exit… (at most two spans inside; `t` is infinite where the ray never
/// leaves a half-space). The CSG operands are traced by these.
pub type Crossings = ArrayVec<ShapeHit, 4>;

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
#[derive(Clone, Debug, PartialEq, strum::EnumDiscriminants)]
#[strum_discriminants(
    name(ShapeKind),
    doc = "The kinds of shape, one per variant of `Shape`: the GPU's records name them by their numbers (`kind as u32`).",
    derive(Hash, strum::EnumIter)
)]
pub enum Shape {
    Sphere(Sphere),
    Plane(Plane),
    Polygon(Polygon),
    Cuboid(Cuboid),
    TaperedCylinder(TaperedCylinder),
    Ellipsoid(Ellipsoid),
    Paraboloid(Paraboloid),
    Torus(Torus),
    Csg(Box<Csg>),
}

impl Shape {
    /// The nearest hit with `t` in the open interval `(t_min, t_max)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_min, t_max),
            Shape::Plane(s) => s.intersect(ray, t_min, t_max),
            Shape::Polygon(s) => s.intersect(ray, t_min, t_max),
            Shape::Cuboid(s) => s.intersect(ray, t_min, t_max),
            Shape::TaperedCylinder(s) => s.intersect(ray, t_min, t_max),
            Shape::Ellipsoid(s) => s.intersect(ray, t_min, t_max),
            Shape::Paraboloid(s) => s.intersect(ray, t_min, t_max),
            Shape::Torus(s) => s.intersect(ray, t_min, t_max),
            Shape::Csg(s) => s.intersect(ray, t_min, t_max),
        }
    }

    /// The outward normal (any length) at the object-space point `p` of part `part`: what
    /// [`Self::surface`] gives, without the texture coordinates, which cost trigonometry on
    /// spheres and cylinders.
    pub fn normal(&self, p: Vec3, part: u32) -> Vec3 {
        match self {
            Shape::Sphere(s) => s.normal(p),
            Shape::TaperedCylinder(s) => s.normal(p, part),
            _ => self.surface(p, part).normal,
        }
    }

    /// Normal and texture coordinates at the object-space point `p` of part `part`.
    pub fn surface(&self, p: Vec3, part: u32) -> LocalSurface {
        match self {
            Shape::Sphere(s) => s.surface(p, part),
            Shape::Plane(s) => s.surface(p, part),
            Shape::Polygon(s) => s.surface(p, part),
            Shape::Cuboid(s) => s.surface(p, part),
            Shape::TaperedCylinder(s) => s.surface(p, part),
            Shape::Ellipsoid(s) => s.surface(p, part),
            Shape::Paraboloid(s) => s.surface(p, part),
            Shape::Torus(s) => s.surface(p, part),
            Shape::Csg(s) => s.surface(p, part),
        }
    }

    /// The shape's kind, as the scene file names it.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Plane(_) => "plane",
            Shape::Polygon(_) => "polygon",
            Shape::Cuboid(_) => "cuboid",
            Shape::TaperedCylinder(_) => "tapered cylinder",
            Shape::Ellipsoid(_) => "ellipsoid",
            Shape::Paraboloid(_) => "paraboloid",
            Shape::Torus(_) => "torus",
            Shape::Csg(_) => "csg",
        }
    }

    /// Object-space bounds; `None` for unbounded shapes (planes).
    pub fn bounds(&self) -> Option<Aabb> {
        match self {
            Shape::Sphere(s) => Some(s.bounds()),
            Shape::Plane(_) => None,
            Shape::Polygon(s) => Some(s.bounds()),
            Shape::Cuboid(s) => Some(s.bounds()),
            Shape::TaperedCylinder(s) => Some(s.bounds()),
            Shape::Ellipsoid(s) => Some(s.bounds()),
            Shape::Paraboloid(s) => Some(s.bounds()),
            Shape::Torus(s) => Some(s.bounds()),
            Shape::Csg(s) => s.bounds(),
        }
    }

    /// Whether the shape encloses a volume, so that a ray can be inside it (refraction needs to
    /// know which side is in).
    pub fn is_closed(&self) -> bool {
        match self {
            Shape::Sphere(_)
            | Shape::Cuboid(_)
            | Shape::Ellipsoid(_)
            | Shape::Torus(_)
            | Shape::Csg(_) => true,
            Shape::Plane(_) | Shape::Polygon(_) => false,
            Shape::TaperedCylinder(s) => s.is_capped(),
            Shape::Paraboloid(s) => s.is_capped(),
        }
    }

    /// Whether the shape can be an operand of a CSG node: a closed solid, or a plane, which
    /// stands for the half-space behind it.
    pub fn is_solid(&self) -> bool {
        self.is_closed() || matches!(self, Shape::Plane(_))
    }

    /// Whether the shape is a convex solid: a line that goes in crosses its surface exactly
    /// twice, entering and leaving.
    pub fn is_convex(&self) -> bool {
        match self {
            Shape::Sphere(_) | Shape::Cuboid(_) | Shape::Ellipsoid(_) => true,
            Shape::TaperedCylinder(s) => s.is_capped(),
            Shape::Paraboloid(s) => s.is_capped(),
            Shape::Plane(_) | Shape::Polygon(_) | Shape::Torus(_) | Shape::Csg(_) => false,
        }
    }

    /// Where the ray crosses the solid along the whole line (see [`Crossings`]), for a shape
    /// that is an operand of a CSG node ([`Self::is_solid`], not a node itself: a node's
    /// operands are its leaves).
    pub fn crossings(&self, ray: &Ray) -> Crossings {
        match self {
            Shape::Plane(s) => s.crossings(ray),
            Shape::Torus(s) => s
                .crossings(ray)
                .into_iter()
                .map(|t| ShapeHit { t, part: 0 })
                .collect(),
            Shape::Sphere(_)
            | Shape::Cuboid(_)
            | Shape::Ellipsoid(_)
            | Shape::TaperedCylinder(_)
            | Shape::Paraboloid(_) => {
                debug_assert!(self.is_convex(), "an open surface is not a CSG operand");
                self.convex_crossings(ray)
            }
            Shape::Polygon(_) | Shape::Csg(_) => {
                unreachable!("`Csg::new` takes neither polygons nor nodes as leaves")
            }
        }
    }

    /// [`Self::crossings`] of a convex solid: the line enters at the first hit on the whole
    /// line and leaves at the next one. A line that only touches the surface does not go in.
    fn convex_crossings(&self, ray: &Ray) -> Crossings {
        let mut crossings = Crossings::new();
        let whole_line = (f32::NEG_INFINITY, f32::INFINITY);
        if let Some(enter) = self.intersect(ray, whole_line.0, whole_line.1)
            && let Some(exit) = self.intersect(ray, enter.t, whole_line.1)
        {
            crossings.push(enter);
            crossings.push(exit);
        }
        crossings
    }
}
