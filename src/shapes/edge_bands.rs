//! The inside test of a projected polygon: the crossing number, over the polygon's edges sorted
//! into horizontal bands so that a point looks only at the edges that can reach its height. A
//! gear's face of 144 edges asks about a handful; a triangle has one band of three edges.

use glam::Vec2;

/// Bands per edge of the polygon, at most: about two edges to a band for a polygon whose
/// edges are short.
const EDGES_PER_BAND: usize = 2;

/// Polygons with at most this many edges that are not horizontal have one band: looking up a
/// band would cost more than testing them all.
const ONE_BAND_MAX_EDGES: usize = 8;

/// Most bands an edge may be listed in on average: the band count shrinks until the lists hold
/// at most this many entries per edge, so a polygon whose long edges span many bands costs
/// memory in proportion to its edges.
const MAX_ENTRIES_PER_EDGE: usize = 4;

/// One edge of the projected polygon, stored for the crossing test: where it starts, the `y`
/// where it ends, and how fast `x` changes with `y` along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProjectedEdge {
    pub start: Vec2,
    pub end_y: f32,
    pub dx_dy: f32,
}

impl ProjectedEdge {
    pub fn new(start: Vec2, end: Vec2) -> Self {
        let dy = end.y - start.y;
        let dx_dy = if dy == 0.0 {
            0.0
        } else {
            (end.x - start.x) / dy
        };
        ProjectedEdge {
            start,
            end_y: end.y,
            dx_dy,
        }
    }

    /// Whether a horizontal half-line from `q` towards +x crosses the edge. The edge counts its
    /// lower end and not its upper one, so a half-line through a vertex is counted once, and a
    /// horizontal edge is never crossed. Both tests always run, which keeps callers' loops free
    /// of branches.
    #[inline(always)]
    pub fn crossed_from(&self, q: Vec2) -> bool {
        let straddles = (self.start.y > q.y) != (self.end_y > q.y);
        let crossing_is_right_of_q = q.x < self.start.x + (q.y - self.start.y) * self.dx_dy;
        straddles & crossing_is_right_of_q
    }
}

/// The edges of a polygon listed by horizontal band: band `k` covers the heights that
/// [`EdgeBands::band`] sends to `k`, and lists every edge that can straddle one of them. An edge
/// straddles a height `y` only if `y` lies between its ends; the band of a height grows with the
/// height, so such an edge is listed in the band of `y`. The bands give the same answer as all
/// the edges, bit for bit.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeBands {
    /// The lowest height of the polygon.
    pub(crate) min_y: f32,
    /// Bands per unit of height.
    pub(crate) bands_per_y: f32,
    /// Band `k`'s edges are `edges[starts[k]..starts[k + 1]]`.
    pub(crate) starts: Vec<u32>,
    pub(crate) edges: Vec<ProjectedEdge>,
}

impl EdgeBands {
    /// The bands of a closed polygon with the projected vertices `points`, between the heights
    /// `min_y` and `max_y`.
    pub fn new(points: &[Vec2], min_y: f32, max_y: f32) -> EdgeBands {
        let edges: Vec<ProjectedEdge> = points
            .iter()
            .zip(points.iter().cycle().skip(1))
            .map(|(&a, &b)| ProjectedEdge::new(a, b))
            .filter(|edge| edge.start.y != edge.end_y)
            .collect();
        let mut count = if edges.len() <= ONE_BAND_MAX_EDGES {
            1
        } else {
            edges.len() / EDGES_PER_BAND
        };
        loop {
            let bands = EdgeBands::with_count(&edges, count, min_y, max_y);
            if count == 1 || bands.edges.len() <= MAX_ENTRIES_PER_EDGE * edges.len() {
                return bands;
            }
            count /= 2;
        }
    }

    fn with_count(edges: &[ProjectedEdge], count: usize, min_y: f32, max_y: f32) -> EdgeBands {
        let height = max_y - min_y;
        let bands_per_y = if count > 1 && height > 0.0 {
            count as f32 / height
        } else {
            0.0
        };
        let band = |y| band_of(y, min_y, bands_per_y, count);
        let span = |edge: &ProjectedEdge| {
            band(edge.start.y.min(edge.end_y))..=band(edge.start.y.max(edge.end_y))
        };
        // Count the edges of each band, then place them.
        let mut starts = vec![0u32; count + 1];
        for edge in edges {
            for k in span(edge) {
                starts[k + 1] += 1;
            }
        }
        for k in 0..count {
            starts[k + 1] += starts[k];
        }
        let mut placed = vec![ProjectedEdge::new(Vec2::ZERO, Vec2::ZERO); starts[count] as usize];
        let mut next = starts[..count].to_vec();
        for edge in edges {
            for k in span(edge) {
                placed[next[k] as usize] = *edge;
                next[k] += 1;
            }
        }
        EdgeBands {
            min_y,
            bands_per_y,
            starts,
            edges: placed,
        }
    }

