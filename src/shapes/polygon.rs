//! Flat polygons with any number of vertices, convex or concave (a gear's face, a letter): a hit
//! on their plane, then a crossing-number test in a 2D projection of the polygon.

use glam::{Vec2, Vec3};

use super::edge_bands::{EdgeBands, ProjectedEdge};
use super::plane::tangent_axes;
use super::{LocalSurface, ShapeHit};
use crate::aabb::Aabb;
use crate::ray::Ray;

/// How far a vertex may lie off the polygon's plane, relative to the polygon's size (the
/// diagonal of its bounding box): enough for coordinates written with a few decimals.
const PLANARITY_TOLERANCE: f32 = 1e-3;

/// Twice the smallest area a polygon may have, relative to its size squared.
const MIN_RELATIVE_DOUBLE_AREA: f32 = 1e-6;

/// A planar polygon, hit from either side. Its front is the side from which the vertices run
/// counter-clockwise.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// Unit normal (Newell's method), pointing to the front.
    pub(crate) normal: Vec3,
    /// `normal · p` for every point `p` of the polygon's plane.
    pub(crate) plane_offset: f32,
    /// The two coordinate axes kept by the projection (the normal's largest axis is dropped, so
    /// the projection squashes the polygon the least).
    pub(crate) kept_axes: [usize; 2],
    /// The polygon's edges in the projection, by band of height.
    pub(crate) edges: EdgeBands,
    /// Bounds of the projected polygon, to reject most misses before walking the edges.
    pub(crate) projected_min: Vec2,
    pub(crate) projected_max: Vec2,
    /// Two unit axes in the plane along which texture coordinates are measured.
    pub(crate) texture_axes: (Vec3, Vec3),
    /// Maps the planar coordinates of a point to `[0, 1]²` over the polygon's extent.
    pub(crate) texture_min: Vec2,
    pub(crate) texture_inv_extent: Vec2,
    bounds: Aabb,
}

impl Polygon {
    pub fn new(vertices: Vec<Vec3>) -> Result<Polygon, String> {
        if vertices.len() < 3 {
            return Err(format!(
                "a polygon needs at least 3 vertices, got {}",
                vertices.len()
            ));
        }
        if let Some((i, v)) = vertices.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(format!("polygon vertex {i} is not finite: {v}"));
        }
        let bounds = Aabb::from_points(vertices.iter().copied());
        let extent = bounds.max - bounds.min;
        let size = extent.length();
        if !size.is_finite() {
            return Err(format!(
                "polygon is too large to work with: its extent is {extent}"
            ));
        }
        // Below this, the squares of its sizes are smaller than single precision holds.
        if extent != Vec3::ZERO && extent.length_squared() < f32::MIN_POSITIVE {
            return Err(format!(
                "polygon is too small to work with: its extent is {extent}"
            ));
        }
        // Newell's method on coordinates scaled to the polygon's size, so nothing overflows.
        let centre = bounds.min + extent * 0.5;
        let scaled = |v: Vec3| (v - centre) / size;
        let double_area_vector = vertices
            .iter()
            .zip(vertices.iter().cycle().skip(1))
            .map(|(&a, &b)| scaled(a).cross(scaled(b)))
            .sum::<Vec3>();
        let normal = match double_area_vector.try_normalize() {
            Some(n) if double_area_vector.length() > MIN_RELATIVE_DOUBLE_AREA => n,
            _ => {
                let points: Vec<Vec3> = vertices.iter().map(|&v| scaled(v)).collect();
                return Err(if spans_an_area(&points) {
                    "polygon is self-intersecting: its edges cross so that the areas of its \
                     parts cancel out"
                } else {
                    "polygon has zero area: its vertices are collinear"
                }
                .to_string());
            }
        };
        // The plane through the vertices' mean offset along the normal, in scaled units.
        let scaled_offset = |v: Vec3| normal.dot(scaled(v));
        let mean_offset =
            vertices.iter().map(|&v| scaled_offset(v)).sum::<f32>() / vertices.len() as f32;
        for (i, &v) in vertices.iter().enumerate() {
            let off_plane = (scaled_offset(v) - mean_offset).abs();
            if off_plane > PLANARITY_TOLERANCE {
                return Err(format!(
                    "polygon vertices do not lie in one plane: vertex {i} is {} off it",
                    off_plane * size
                ));
            }
        }

        let dropped = normal.abs().max_position();
        let kept_axes = [(dropped + 1) % 3, (dropped + 2) % 3];
        let project = |v: Vec3| Vec2::new(v[kept_axes[0]], v[kept_axes[1]]);
        let (projected_min, projected_max) = (project(bounds.min), project(bounds.max));
        let projected: Vec<Vec2> = vertices.iter().map(|&v| project(v)).collect();
        let edges = EdgeBands::new(&projected, projected_min.y, projected_max.y);

