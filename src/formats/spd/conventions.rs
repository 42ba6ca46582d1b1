//! What every SPD database has in common: the "UNC sky blue" background, a 45° view at
//! 512×512, point lights without a colour, materials given by their highlight's half angle, and
//! rotations computed the way SPD computes them, so that generated numbers round as SPD's do.

use glam::{DMat3, DVec3};

use crate::formats::nff::{Fill, Item, NffDocument, NffLight, View};

/// The background of every database.
const SKY_BLUE: DVec3 = DVec3::new(0.078, 0.361, 0.753);

/// A document with SPD's background, a 45° view from `from` towards `at` rendered at 512×512,
/// and white lights at `lights`.
pub(super) fn document(
    from: [f64; 3],
    at: [f64; 3],
    up: [f64; 3],
    hither: f64,
    lights: &[[f64; 3]],
) -> NffDocument {
    NffDocument {
        background: Some(SKY_BLUE),
        view: Some(View {
            from: DVec3::from_array(from),
            at: DVec3::from_array(at),
            up: DVec3::from_array(up),
            angle: 45.0,
            hither,
            resolution: [512, 512],
        }),
        lights: lights
            .iter()
            .map(|&p| NffLight {
                position: DVec3::from_array(p),
                color: None,
            })
            .collect(),
        items: Vec::new(),
    }
}

/// The properties of an SPD material, as SPD's generators state them.
#[derive(Clone, Copy, Debug)]
pub(super) struct Surface {
    pub color: [f64; 3],
    pub kd: f64,
    pub ks: f64,
    /// Angle in degrees at which the highlight falls to half its strength (0: none).
    pub highlight_half_angle: f64,
    pub transmittance: f64,
    pub ior: f64,
}

impl Surface {
    /// A matte surface of `color`, diffuse weight `kd`.
    pub fn matte(color: [f64; 3], kd: f64) -> Surface {
        Surface {
            color,
            kd,
            ks: 0.0,
            highlight_half_angle: 0.0,
            transmittance: 0.0,
            ior: 0.0,
        }
    }

    /// The `f` item for this surface.
    pub fn fill(self) -> Item {
        Item::Fill(Fill {
            color: DVec3::from_array(self.color),
            kd: self.kd,
            ks: self.ks,
            shine: Fill::shine_from_half_angle(self.highlight_half_angle),
            transmittance: self.transmittance,
            ior: self.ior,
        })
    }
}

/// The rotation by `angle` radians about `axis` (normalised here), its terms computed in SPD's
/// order.
pub(super) fn axis_rotation(axis: DVec3, angle: f64) -> DMat3 {
    let [x, y, z] = (axis / axis.length()).to_array();
    let (sin, cos) = angle.sin_cos();
    let one_minus_cos = 1.0 - cos;
    DMat3::from_cols(
        DVec3::new(
            x * x + (1.0 - x * x) * cos,
            x * y * one_minus_cos + z * sin,
            x * z * one_minus_cos - y * sin,
        ),
        DVec3::new(
            x * y * one_minus_cos - z * sin,
            y * y + (1.0 - y * y) * cos,
            y * z * one_minus_cos + x * sin,
        ),
        DVec3::new(
            x * z * one_minus_cos + y * sin,
            y * z * one_minus_cos - x * sin,
            z * z + (1.0 - z * z) * cos,
        ),
    )
}
