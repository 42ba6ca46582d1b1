//! Writing an [`NffDocument`] as NFF text, laid out as the SPD generators lay it out (`b`, the
//! `v` block, the lights, then materials and objects; numbers as C's `%g`), so a generated
//! scene can be compared line by line with SPD's own files.

use std::io::{self, Write};

use glam::DVec3;

use super::document::{Item, NffDocument};
use super::format_g::G;

/// The three numbers of a vector, separated by spaces.
struct Triple(DVec3);

impl std::fmt::Display for Triple {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {} {}", G(self.0.x), G(self.0.y), G(self.0.z))
    }
}

impl NffDocument {
    /// Writes the document as NFF text.
    pub fn write_nff(&self, out: &mut impl Write) -> io::Result<()> {
        if let Some(background) = self.background {
            writeln!(out, "b {}", Triple(background))?;
        }
        if let Some(v) = &self.view {
            writeln!(out, "v")?;
            writeln!(out, "from {}", Triple(v.from))?;
            writeln!(out, "at {}", Triple(v.at))?;
            writeln!(out, "up {}", Triple(v.up))?;
            writeln!(out, "angle {}", G(v.angle))?;
            writeln!(out, "hither {}", G(v.hither))?;
            writeln!(out, "resolution {} {}", v.resolution[0], v.resolution[1])?;
        }
        for light in &self.lights {
            match light.color {
                Some(color) => writeln!(out, "l {} {}", Triple(light.position), Triple(color))?,
                None => writeln!(out, "l {}", Triple(light.position))?,
            }
        }
        for item in &self.items {
            match item {
                Item::Fill(fill) => writeln!(
                    out,
                    "f {} {} {} {} {} {}",
                    Triple(fill.color),
                    G(fill.kd),
                    G(fill.ks),
                    G(fill.shine),
                    G(fill.transmittance),
                    G(fill.ior)
                )?,
                Item::Sphere { center, radius } => {
                    writeln!(out, "s {} {}", Triple(*center), G(*radius))?
                }
                Item::Cone {
                    base,
                    base_radius,
                    apex,
                    apex_radius,
                } => writeln!(
                    out,
                    "c {} {} {} {}",
                    Triple(*base),
                    G(*base_radius),
                    Triple(*apex),
                    G(*apex_radius)
                )?,
                Item::Polygon(vertices) => {
                    writeln!(out, "p {}", vertices.len())?;
                    for v in vertices {
                        writeln!(out, "{}", Triple(*v))?;
                    }
                }
                Item::Patch(vertices) => {
                    writeln!(out, "pp {}", vertices.len())?;
                    for v in vertices {
                        writeln!(out, "{} {}", Triple(v.position), Triple(v.normal))?;
                    }
                }
            }
        }
        Ok(())
    }

    /// The document as NFF text.
    pub fn to_nff_string(&self) -> String {
        let mut bytes = Vec::new();
        self.write_nff(&mut bytes)
            .expect("writing into memory cannot fail");
        String::from_utf8(bytes).expect("NFF text is ASCII")
    }
}
