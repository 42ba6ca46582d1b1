//! teapot: the Utah teapot, each of its 32 Bézier patches cut into SF×SF quadrilaterals and
//! those into two smooth-shaded triangles (`pp`), on an SF×SF checkerboard, lit by two lights.
//! Triangles that collapse at the cusps of the lid and the bottom are left out, so there are
//! 64·SF² − 8·SF of them. Everything reflects.

use glam::DVec3;

use super::conventions::{Surface, document};
use super::teapot_patches::{CONTROL_POINTS, PATCHES};
use crate::formats::nff::{Item, NffDocument, PatchVertex};

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
    doc.items.extend(utah_teapot(size));
    doc
}

/// The pot alone, in SPD's coordinates (Z up, standing on z = 0): each of its patches cut into
/// `size`×`size` quadrilaterals of two smooth-shaded triangles (`pp` items). The SDL reader's
/// `teapot` is made of these.
pub(crate) fn utah_teapot(size: u32) -> Vec<Item> {
    let mut items = Vec::new();
    for patch in &PATCHES {
        tessellate(&mut items, patch, size);
    }
    items
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
    let coefficients = power_coefficients(patch);
    // The quadrilateral's corners in (s, t) steps, and the two triangles made of them.
    const CORNERS: [(u32, u32); 4] = [(0, 0), (0, 1), (1, 1), (1, 0)];
    const TRIANGLES: [[usize; 3]; 2] = [[0, 1, 2], [2, 3, 0]];
    let n = f64::from(size);
    for s in 0..size {
        for t in 0..size {
            for triangle in TRIANGLES {
                let mut vertices = triangle.map(|corner| {
                    let (ds, dt) = CORNERS[corner];
                    point(&coefficients, f64::from(s + ds) / n, f64::from(t + dt) / n)
                });
                if fix_cusp(&mut vertices) {
                    items.push(Item::Patch(vertices.to_vec()));
                }
            }
        }
    }
}

type Matrix = [[f64; 4]; 4];

/// The cubic Bézier basis: a row of powers `[u³ u² u 1]` times it gives the four Bernstein
/// weights.
const BEZIER: Matrix = [
    [-1.0, 3.0, -3.0, 1.0],
    [3.0, -6.0, 3.0, 0.0],
    [-3.0, 3.0, 0.0, 0.0],
    [1.0, 0.0, 0.0, 0.0],
];

/// For x, y and z, the matrix `B·G·Bᵀ` of the patch's control points `G` in the Bézier basis
/// `B`: the coordinate at (s, t) is `[s³ s² s 1]·B·G·Bᵀ·[t³ t² t 1]ᵀ`. Evaluated this way,
/// as SPD does, the points round to SPD's own digits.
fn power_coefficients(patch: &[u16; 16]) -> [Matrix; 3] {
    let transposed: Matrix = std::array::from_fn(|i| std::array::from_fn(|j| BEZIER[j][i]));
    std::array::from_fn(|axis| {
        let control: Matrix = std::array::from_fn(|row| {
            std::array::from_fn(|column| CONTROL_POINTS[usize::from(patch[row * 4 + column])][axis])
        });
        multiply(&multiply(&BEZIER, &control), &transposed)
    })
}

fn multiply(a: &Matrix, b: &Matrix) -> Matrix {
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] + a[i][3] * b[3][j]
        })
    })
}

/// `[u³ u² u 1]` and its derivative `[3u² 2u 1 0]`.
fn powers(u: f64) -> ([f64; 4], [f64; 4]) {
    ([u * u * u, u * u, u, 1.0], [u * u * 3.0, u * 2.0, 1.0, 0.0])
}

/// `row · matrix · column`.
fn sandwich(row: &[f64; 4], matrix: &Matrix, column: &[f64; 4]) -> f64 {
    let r: [f64; 4] = std::array::from_fn(|j| {
        row[0] * matrix[0][j]
            + row[1] * matrix[1][j]
            + row[2] * matrix[2][j]
            + row[3] * matrix[3][j]
    });
    r[0] * column[0] + r[1] * column[1] + r[2] * column[2] + r[3] * column[3]
}

/// The point of the patch at parameters (s, t), with its unit normal (zero at a cusp, where
/// the patch has none).
fn point(coefficients: &[Matrix; 3], s: f64, t: f64) -> PatchVertex {
    let (s_powers, s_slopes) = powers(s);
    let (t_powers, t_slopes) = powers(t);
    let axis = |row: &[f64; 4], column: &[f64; 4]| {
        DVec3::from_array(std::array::from_fn(|i| {
            sandwich(row, &coefficients[i], column)
        }))
    };
    let along_s = axis(&s_slopes, &t_powers);
    let along_t = axis(&s_powers, &t_slopes);
    let normal = along_t.cross(along_s);
    let length = normal.length();
    PatchVertex {
        position: axis(&s_powers, &t_powers),
        normal: if length > 0.0 {
            normal / length
        } else {
            normal
        },
    }
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
        cusp.normal = DVec3::new(0.0, 0.0, if cusp.position.z > 1.5 { 1.0 } else { -1.0 });
    }
    true
}