    /// Every edge that is not horizontal, when the polygon has one band (at most
    /// [`ONE_BAND_MAX_EDGES`] of them).
    pub fn single_band(&self) -> Option<&[ProjectedEdge]> {
        (self.starts.len() == 2).then_some(&self.edges[..])
    }

    /// Crossing-number test: a horizontal half-line from `q` towards +x crosses the edges an odd
    /// number of times exactly when `q` is inside.
    #[inline]
    pub fn contains(&self, q: Vec2) -> bool {
        let k = band_of(q.y, self.min_y, self.bands_per_y, self.starts.len() - 1);
        let edges = &self.edges[self.starts[k] as usize..self.starts[k + 1] as usize];
        edges
            .iter()
            .fold(false, |inside, edge| inside ^ edge.crossed_from(q))
    }
}

/// The band of the height `y`, among `count` bands of `bands_per_y` per unit of height from
/// `min_y`: it never decreases as `y` grows (a NaN goes to band 0, whose edges it crosses none
/// of, as it crosses no edge).
#[inline(always)]
fn band_of(y: f32, min_y: f32, bands_per_y: f32, count: usize) -> usize {
    (((y - min_y) * bands_per_y) as usize).min(count - 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The crossing number over every edge: what the bands must agree with.
    fn contains_by_all_edges(points: &[Vec2], q: Vec2) -> bool {
        points
            .iter()
            .zip(points.iter().cycle().skip(1))
            .fold(false, |inside, (&a, &b)| {
                inside ^ ProjectedEdge::new(a, b).crossed_from(q)
            })
    }

    fn bands_of(points: &[Vec2]) -> EdgeBands {
        let min_y = points.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
        let max_y = points.iter().map(|p| p.y).fold(f32::NEG_INFINITY, f32::max);
        EdgeBands::new(points, min_y, max_y)
    }

    /// A star of `n` points, alternately at radius 1 and 0.9: short teeth, as on a gear.
    fn star(n: usize) -> Vec<Vec2> {
        (0..n)
            .map(|i| {
                let angle = i as f32 * std::f32::consts::TAU / n as f32;
                let r = if i % 2 == 0 { 1.0 } else { 0.9 };
                Vec2::new(r * angle.cos(), r * angle.sin())
            })
            .collect()
    }

    #[test]
    fn a_star_is_split_into_bands_that_each_list_few_edges() {
        let bands = bands_of(&star(144));
        let count = bands.starts.len() - 1;
        assert_eq!(count, 72);
        // A height chosen at random looks at 8 edges or fewer on average, instead of 144.
        assert!(bands.edges.len() <= 8 * count, "{}", bands.edges.len());
    }

    #[test]
    fn edges_spanning_the_whole_height_shrink_the_band_count() {
        // A comb: 50 tall teeth, each of two edges spanning the whole height.
        let mut points = Vec::new();
        for i in 0..50 {
            let x = i as f32;
            points.extend([Vec2::new(x, 0.0), Vec2::new(x + 0.5, 10.0)]);
        }
        points.push(Vec2::new(50.0, -1.0));
        points.push(Vec2::new(0.0, -1.0));
        let bands = bands_of(&points);
        assert!(bands.edges.len() <= MAX_ENTRIES_PER_EDGE * points.len());
        for q in [
            Vec2::new(3.1, 5.0),
            Vec2::new(3.4, 9.0),
            Vec2::new(10.0, -0.5),
        ] {
            assert_eq!(bands.contains(q), contains_by_all_edges(&points, q), "{q}");
        }
    }

    proptest! {
        /// Random polygons (stars with jittered radii, so many edges, some concave) and random
        /// points, many on vertex heights: the bands answer as all the edges do.
        #[test]
        fn bands_agree_with_every_edge(
            radii in proptest::collection::vec(1u32..1000, 3..200),
            point in (0u32..4096, 0u32..4096),
            on_vertex in proptest::option::of(0usize..200),
        ) {
            let n = radii.len();
            let points: Vec<Vec2> = radii
                .iter()
                .enumerate()
                .map(|(i, &r)| {
                    let angle = i as f32 * std::f32::consts::TAU / n as f32;
                    r as f32 / 1000.0 * Vec2::new(angle.cos(), angle.sin())
                })
                .collect();
            let bands = bands_of(&points);
            let mut q = Vec2::new(point.0 as f32, point.1 as f32) / 2048.0 - 1.0;
            if let Some(i) = on_vertex {
                q.y = points[i % n].y;
            }
            prop_assert_eq!(bands.contains(q), contains_by_all_edges(&points, q));
        }
    }
}