        let texture_axes = tangent_axes(normal);
        let planar = |v: Vec3| Vec2::new(v.dot(texture_axes.0), v.dot(texture_axes.1));
        let texture_min = vertices
            .iter()
            .map(|&v| planar(v))
            .fold(Vec2::INFINITY, Vec2::min);
        let texture_max = vertices
            .iter()
            .map(|&v| planar(v))
            .fold(Vec2::NEG_INFINITY, Vec2::max);
        let inv_extent = (texture_max - texture_min).recip();

        Ok(Polygon {
            normal,
            plane_offset: normal.dot(centre) + mean_offset * size,
            kept_axes,
            edges,
            projected_min,
            projected_max,
            texture_axes,
            texture_min,
            texture_inv_extent: Vec2::select(inv_extent.is_finite_mask(), inv_extent, Vec2::ZERO),
            bounds,
        })
    }

    /// The edges that a horizontal line of the projection can cross, when there are few
    /// enough to test them all (see [`EdgeBands::single_band`]).
    pub(super) fn crossable_edges(&self) -> Option<&[ProjectedEdge]> {
        self.edges.single_band()
    }

    /// Unit normal on the polygon's front.
    pub fn normal(&self) -> Vec3 {
        self.normal
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<ShapeHit> {
        let denom = self.normal.dot(ray.dir);
        if denom == 0.0 {
            return None; // parallel to the plane
        }
        let t = (self.plane_offset - self.normal.dot(ray.origin)) / denom;
        if !(t > t_min && t < t_max) {
            return None;
        }
        let p = ray.at(t);
        let q = Vec2::new(p[self.kept_axes[0]], p[self.kept_axes[1]]);
        self.contains_projected(q)
            .then_some(ShapeHit { t, part: 0 })
    }

    /// Whether the projected point `q` is inside the polygon.
    #[inline]
    fn contains_projected(&self, q: Vec2) -> bool {
        if q.cmplt(self.projected_min).any() || q.cmpgt(self.projected_max).any() {
            return false;
        }
        self.edges.contains(q)
    }

    /// Planar mapping: coordinates along two axes in the plane, scaled so that the polygon's
    /// extent along each covers `[0, 1]`.
    pub fn surface(&self, p: Vec3, _part: u32) -> LocalSurface {
        let planar = Vec2::new(p.dot(self.texture_axes.0), p.dot(self.texture_axes.1));
        let uv = (planar - self.texture_min) * self.texture_inv_extent;
        LocalSurface {
            normal: self.normal,
            uv: uv.clamp(Vec2::ZERO, Vec2::ONE),
        }
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }
}

/// Whether the points (scaled to a size of about 1) do not all lie on one line: some triangle of
/// the first point, the point farthest from it and another point has an area.
fn spans_an_area(points: &[Vec3]) -> bool {
    let first = points[0];
    let farthest = points
        .iter()
        .map(|&p| p - first)
        .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        .unwrap_or(Vec3::ZERO);
    points
        .iter()
        .any(|&p| farthest.cross(p - first).length() > MIN_RELATIVE_DOUBLE_AREA)
}

#[cfg(test)]
mod tests {
    use std::f32::consts::TAU;

    use super::*;
    use crate::shapes::Shape;
    use crate::shapes::test_support::{assert_near, hit_in_world};
    use crate::transform::TransformStep;

