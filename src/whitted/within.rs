//! Which medium a ray runs through as the tracer follows it from surface to surface: the
//! scene's fog between objects, the medium of the material it entered, or clear material (the
//! rule is in [`crate::medium`]'s comment).

use glam::Vec3;

use crate::material::Material;
use crate::medium::{Fog, Medium, Segment};

/// Which medium a ray runs through, as the tracer follows it from surface to surface (the
/// rule of the module's comment).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Within {
    /// Between objects: the scene's fog, if it has one.
    Fog,
    /// Inside an object filled with a medium: that of this material (an index into the scene's
    /// materials; an index keeps the tracer's record of a ray as small as a flag's).
    Medium(u32),
    /// Inside an object of clear material.
    Clear,
}

impl Within {
    /// Where a ray is after passing through a surface of material `material` (of
    /// `materials`): `entering` the object, in its medium; leaving it, back in the fog.
    pub fn after_crossing(materials: &[Material], material: u32, entering: bool) -> Within {
        match materials[material as usize].medium {
            _ if !entering => Within::Fog,
            Some(_) => Within::Medium(material),
            None => Within::Clear,
        }
    }

    /// The medium along the ray from `origin` along the unit vector `dir` up to distance `end`
    /// (the next surface; infinity for none), with the segment of the ray inside it; `None`
    /// where there is no medium. The fog is `fog`, the scene's, and the materials `materials`.
    /// Inside an object the segment
    /// runs from the origin to the next surface; a ray inside an object that finds no further
    /// surface (an object that is not closed) is taken to have left it and is not attenuated.
    pub fn segment(
        &self,
        fog: Option<&Fog>,
        materials: &[Material],
        origin: Vec3,
        dir: Vec3,
        end: f32,
    ) -> Option<(Medium, Segment)> {
        match self {
            Within::Fog => {
                let fog = fog?;
                Some((fog.medium, fog.segment(origin, dir, 0.0, end)?))
            }
            Within::Medium(material) if end.is_finite() => {
                let medium = materials[*material as usize].medium?;
                Some((medium, Segment { start: 0.0, end }))
            }
            Within::Medium(_) | Within::Clear => None,
        }
    }
}
