//! The SDL shapes in their own object space, as the book draws them: the unit sphere, the cube
//! from −1 to 1, tapered cylinders along +z from z = 0 to 1, the square and the plane z = 0, the
//! GLUT teapot, and the polyhedra the book reads from `.3vn` files beside the program, which
//! raylab generates instead (each the convex hull of its corners, circumradius 1).

use glam::{Affine3A, DVec3, Vec3};

use crate::formats::nff::Item;
use crate::formats::spd::utah_teapot;
use crate::mesh::Mesh;
use crate::shapes::{Cuboid, Plane, Polygon, Shape, Sphere, TaperedCylinder, Torus};

pub(crate) fn sphere() -> Result<Shape, String> {
    Sphere::new(Vec3::ZERO, 1.0).map(Shape::Sphere)
}

pub(crate) fn cube() -> Result<Shape, String> {
    Cuboid::new(Vec3::splat(-1.0), Vec3::ONE).map(Shape::Cuboid)
}

/// Radius 1 at z = 0, `top_radius` at z = 1, closed at both ends.
pub(crate) fn tapered_cylinder(top_radius: f32) -> Result<Shape, String> {
    TaperedCylinder::new(Vec3::ZERO, Vec3::Z, 1.0, top_radius, true).map(Shape::TaperedCylinder)
}

/// How far the hole of a tapered tube reaches past the tube's ends, so that the difference
/// cuts through them cleanly instead of leaving a skin where two caps coincide.
const TUBE_HOLE_OVERHANG: f32 = 0.01;

/// `taperedTube s t`: the tapered cylinder of radii 1 and `s` with a wall `t` thick, as the
/// solid and the hole to take out of it. The hole's radius is `t` less than the solid's at every
/// height; where it would shrink to nothing (a thick wall on a thin end), the hole ends in a
/// point and the tube is closed there.
pub(crate) fn tapered_tube(top_radius: f32, thickness: f32) -> Result<(Shape, Shape), String> {
    if !(thickness > 0.0 && thickness < 1.0) {
        return Err(format!(
            "a tapered tube's wall must be thicker than 0 and thinner than its base radius 1, \
             got {thickness}"
        ));
    }
    let solid = tapered_cylinder(top_radius)?;
    let hole_radius = |z: f32| (1.0 - thickness) + (top_radius - 1.0) * z;
    // Where the hole's radius reaches zero, if it does within the overhang.
    let apex = (1.0 - thickness) / (1.0 - top_radius);
    let (mut low, mut high) = (-TUBE_HOLE_OVERHANG, 1.0 + TUBE_HOLE_OVERHANG);
    if hole_radius(high) < 0.0 {
        high = apex;
    }
    if hole_radius(low) < 0.0 {
        low = apex;
    }
    let (base, top) = (Vec3::Z * low, Vec3::Z * high);
    let hole = TaperedCylinder::new(
        base,
        top,
        hole_radius(low).max(0.0),
        hole_radius(high).max(0.0),
        true,
    )?;
    Ok((solid, Shape::TaperedCylinder(hole)))
}

/// The book's torus (GLUT's `glutSolidTorus(0.2, 1.0, …)`): a ring of radius 1 around the z
/// axis, its tube of radius 0.2. raylab's torus rings the y axis, so it comes with the frame
/// that turns y into z (a quarter turn about x).
pub(crate) fn torus() -> Result<(Shape, Affine3A), String> {
    let torus = Torus::new(Vec3::ZERO, 1.0, 0.2)?;
    let y_to_z = Affine3A::from_rotation_x(std::f32::consts::FRAC_PI_2);
    Ok((Shape::Torus(torus), y_to_z))
}

/// The square −1 ≤ x, y ≤ 1 in the plane z = 0.
pub(crate) fn square() -> Result<Shape, String> {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    Polygon::new(corners.map(|(x, y)| Vec3::new(x, y, 0.0)).to_vec()).map(Shape::Polygon)
}

/// The plane z = 0.
pub(crate) fn plane() -> Result<Shape, String> {
    Ok(Shape::Plane(Plane {
        point: Vec3::ZERO,
        normal: Vec3::Z,
    }))
}

/// How many times each side of a teapot patch is cut.
const TEAPOT_CUTS: u32 = 8;

