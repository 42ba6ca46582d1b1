//! An NFF material as SPD's POV-Ray exporter writes it, so that raylab renders an SPD scene as
//! POV-Ray 3.7 renders the exporter's file (`--nff-lights povray`).
//!
//! SPD's generators describe each material by nine numbers: colour, ambient `ka`, diffuse `Kd`,
//! the reflected ray's weight `Ks`, the strength of the Phong highlight, its half-angle (as the
//! exponent `Shine`), the transmitted share `T` and the index of refraction. NFF's `f` line
//! keeps all but `ka` and the highlight's strength; the POV-Ray file keeps them as `ambient`
//! and `phong`. Both are constants of each generator, and across SPD's generators the four
//! numbers `(Kd, Ks, Shine, T)` tell every material apart, so they are looked up
//! ([`GENERATOR_FINISHES`]); any other material gets no ambient and a highlight as strong as
//! `Ks` where it has one.
//!
//! POV-Ray then shades a finish as the Whitted model does, with two differences the material
//! can carry: a filtered (transparent) surface's ambient and diffuse light are weighed by its
//! opacity `1 − T` (its highlight and reflection are not), and the ambient light is white.

use super::document::Fill;
use crate::color::Color;
use crate::material::Material;

/// The exponent SPD writes for "no highlight".
const NO_HIGHLIGHT: f64 = 100_000.0;

/// `[Kd, Ks, Shine, T]`: what tells the generators' materials apart.
type Key = [f64; 4];
/// `(ka, phong)`: what NFF leaves out.
type Finish = (f64, f64);

/// The finish of every material of SPD's generators, as their calls of `lib_output_color` give
/// them: balls (floor, spheres), gears (floor, glass gears, solid gears), jacks, lattice
/// (cylinders; its spheres are balls'), mount (glass, mountain), rings (rings; the wall is a
/// solid gear's), shells, sombrero and teapot (pot, checks).
const GENERATOR_FINISHES: [(Key, Finish); 13] = [
    ([0.8, 0.0, NO_HIGHLIGHT, 0.0], (0.2, 0.0)),
    ([0.5, 0.5, 3.0827, 0.0], (0.0, 0.5)),
    ([0.3, 0.6, 3.0827, 0.0], (0.0, 0.3)),
    ([0.2, 0.0, NO_HIGHLIGHT, 0.8], (0.0, 0.0)),
    ([1.0, 0.0, NO_HIGHLIGHT, 0.0], (0.0, 0.0)),
    ([0.7, 0.7, 11.1434, 0.0], (0.1, 0.4)),
    ([0.99, 0.0, NO_HIGHLIGHT, 0.0], (0.1, 0.0)),
    ([0.1, 0.1, 101.148, 0.9], (0.0, 0.4)),
    ([0.5, 0.2, 3.0827, 0.0], (0.0, 0.3)),
    ([0.8, 0.2, 45.2776, 0.0], (0.0, 0.5)),
    ([0.8, 0.0, 2.60078, 0.0], (0.1, 0.5)),
    ([0.75, 0.25, 3.0827, 0.0], (0.0, 0.25)),
    ([0.5, 0.5, 4.81884, 0.0], (0.0, 0.5)),
];

/// The ambient coefficient and the highlight's strength the exporter gave the material `fill`.
pub fn finish(fill: &Fill) -> Finish {
    let key = [fill.kd, fill.ks, fill.shine, fill.transmittance];
    // The file's numbers have six significant digits.
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-5 * b.abs().max(1.0);
    let known = GENERATOR_FINISHES
        .iter()
        .find(|(known, _)| key.iter().zip(known).all(|(&a, &b)| same(a, b)));
    match known {
        Some((_, finish)) => *finish,
        None if fill.shine < NO_HIGHLIGHT => (0.0, fill.ks),
        None => (0.0, 0.0),
    }
}

/// The material POV-Ray renders for `fill` under white ambient light.
pub fn material(fill: &Fill) -> Material {
    let (ambient, phong) = finish(fill);
    let opacity = (1.0 - fill.transmittance) as f32;
    let transmits = fill.transmittance > 0.0;
    Material {
        color: fill.color.as_vec3(),
        ambient: ambient as f32 * opacity,
        diffuse: fill.kd as f32 * opacity,
        specular: phong as f32,
        specular_color: Color::ONE,
        shininess: fill.shine as f32,
        reflectivity: fill.ks as f32,
        transparency: fill.transmittance as f32,
        ior: if transmits { fill.ior as f32 } else { 1.0 },
        ..Material::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn fill(kd: f64, ks: f64, shine: f64, transmittance: f64) -> Fill {
        Fill {
            color: DVec3::new(1.0, 0.5, 0.25),
            kd,
            ks,
            shine,
            transmittance,
            ior: 1.5,
        }
    }

    #[test]
    fn the_generators_materials_get_their_ambient_and_highlight_back() {
        // The balls' floor, ambient 0.2; a lattice cylinder, 0.1; the mount's glass, whose
        // highlight (0.4) is stronger than its reflection (0.1).
        assert_eq!(finish(&fill(0.8, 0.0, 100_000.0, 0.0)), (0.2, 0.0));
        assert_eq!(finish(&fill(0.99, 0.0, 100_000.0, 0.0)), (0.1, 0.0));
        assert_eq!(finish(&fill(0.1, 0.1, 101.148, 0.9)), (0.0, 0.4));
        // As the file prints them, to six digits.
        assert_eq!(finish(&fill(0.5, 0.2, 3.08269, 0.0)), (0.0, 0.3));
    }

    #[test]
    fn other_materials_get_no_ambient_and_a_highlight_as_strong_as_ks() {
        assert_eq!(finish(&fill(0.6, 0.3, 20.0, 0.0)), (0.0, 0.3));
        assert_eq!(finish(&fill(0.6, 0.3, 100_000.0, 0.0)), (0.0, 0.0));
    }

    #[test]
    fn a_filtered_surface_is_shaded_in_proportion_to_its_opacity() {
        let glass = material(&fill(0.1, 0.1, 101.148, 0.9));
        assert!((glass.diffuse - 0.01).abs() < 1e-6);
        assert_eq!((glass.ambient, glass.specular), (0.0, 0.4));
        assert_eq!(
            (glass.reflectivity, glass.transparency, glass.ior),
            (0.1, 0.9, 1.5)
        );
        let floor = material(&fill(0.8, 0.0, 100_000.0, 0.0));
        assert_eq!(
            (floor.ambient, floor.diffuse, floor.specular),
            (0.2, 0.8, 0.0)
        );
        assert_eq!(floor.ior, 1.0);
    }
}
