//! [`NffDocument`]: what an NFF file says, as plain data in the file's own terms (double
//! precision, materials and objects in file order). The reader fills one from text, the SPD
//! generators build one in code; it is written back as text or built into a [`crate::scene::Scene`].

use glam::DVec3;

/// The contents of an NFF file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NffDocument {
    /// `b`: the colour of rays that hit nothing; black when the file has no `b`.
    pub background: Option<DVec3>,
    /// `v`: the camera and the image size. Every renderable file has one.
    pub view: Option<View>,
    /// `l`: point lights.
    pub lights: Vec<NffLight>,
    /// Materials (`f`) and objects in file order: a material applies to the objects after it.
    pub items: Vec<Item>,
}

/// The `v` block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The eye.
    pub from: DVec3,
    /// The point seen in the centre of the image.
    pub at: DVec3,
    /// Which way is up; need not be perpendicular to `at − from`.
    pub up: DVec3,
    /// Field of view in degrees, edge to edge across the image's width.
    pub angle: f64,
    /// Distance from the eye to the near clipping plane; 0 for none.
    pub hither: f64,
    /// Image width and height in pixels.
    pub resolution: [u32; 2],
}

/// An `l` point light; NFF leaves the intensity of a light without a colour to the renderer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NffLight {
    pub position: DVec3,
    pub color: Option<DVec3>,
}

/// An `f` material: `f R G B Kd Ks Shine T IOR`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fill {
    pub color: DVec3,
    /// Diffuse weight.
    pub kd: f64,
    /// Specular weight: of the Phong highlight and of the reflected ray.
    pub ks: f64,
    /// Phong exponent of the highlight.
    pub shine: f64,
    /// Transmittance: the weight of the refracted ray.
    pub transmittance: f64,
    /// Index of refraction; meaningful only when `transmittance > 0`.
    pub ior: f64,
}

impl Fill {
    /// The material objects get before any `f`: matte white.
    pub const DEFAULT: Fill = Fill {
        color: DVec3::ONE,
        kd: 1.0,
        ks: 0.0,
        shine: 0.0,
        transmittance: 0.0,
        ior: 1.0,
    };

    /// The Phong exponent SPD writes for a highlight that falls to half its strength
    /// `degrees` away from the mirror direction: `ln ½ / ln cos θ`, or 100000 ("no visible
    /// highlight") for 0°.
    pub fn shine_from_half_angle(degrees: f64) -> f64 {
        if degrees <= 0.0 {
            100_000.0
        } else {
            0.5f64.ln() / degrees.to_radians().cos().ln()
        }
    }
}

/// A material or an object, in file order.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Fill(Fill),
    /// `s`: a sphere (a negative radius means only its inside is meant to be seen).
    Sphere {
        center: DVec3,
        radius: f64,
    },
    /// `c`: an open cone or cylinder, the radius changing linearly from base to apex.
    Cone {
        base: DVec3,
        base_radius: f64,
        apex: DVec3,
        apex_radius: f64,
    },
    /// `p`: a planar polygon, convex or concave, counter-clockwise seen from its front.
    Polygon(Vec<DVec3>),
    /// `pp`: a polygonal patch, a polygon with a normal at each vertex for smooth shading.
    Patch(Vec<PatchVertex>),
}

/// A vertex of a `pp` patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchVertex {
    pub position: DVec3,
    pub normal: DVec3,
}

/// How many objects of each kind a document holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PrimitiveCounts {
    pub spheres: usize,
    pub cones: usize,
    pub polygons: usize,
    pub patches: usize,
}

impl PrimitiveCounts {
    pub fn total(&self) -> usize {
        self.spheres + self.cones + self.polygons + self.patches
    }
}

impl std::fmt::Display for PrimitiveCounts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} spheres, {} cones, {} polygons, {} patches",
            self.spheres, self.cones, self.polygons, self.patches
        )
    }
}

impl NffDocument {
    /// Counts the objects by kind.
    pub fn primitive_counts(&self) -> PrimitiveCounts {
        let mut counts = PrimitiveCounts::default();
        for item in &self.items {
            match item {
                Item::Fill(_) => {}
                Item::Sphere { .. } => counts.spheres += 1,
                Item::Cone { .. } => counts.cones += 1,
                Item::Polygon(_) => counts.polygons += 1,
                Item::Patch(_) => counts.patches += 1,
            }
        }
        counts
    }
}