/// `glutSolidTeapot(1.0)`: the Utah teapot scaled by ½, its middle at the origin and Y up.
pub(crate) fn teapot() -> Mesh {
    // GLUT: rotate 270° about x, scale by ½, move down by 1.5 (in the patches' Z-up space).
    let glut = |p: DVec3| Vec3::new(p.x as f32, p.z as f32 - 1.5, -p.y as f32) * 0.5;
    let turn = |n: DVec3| Vec3::new(n.x as f32, n.z as f32, -n.y as f32);
    let mut mesh = Mesh::default();
    for item in utah_teapot(TEAPOT_CUTS) {
        if let Item::Patch(vertices) = item {
            let first = mesh.positions.len() as u32;
            for v in &vertices {
                mesh.positions.push(glut(v.position));
                mesh.normals.push(turn(v.normal));
            }
            mesh.faces.push([first, first + 1, first + 2]);
        }
    }
    mesh
}

/// The golden ratio.
const PHI: f64 = 1.618_033_988_749_895;

/// The built-in polyhedra by keyword, in the order the book lists them.
pub(crate) const POLYHEDRA: [&str; 6] = [
    "tetrahedron",
    "octahedron",
    "dodecahedron",
    "icosahedron",
    "buckyball",
    "diamond",
];

/// The corners of the polyhedron `name` (one of [`POLYHEDRA`]).
fn corners(name: &str) -> Vec<DVec3> {
    let v = DVec3::new;
    match name {
        "tetrahedron" => vec![
            v(1., 1., 1.),
            v(1., -1., -1.),
            v(-1., 1., -1.),
            v(-1., -1., 1.),
        ],
        "octahedron" => vec![
            v(1., 0., 0.),
            v(-1., 0., 0.),
            v(0., 1., 0.),
            v(0., -1., 0.),
            v(0., 0., 1.),
            v(0., 0., -1.),
        ],
        "dodecahedron" => {
            let mut points = signs(v(1., 1., 1.));
            points.extend(cyclic(v(0., 1. / PHI, PHI)));
            points
        }
        "icosahedron" => cyclic(v(0., 1., PHI)),
        // The truncated icosahedron: the football.
        "buckyball" => [
            v(0., 1., 3. * PHI),
            v(1., 2. + PHI, 2. * PHI),
            v(PHI, 2., 2. * PHI + 1.),
        ]
        .into_iter()
        .flat_map(cyclic)
        .collect(),
        // A gem about the z axis: an octagonal table on top of the crown, a girdle, and the
        // pavilion down to a point.
        "diamond" => {
            let ring = |radius: f64, z: f64, turn: f64| {
                (0..8).map(move |k| {
                    let angle = (f64::from(k) + turn) * std::f64::consts::TAU / 8.0;
                    v(radius * angle.cos(), radius * angle.sin(), z)
                })
            };
            let mut points: Vec<DVec3> = ring(0.55, 0.35, 0.0).chain(ring(1.0, 0.0, 0.5)).collect();
            points.push(v(0., 0., -0.85));
            points
        }
        _ => unreachable!("not a polyhedron: {name}"),
    }
}

/// `p` with every choice of signs of its non-zero coordinates.
fn signs(p: DVec3) -> Vec<DVec3> {
    let mut points = vec![p];
    for axis in 0..3 {
        if p[axis] != 0.0 {
            let flipped: Vec<DVec3> = points
                .iter()
                .map(|q| {
                    let mut q = *q;
                    q[axis] = -q[axis];
                    q
                })
                .collect();
            points.extend(flipped);
        }
    }
    points
}

/// Every choice of signs of `p`, in each of its three cyclic orders.
fn cyclic(p: DVec3) -> Vec<DVec3> {
    [p, DVec3::new(p.y, p.z, p.x), DVec3::new(p.z, p.x, p.y)]
        .into_iter()
        .flat_map(signs)
        .collect()
}

/// The polyhedron `name` (one of [`POLYHEDRA`]), flat-shaded, its corners at distance 1 from
/// the origin (the diamond's girdle at 1).
pub(crate) fn polyhedron(name: &str) -> Mesh {
    let points = corners(name);
    let radius = points.iter().map(|p| p.length()).fold(0.0, f64::max);
    convex_hull(&points.iter().map(|p| *p / radius).collect::<Vec<_>>())
}