    fn unit_square_vertices() -> [Vec3; 4] {
        [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
    }

    fn unit_square() -> Polygon {
        Polygon::new(unit_square_vertices().to_vec()).unwrap()
    }

    /// An L in the plane z = 1: the 2×2 square at the origin without its top-right 1×1 quarter.
    fn l_shape() -> Polygon {
        Polygon::new(
            [
                (0.0, 0.0),
                (2.0, 0.0),
                (2.0, 1.0),
                (1.0, 1.0),
                (1.0, 2.0),
                (0.0, 2.0),
            ]
            .map(|(x, y)| Vec3::new(x, y, 1.0))
            .to_vec(),
        )
        .unwrap()
    }

    /// A gear face in the plane y = 0 with 36 teeth of four vertices each (144 in all): radius
    /// 0.8 at the roots, 1 at the tips.
    fn gear() -> Polygon {
        let vertices = (0..144)
            .map(|i| {
                let angle = i as f32 * TAU / 144.0;
                let radius = if i % 4 == 1 || i % 4 == 2 { 1.0 } else { 0.8 };
                // Counter-clockwise seen from +y runs from +z towards +x.
                Vec3::new(radius * angle.sin(), 0.0, radius * angle.cos())
            })
            .collect();
        Polygon::new(vertices).unwrap()
    }

    fn down_at(x: f32, y: f32) -> Ray {
        Ray::new(Vec3::new(x, y, 5.0), Vec3::new(0.0, 0.0, -2.0))
    }

    #[test]
    fn hit_from_the_front() {
        let square = unit_square();
        let ray = down_at(0.25, 0.5);
        let hit = square.intersect(&ray, 0.0, f32::INFINITY).unwrap();
        assert_eq!(hit, ShapeHit { t: 2.5, part: 0 });
        assert_eq!(ray.at(hit.t), Vec3::new(0.25, 0.5, 0.0));
        let surface = square.surface(ray.at(hit.t), hit.part);
        assert_eq!(surface.normal, Vec3::Z);
        assert_near(surface.uv.extend(0.0), Vec3::new(0.25, 0.5, 0.0), 1e-6);
    }

    #[test]
    fn hit_from_the_back() {
        let ray = Ray::new(Vec3::new(0.5, 0.5, -1.0), Vec3::new(0.0, 0.0, 4.0));
        let hit = unit_square().intersect(&ray, 0.0, f32::INFINITY).unwrap();
        assert_eq!(hit.t, 0.25);
        assert_eq!(unit_square().normal(), Vec3::Z);
    }

    #[test]
    fn clockwise_vertices_face_the_other_way() {
        let square = Polygon::new(vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
        ])
        .unwrap();
        assert_eq!(square.normal(), -Vec3::Z);
    }

    #[test]
    fn misses_outside_and_parallel() {
        let square = unit_square();
        assert_eq!(
            square.intersect(&down_at(1.5, 0.5), 0.0, f32::INFINITY),
            None
        );
        assert_eq!(
            square.intersect(&down_at(0.5, -0.01), 0.0, f32::INFINITY),
            None
        );
        let in_plane = Ray::new(Vec3::new(-1.0, 0.5, 0.0), Vec3::X);
        assert_eq!(square.intersect(&in_plane, 0.0, f32::INFINITY), None);
    }

    #[test]
    fn respects_the_t_range() {
        let square = unit_square();
        let ray = down_at(0.5, 0.5);
        assert_eq!(square.intersect(&ray, 0.0, 2.5), None);
        assert_eq!(square.intersect(&ray, 2.5, 10.0), None);
        assert!(square.intersect(&ray, 2.4, 2.6).is_some());
    }

    #[test]
    fn ray_starting_on_the_polygon_does_not_hit_it_again() {
        let ray = Ray::new(Vec3::new(0.5, 0.5, 0.0), Vec3::new(0.3, 0.1, 1.0));
        assert_eq!(unit_square().intersect(&ray, 1e-4, f32::INFINITY), None);
    }

    #[test]
    fn concave_l_shape_misses_its_notch() {
        let l = l_shape();
        let at = |x, y| Ray::new(Vec3::new(x, y, 3.0), Vec3::new(0.0, 0.0, -1.0));
        assert_eq!(l.intersect(&at(1.5, 1.5), 0.0, f32::INFINITY), None);
        assert_eq!(l.intersect(&at(2.5, 0.5), 0.0, f32::INFINITY), None);
        for (x, y) in [(0.5, 0.5), (1.5, 0.5), (0.5, 1.5), (0.99, 1.99)] {
            let hit = l.intersect(&at(x, y), 0.0, f32::INFINITY);
            assert_eq!(hit, Some(ShapeHit { t: 2.0, part: 0 }), "at ({x}, {y})");
        }
    }

    #[test]
    fn texture_coordinates_span_the_bounding_box() {
        let l = l_shape();
        let uv = |x, y| l.surface(Vec3::new(x, y, 1.0), 0).uv;
        assert_near(uv(0.0, 0.0).extend(0.0), Vec3::ZERO, 1e-6);
        assert_near(uv(2.0, 2.0).extend(0.0), Vec3::new(1.0, 1.0, 0.0), 1e-6);
        assert_near(uv(1.5, 0.5).extend(0.0), Vec3::new(0.75, 0.25, 0.0), 1e-6);
    }

