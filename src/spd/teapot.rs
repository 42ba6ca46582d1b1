//! teapot: the Utah teapot, each of its 32 Bézier patches cut into SF×SF quadrilaterals and
//! those into two smooth-shaded triangles (`pp`), on an SF×SF checkerboard, lit by two lights.
//! Triangles that collapse at the cusps of the lid and the bottom are left out, so there are
//! 64·SF² − 8·SF of them. Everything reflects.

use glam::DVec3;

use super::conventions::{Surface, document};
use super::teapot_patches::{CONTROL_POINTS, PATCHES};
use crate::nff::{Item, NffDocument, PatchVertex};

/// How close to the Z axis a vertex must be to sit on a cusp.
const CUSP_TOLERANCE: f64 = 0.0001;

pub(super) fn teapot(size: u32) -> NffDocument {
    let mut doc = document(
        [4.86, 7.2, 5.4],
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        1.0,
        &[[-3.1, 9.8, 12.1], [11.3, 5.1, 8.8]],
    );
    checkerboard(&mut doc.items, size);
    let pot = Surface {
        color: [1.0, 0.5, 0.1],
        kd: 0.75,
        ks: 0.25,
        highlight_half_angle: 37.0,
        transmittance: 0.0,
        ior: 0.0,
    };
    doc.items.push(pot.fill());
    for patch in &PATCHES {
        tessellate(&mut doc.items, patch, size);
    }
    doc
}

/// An 8×8 board centred on the origin, in `size`×`size` squares: first the white ones, then
/// the grey ones.
fn checkerboard(items: &mut Vec<Item>, size: u32) {
    for (color, parity) in [(1.0, 1), (0.5, 0)] {
        let checks = Surface {
            color: [color; 3],
            kd: 0.5,
            ks: 0.5,
            highlight_half_angle: 30.0,
            transmittance: 0.0,
            ior: 0.0,
        };
        items.push(checks.fill());
        let at = |i: u32| 4.0 * (2.0 * f64::from(i) / f64::from(size) - 1.0);
        for s in 0..size {
            for t in (0..size).filter(|t| (s + t) % 2 == parity) {
                items.push(Item::Polygon(vec![
                    DVec3::new(at(s), at(t), 0.0),
                    DVec3::new(at(s + 1), at(t), 0.0),
                    DVec3::new(at(s + 1), at(t + 1), 0.0),
                    DVec3::new(at(s), at(t + 1), 0.0),
                ]));
            }
        }
    }
}

/// Cuts one patch into `size`×`size` quadrilaterals of two triangles each.
fn tessellate(items: &mut Vec<Item>, patch: &[u16; 16], size: u32) {
    let control = patch.map(|i| DVec3::from_array(CONTROL_POINTS[usize::from(i)]));
    // The quadrilateral's corners in (s, t) steps, and the two triangles made of them.
    const CORNERS: [(u32, u32); 4] = [(0, 0), (0, 1), (1, 1), (1, 0)];
    const TRIANGLES: [[usize; 3]; 2] = [[0, 1, 2], [2, 3, 0]];
    let n = f64::from(size);
    for s in 0..size {
        for t in 0..size {
            for triangle in TRIANGLES {
                let mut vertices = triangle.map(|corner| {
                    let (ds, dt) = CORNERS[corner];
                    point(&control, f64::from(s + ds) / n, f64::from(t + dt) / n)
                });
                if fix_cusp(&mut vertices) {
                    items.push(Item::Patch(vertices.to_vec()));
                }
            }
        }
    }
}

/// The point of the patch at parameters (s, t), with its unit normal.
fn point(control: &[DVec3; 16], s: f64, t: f64) -> PatchVertex {
    let (bs, dbs) = (bernstein(s), bernstein_derivative(s));
    let (bt, dbt) = (bernstein(t), bernstein_derivative(t));
    let (mut position, mut along_s, mut along_t) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for row in 0..4 {
        for column in 0..4 {
            let p = control[row * 4 + column];
            position += bs[row] * bt[column] * p;
            along_s += dbs[row] * bt[column] * p;
            along_t += bs[row] * dbt[column] * p;
        }
    }
    PatchVertex {
        position,
        normal: along_t.cross(along_s).normalize_or_zero(),
    }
}

/// The cubic Bernstein polynomials at `u`.
fn bernstein(u: f64) -> [f64; 4] {
    let v = 1.0 - u;
    [v * v * v, 3.0 * u * v * v, 3.0 * u * u * v, u * u * u]
}

/// Their derivatives at `u`.
fn bernstein_derivative(u: f64) -> [f64; 4] {
    let v = 1.0 - u;
    [
        -3.0 * v * v,
        3.0 * v * v - 6.0 * u * v,
        6.0 * u * v - 3.0 * u * u,
        3.0 * u * u,
    ]
}

/// At the cusps on the Z axis (the top of the lid, the middle of the bottom) the patches'
/// normals vanish. A triangle with two vertices there has collapsed: `false`, leave it out.
/// A triangle with one gets the axis as that vertex's normal, up at the lid, down at the bottom.
fn fix_cusp(vertices: &mut [PatchVertex; 3]) -> bool {
    let on_axis = vertices
        .map(|v| v.position.x.abs() <= CUSP_TOLERANCE && v.position.y.abs() <= CUSP_TOLERANCE);
    if on_axis.iter().filter(|&&on| on).count() > 1 {
        return false;
    }
    if let Some(cusp) = on_axis.iter().position(|&on| on) {
        let cusp = &mut vertices[cusp];
        // The lid's cusp is above the middle of the pot, the bottom's below it.
        cusp.normal = if cusp.position.z > 1.5 {
            DVec3::Z
        } else {
            -DVec3::Z
        };
    }
    true
}