/// How far from a face's plane a corner may lie and still be on it.
const ON_PLANE: f64 = 1e-9;

/// The convex hull of a few points, none inside it: every plane through three points with all
/// the others behind it is a face, its points ordered around their middle and cut into a fan.
fn convex_hull(points: &[DVec3]) -> Mesh {
    let mut faces: Vec<(DVec3, f64)> = Vec::new();
    for i in 0..points.len() {
        for j in i + 1..points.len() {
            for k in j + 1..points.len() {
                let normal = (points[j] - points[i]).cross(points[k] - points[i]);
                let Some(normal) = normal.try_normalize() else {
                    continue;
                };
                let offset = normal.dot(points[i]);
                let sides = points.iter().map(|p| normal.dot(*p) - offset);
                let (normal, offset) = if sides.clone().all(|s| s <= ON_PLANE) {
                    (normal, offset)
                } else if sides.clone().all(|s| s >= -ON_PLANE) {
                    (-normal, -offset)
                } else {
                    continue;
                };
                let known = faces
                    .iter()
                    .any(|(n, d)| n.dot(normal) > 1.0 - ON_PLANE && (d - offset).abs() < ON_PLANE);
                if !known {
                    faces.push((normal, offset));
                }
            }
        }
    }
    let mut mesh = Mesh::default();
    for (normal, offset) in faces {
        let mut on_face: Vec<DVec3> = points
            .iter()
            .copied()
            .filter(|p| (normal.dot(*p) - offset).abs() < 1e-6)
            .collect();
        let middle = on_face.iter().sum::<DVec3>() / on_face.len() as f64;
        let across = (on_face[0] - middle).normalize();
        let up = normal.cross(across);
        let angle = |p: &DVec3| (p - middle).dot(up).atan2((p - middle).dot(across));
        on_face.sort_by(|a, b| angle(a).total_cmp(&angle(b)));
        let first = mesh.positions.len() as u32;
        mesh.positions.extend(on_face.iter().map(|p| p.as_vec3()));
        let count = on_face.len() as u32;
        mesh.faces
            .extend((1..count - 1).map(|k| [first, first + k, first + k + 1]));
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (corners, faces as the book's `.3vn` files count them, triangles).
    fn counts(mesh: &Mesh) -> (usize, usize) {
        (mesh.positions.len(), mesh.faces.len())
    }

    #[test]
    fn the_polyhedra_have_their_faces() {
        // Positions are repeated per face: Σ corners of faces; triangles = Σ (corners − 2).
        assert_eq!(counts(&polyhedron("tetrahedron")), (12, 4));
        assert_eq!(counts(&polyhedron("octahedron")), (24, 8));
        assert_eq!(counts(&polyhedron("icosahedron")), (60, 20));
        assert_eq!(counts(&polyhedron("dodecahedron")), (60, 36));
        // 12 pentagons and 20 hexagons.
        assert_eq!(
            counts(&polyhedron("buckyball")),
            (12 * 5 + 20 * 6, 12 * 3 + 20 * 4)
        );
        let diamond = polyhedron("diamond");
        assert!(diamond.validate().is_ok());
    }

    #[test]
    fn polyhedra_face_outwards_and_touch_the_unit_sphere() {
        for name in POLYHEDRA {
            let mesh = polyhedron(name);
            for face in &mesh.faces {
                let [a, b, c] = face.map(|i| mesh.positions[i as usize]);
                let normal = (b - a).cross(c - a);
                assert!(normal.dot(a) > 0.0, "{name}: a face turns inwards");
            }
            let far = mesh
                .positions
                .iter()
                .map(|p| p.length())
                .fold(0.0, f32::max);
            assert!((far - 1.0).abs() < 1e-5, "{name}: {far}");
        }
    }

    #[test]
    fn the_teapot_stands_y_up_around_the_origin() {
        let mesh = teapot();
        let top = mesh.positions.iter().map(|p| p.y).fold(f32::MIN, f32::max);
        let bottom = mesh.positions.iter().map(|p| p.y).fold(f32::MAX, f32::min);
        assert!(
            (bottom + 0.75).abs() < 1e-3 && top > 0.7 && top < 0.9,
            "{bottom} {top}"
        );
    }
}