    #[test]
    fn gear_hits_its_teeth_and_misses_the_gaps() {
        let gear = gear();
        let down = |angle: f32, radius: f32| {
            let p = Vec3::new(radius * angle.sin(), 0.0, radius * angle.cos());
            Ray::new(p + Vec3::Y * 2.0, -Vec3::Y)
        };
        let step = TAU / 144.0;
        // Middle of the first tooth (vertices 1 and 2) and middle of the first gap (3 and 4).
        let tooth = 1.5 * step;
        let gap = 3.5 * step;
        assert_near(gear.normal(), Vec3::Y, 1e-6);
        let hit = gear
            .intersect(&down(tooth, 0.95), 0.0, f32::INFINITY)
            .unwrap();
        assert!((hit.t - 2.0).abs() < 1e-6);
        assert_eq!(gear.intersect(&down(gap, 0.95), 0.0, f32::INFINITY), None);
        assert!(
            gear.intersect(&down(gap, 0.5), 0.0, f32::INFINITY)
                .is_some()
        );
        assert!(
            gear.intersect(&down(0.0, 0.0), 0.0, f32::INFINITY)
                .is_some()
        );
        assert_eq!(gear.intersect(&down(tooth, 1.05), 0.0, f32::INFINITY), None);
    }

    #[test]
    fn hit_point_lies_on_the_plane_and_normal_is_unit() {
        let tilted = Polygon::new(vec![
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ])
        .unwrap();
        let ray = Ray::new(Vec3::new(2.0, 2.0, 2.0), Vec3::new(-1.7, -2.0, -1.9));
        let hit = tilted.intersect(&ray, 0.0, f32::INFINITY).unwrap();
        let p = ray.at(hit.t);
        assert!((p.x + p.y + p.z - 1.0).abs() < 1e-6, "{p}");
        let n = tilted.surface(p, hit.part).normal;
        assert!((n.length() - 1.0).abs() < 1e-6);
        assert_near(n, Vec3::ONE / 3f32.sqrt(), 1e-6);
    }

    #[test]
    fn rejects_bad_vertex_lists() {
        let err = |v: Vec<Vec3>| Polygon::new(v).unwrap_err();
        assert_eq!(
            err(vec![Vec3::ZERO, Vec3::X]),
            "a polygon needs at least 3 vertices, got 2"
        );
        assert!(err(vec![Vec3::ZERO, Vec3::X, Vec3::splat(f32::NAN)]).contains("not finite"));
        assert!(err(vec![Vec3::ZERO, Vec3::X, Vec3::X * 2.0]).contains("zero area"));
        assert!(err(vec![Vec3::ZERO, Vec3::X, Vec3::ONE, Vec3::Y * 0.5]).contains("one plane"));
        assert!(err(vec![Vec3::ONE; 3]).contains("zero area"));
    }

    #[test]
    fn a_bowtie_is_self_intersecting_not_collinear() {
        // Two triangles of equal area meeting at (0.5, 0.5), one clockwise, one not.
        let bowtie = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let error = Polygon::new(bowtie).unwrap_err();
        assert!(error.contains("self-intersecting"), "{error}");
        assert!(!error.contains("collinear"), "{error}");
    }

    #[test]
    fn a_polygon_too_small_for_single_precision_says_so() {
        let tiny = unit_square_vertices().map(|v| v * 1e-30).to_vec();
        let error = Polygon::new(tiny).unwrap_err();
        assert!(error.contains("too small"), "{error}");
        // Small but workable.
        let small = unit_square_vertices().map(|v| v * 1e-15).to_vec();
        assert!(Polygon::new(small).is_ok());
    }

    #[test]
    fn accepts_slightly_uneven_vertices() {
        let almost_flat = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(10.0, 0.0, 0.0),
            Vec3::new(10.0, 10.0, 0.001),
            Vec3::new(0.0, 10.0, 0.0),
        ];
        assert!(Polygon::new(almost_flat).is_ok());
    }

    #[test]
    fn transformed_square_in_the_world() {
        // The unit square scaled by 2, turned to face +x (rotation by 90° about y maps +z to
        // +x and +x to −z), then moved by (3, 0, 0): it spans y ∈ [0, 2], z ∈ [−2, 0] at x = 3.
        let steps = [
            TransformStep::Scale(Vec3::splat(2.0)),
            TransformStep::Rotate {
                axis: Vec3::Y,
                degrees: 90.0,
            },
            TransformStep::Translate(Vec3::new(3.0, 0.0, 0.0)),
        ];
        let ray = Ray::new(Vec3::new(10.0, 1.5, -0.5), Vec3::new(-2.0, 0.0, 0.0));
        let (hit, surface) = hit_in_world(Shape::Polygon(unit_square()), &steps, &ray).unwrap();
        assert!((hit.t - 3.5).abs() < 1e-5);
        assert_near(surface.point, Vec3::new(3.0, 1.5, -0.5), 1e-5);
        assert_near(surface.normal, Vec3::X, 1e-5);
        assert_near(surface.object_point, Vec3::new(0.25, 0.75, 0.0), 1e-5);
        let miss = Ray::new(Vec3::new(10.0, 1.5, 0.5), Vec3::new(-2.0, 0.0, 0.0));
        assert!(hit_in_world(Shape::Polygon(unit_square()), &steps, &miss).is_none());
    }
}
