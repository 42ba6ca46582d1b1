//! How a surface splits a ray: the mirror direction, Snell's law for the transmitted
//! direction, and the weights of the reflected and transmitted rays (with total internal
//! reflection and, optionally, Schlick's Fresnel approximation).

use glam::Vec3;

use crate::color::Color;
use crate::material::Material;

/// How a surface splits what is not absorbed between the reflected and the transmitted ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scattering {
    pub reflect: f32,
    /// The reflected ray's weight as a colour: `kr` tinted by the material's reflection colour,
    /// plus what Fresnel or total internal reflection takes from transmission, untinted. Its
    /// largest component is at most `reflect`.
    pub reflect_color: Color,
    pub transmit: f32,
    /// Direction of the transmitted ray, `None` under total internal reflection.
    pub refracted: Option<Vec3>,
}

/// Mirror direction of `d` about the unit normal `n`.
pub fn reflect(d: Vec3, n: Vec3) -> Vec3 {
    d - 2.0 * d.dot(n) * n
}

/// Direction of a ray `d` (unit) refracted through a surface with unit normal `n` facing the
/// incoming ray, with `eta = n1 / n2` (Snell's law); `None` past the critical angle.
pub fn refract(d: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}

/// The reflected and transmitted weights at a surface. Entering, the ray goes from index 1
/// into `ior`; leaving, the other way round. Under total internal reflection the transmitted
/// share is reflected. With `fresnel`, Schlick's reflectance moves light from transmission to
/// reflection at grazing angles.
pub fn scattering(material: &Material, dir: Vec3, normal: Vec3, entering: bool) -> Scattering {
    let mut reflect = material.reflectivity;
    let mut transmit = material.transparency;
    let tinted = material.reflection_color * material.reflectivity;
    if transmit == 0.0 {
        return Scattering {
            reflect,
            reflect_color: tinted,
            transmit,
            refracted: None,
        };
    }
    let (n1, n2) = if entering {
        (1.0, material.ior)
    } else {
        (material.ior, 1.0)
    };
    let refracted = refract(dir, normal, n1 / n2);
    match refracted {
        None => {
            reflect += transmit;
            transmit = 0.0;
        }
        Some(t) if material.fresnel => {
            // Schlick's formula wants the angle on the optically thinner side.
            let cos = if n1 <= n2 {
                -dir.dot(normal)
            } else {
                -t.dot(normal)
            };
            let fresnel = Material::schlick(cos, n1, n2);
            reflect += transmit * fresnel;
            transmit *= 1.0 - fresnel;
        }
        Some(_) => {}
    }
    Scattering {
        reflect,
        reflect_color: tinted + Color::splat(reflect - material.reflectivity),
        transmit,
        refracted,
    }
}
