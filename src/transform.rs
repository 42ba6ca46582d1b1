//! Affine transforms of objects: translate, rotate about any axis and scale, composed in file
//! order, with the inverse and the inverse transpose (for normals) kept alongside.

use glam::{Affine3A, Mat3A, Mat4, Vec3};

use crate::aabb::Aabb;
use crate::ray::Ray;

/// One step of an object's transform, as written in a scene file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TransformStep {
    Translate(Vec3),
    /// Rotation by `degrees` about `axis` (right-handed).
    Rotate {
        axis: Vec3,
        degrees: f32,
    },
    Scale(Vec3),
}

/// The map from an object's own space to the world, with its inverse and normal matrix.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub world_from_object: Affine3A,
    pub object_from_world: Affine3A,
    /// Inverse transpose of the linear part: maps object-space normals to world space.
    pub normal_to_world: Mat3A,
}

/// Why a transform cannot be used.
#[derive(Clone, Debug, PartialEq)]
pub enum TransformError {
    ZeroRotationAxis,
    /// A scale factor of zero (or not finite) squashes the object flat.
    DegenerateScale(Vec3),
}

impl std::fmt::Display for TransformError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TransformError::ZeroRotationAxis => write!(f, "rotation axis must not be zero"),
            TransformError::DegenerateScale(s) => {
                write!(f, "scale factors must be finite and non-zero, got {s}")
            }
        }
    }
}

impl Transform {
    /// The transform that leaves everything where it stands.
    pub const IDENTITY: Transform = Transform {
        world_from_object: Affine3A::IDENTITY,
        object_from_world: Affine3A::IDENTITY,
        normal_to_world: Mat3A::IDENTITY,
    };

    /// The transform that maps object space to the world by `world_from_object`.
    pub(crate) fn from_affine(world_from_object: Affine3A) -> Self {
        let object_from_world = world_from_object.inverse();
        Transform {
            world_from_object,
            object_from_world,
            normal_to_world: object_from_world.matrix3.transpose(),
        }
    }

    /// The transform of a 4×4 matrix (a model file's node matrix; its last row is taken to be
    /// `0 0 0 1`), or `None` when it is not finite or squashes space flat (no inverse).
    pub fn from_matrix(world_from_object: Mat4) -> Option<Self> {
        let affine = Affine3A::from_mat4(world_from_object);
        let det = affine.matrix3.determinant();
        (affine.is_finite() && det.is_normal()).then(|| Transform::from_affine(affine))
    }

    /// Composes the steps in file order: the first step is applied to the object first.
    pub fn from_steps(steps: &[TransformStep]) -> Result<Self, TransformError> {
        let mut m = Affine3A::IDENTITY;
        for step in steps {
            let s = match *step {
                TransformStep::Translate(t) => Affine3A::from_translation(t),
                TransformStep::Rotate { axis, degrees } => {
                    let axis = axis
                        .try_normalize()
                        .ok_or(TransformError::ZeroRotationAxis)?;
                    Affine3A::from_axis_angle(axis, degrees.to_radians())
                }
                TransformStep::Scale(s) => {
                    if !s.is_finite() || s.cmpeq(Vec3::ZERO).any() {
                        return Err(TransformError::DegenerateScale(s));
                    }
                    Affine3A::from_scale(s)
                }
            };
            m = s * m;
        }
        Ok(Transform::from_affine(m))
    }

    /// The transform that applies `self` first and then `outer` (an object placed inside a
    /// group that is placed in turn).
    pub fn then(&self, outer: &Transform) -> Transform {
        Transform::from_affine(outer.world_from_object * self.world_from_object)
    }

    /// The ray in object space. The direction is not renormalised, so `t` means the same point in
    /// both spaces.
    #[inline]
    pub fn ray_to_object(&self, ray: &Ray) -> Ray {
        Ray::new(
            self.object_from_world.transform_point3(ray.origin),
            self.object_from_world.transform_vector3(ray.dir),
        )
    }

    pub fn point_to_world(&self, p: Vec3) -> Vec3 {
        self.world_from_object.transform_point3(p)
    }

    /// An object-space normal in world space, unit length.
    pub fn normal_to_world(&self, n: Vec3) -> Vec3 {
        (self.normal_to_world * n).normalize()
    }

    /// How far, in object space, a point may lie from where exact arithmetic puts it when it is
    /// computed in single precision along the ray from the world point `origin` moved into
    /// object space ([`Self::ray_to_object`]), or moved into the world and back, for points
    /// within `extent` of the object's origin (on every axis): a few units in the last place
    /// of the numbers each move adds up. A box grown by it holds every point of what it bounds
    /// as either space computes it.
    pub fn rounding_slack(&self, origin: Vec3, extent: f32) -> f32 {
        /// Units in the last place allowed for: each move is a sum of four products.
        const ULPS: f32 = 16.0;
        // The largest row sum of absolute values: how much the linear part can grow a vector.
        let norm = |m: &Mat3A| {
            let t = m.transpose();
            [t.x_axis, t.y_axis, t.z_axis]
                .map(|row| row.abs().element_sum())
                .into_iter()
                .fold(0.0, f32::max)
        };
        let (inverse, forward) = (&self.object_from_world, &self.world_from_object);
        let inverse_norm = norm(&inverse.matrix3);
        let origin_scale =
            inverse_norm * origin.abs().max_element() + inverse.translation.abs().max_element();
        let world_scale = norm(&forward.matrix3) * extent + forward.translation.abs().max_element();
        ULPS * f32::EPSILON * (origin_scale + inverse_norm * world_scale + extent)
    }

    /// World-space bounds of an object-space box.
    pub fn bounds_to_world(&self, b: &Aabb) -> Aabb {
        Aabb::from_points(b.corners().map(|c| self.point_to_world(c)))
    }
}
