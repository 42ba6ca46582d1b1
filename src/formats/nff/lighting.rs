//! How bright an NFF scene's lights are. NFF leaves it open: a light written without a colour
//! is "non-zero, of no particular value", and there is no ambient light in the file. raylab
//! follows the SPD readme by default and can follow SPD's POV-Ray exporter instead, which also
//! gives each material what NFF leaves out (see `povray`).

use strum::VariantNames;

/// A rule for the intensity of `l` lights without a colour and of the ambient light, given the
/// number `N` of lights. The command line names it in lower case (`readme`).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    strum::Display,
    strum::EnumString,
    strum::EnumIter,
    strum::VariantNames,
)]
#[strum(serialize_all = "lowercase", parse_err_ty = String, parse_err_fn = unknown_lighting)]
pub enum NffLighting {
    /// The SPD readme's suggestion: every light and the ambient light have intensity
    /// √N / (2N) (so N lights together give √N / 2).
    #[default]
    Readme,
    /// SPD's POV-Ray exporter, as POV-Ray 3.7 renders its files: every light 1 / √N, white
    /// ambient light, and the materials as the exporter writes them.
    Povray,
}

impl NffLighting {
    /// Intensity of each of `lights` lights without a colour.
    pub fn light_intensity(self, lights: usize) -> f64 {
        let n = lights.max(1) as f64;
        match self {
            NffLighting::Readme => n.sqrt() / (2.0 * n),
            NffLighting::Povray => 1.0 / n.sqrt(),
        }
    }

    /// Intensity of the ambient light in a scene with `lights` lights (each material's ambient
    /// coefficient scales it).
    pub fn ambient(self, lights: usize) -> f64 {
        match self {
            NffLighting::Readme => self.light_intensity(lights),
            NffLighting::Povray => 1.0,
        }
    }
}

/// Why `name` is no lighting's name.
fn unknown_lighting(name: &str) -> String {
    format!(
        "unknown NFF lighting `{name}`; expected one of {}",
        NffLighting::VARIANTS.join(", ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use strum::IntoEnumIterator;

    #[test]
    fn readme_splits_light_as_the_spd_readme_suggests() {
        let l = NffLighting::Readme;
        assert!((l.light_intensity(1) - 0.5).abs() < 1e-12);
        assert!((l.light_intensity(3) - 3f64.sqrt() / 6.0).abs() < 1e-12);
        assert_eq!(l.ambient(7), l.light_intensity(7));
    }

    #[test]
    fn povray_uses_one_over_root_n_and_white_ambient_light() {
        let l = NffLighting::Povray;
        assert!((l.light_intensity(5) - 0.447214).abs() < 1e-6);
        assert_eq!(l.ambient(5), 1.0);
    }

    #[test]
    fn names_round_trip_and_unknown_names_are_errors() {
        for l in NffLighting::iter() {
            assert_eq!(l.to_string().parse::<NffLighting>(), Ok(l));
        }
        assert_eq!(NffLighting::VARIANTS, ["readme", "povray"]);
        assert_eq!(
            "bright".parse::<NffLighting>(),
            Err("unknown NFF lighting `bright`; expected one of readme, povray".to_string())
        );
    }
}
