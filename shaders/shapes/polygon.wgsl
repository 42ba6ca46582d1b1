// Flat polygons, convex or concave: the twin of src/shapes/polygon.rs and of the crossing-number
// test by bands of src/shapes/edge_bands.rs. src/gpu/shapes.rs (`push_polygon`) lays out the
// words: a header of six, the bands' starts four to a word, then the listed edges one to a word.

struct Polygon {
    // Unit normal, pointing to the front.
    normal: vec3<f32>,
    // normal · p for every point p of the polygon's plane.
    plane_offset: f32,
    projected_min: vec2<f32>,
    projected_max: vec2<f32>,
    // The two coordinate axes kept by the projection.
    kept_axes: vec2<u32>,
    texture_axis_s: vec3<f32>,
    texture_axis_t: vec3<f32>,
    texture_min: vec2<f32>,
    texture_inv_extent: vec2<f32>,
    // The edge bands (`EdgeBands`): the lowest height, bands per unit of height, the number of
    // bands, and where their starts and the listed edges are in the shape words.
    min_y: f32,
    bands_per_y: f32,
    band_count: u32,
    starts: u32,
    edges: u32,
}

fn load_polygon(first: u32) -> Polygon {
    let plane = shape_words[first];
    let projected = shape_words[first + 1u];
    let s = shape_words[first + 2u];
    let t = shape_words[first + 3u];
    let texture = shape_words[first + 4u];
    let bands = shape_words[first + 5u];
    let band_count = bitcast<u32>(bands.z);
    let starts = first + 6u;
    // The band count + 1 starts, four to a word.
    let edges = starts + (band_count + 4u) / 4u;
    return Polygon(
        plane.xyz,
        plane.w,
        projected.xy,
        projected.zw,
        bitcast<vec2<u32>>(texture.zw),
        s.xyz,
        t.xyz,
        vec2<f32>(s.w, t.w),
        texture.xy,
        bands.x,
        bands.y,
        band_count,
        starts,
        edges,
    );
}

// `Polygon::intersect`: a hit on the plane, then the inside test in the projection.
fn intersect_polygon(s: Polygon, origin: vec3<f32>, dir: vec3<f32>, t_min: f32, t_max: f32) -> ShapeHit {
    let denom = dot(s.normal, dir);
    if denom == 0.0 {
        return no_hit(); // parallel to the plane
    }
    let t = (s.plane_offset - dot(s.normal, origin)) / denom;
    if !(t > t_min && t < t_max) {
        return no_hit();
    }
    let p = origin + dir * t;
    let q = vec2<f32>(p[s.kept_axes.x], p[s.kept_axes.y]);
    if polygon_contains_projected(s, q) {
        return ShapeHit(t, 0u, true);
    }
    return no_hit();
}

// `Polygon::contains_projected`: whether the projected point `q` is inside the polygon.
fn polygon_contains_projected(s: Polygon, q: vec2<f32>) -> bool {
    if any(q < s.projected_min) || any(q > s.projected_max) {
        return false;
    }
    return polygon_bands_contain(s, q);
}

// `EdgeBands::contains`: the crossing number over the edges of the band of q's height.
fn polygon_bands_contain(s: Polygon, q: vec2<f32>) -> bool {
    let k = polygon_band_of(s, q.y);
    let start = polygon_band_start(s, k);
    let end = polygon_band_start(s, k + 1u);
    var inside = false;
    for (var i = start; i < end; i++) {
        let edge = shape_words[s.edges + i];
        // `ProjectedEdge::crossed_from`: (start.x, start.y, end_y, dx_dy).
        let straddles = (edge.y > q.y) != (edge.z > q.y);
        let crossing_is_right_of_q = q.x < edge.x + (q.y - edge.y) * edge.w;
        inside = inside != (straddles && crossing_is_right_of_q);
    }
    return inside;
}

// `band_of`: the band of the height `y`, never beyond the last; below the lowest height, band 0
// (Rust's conversion to `usize` saturates at 0).
fn polygon_band_of(s: Polygon, y: f32) -> u32 {
    let x = (y - s.min_y) * s.bands_per_y;
    if x > 0.0 {
        return u32(min(x, f32(s.band_count - 1u)));
    }
    return 0u;
}

// Where band `k`'s edges start among the listed edges.
fn polygon_band_start(s: Polygon, k: u32) -> u32 {
    return bitcast<u32>(shape_words[s.starts + k / 4u][k % 4u]);
}

// `Polygon::surface`: planar mapping, scaled so that the polygon's extent along each axis
// covers [0, 1].
fn polygon_surface(s: Polygon, p: vec3<f32>, part: u32) -> LocalSurface {
    let planar = vec2<f32>(dot(p, s.texture_axis_s), dot(p, s.texture_axis_t));
    let uv = (planar - s.texture_min) * s.texture_inv_extent;
    return LocalSurface(s.normal, clamp(uv, vec2<f32>(0.0), vec2<f32>(1.0)));
}
