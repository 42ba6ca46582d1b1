// Mesh triangles: the twin of the watertight test of src/shapes/triangle.rs (Woop, Benthin and
// Wald 2013). The ray is sheared once (`ShearedRay`) so that it runs along +z from the origin;
// each triangle is then tested by the signs of three 2D edge functions.

// A mesh triangle's corners, and its index among the scene's triangles (src/gpu/bvh.rs).
struct Triangle {
    p0: vec3<f32>,
    index: u32,
    p1: vec3<f32>,
    // The id the object view colours it by: its mesh's (`Geometry::object_id`).
    object: u32,
    p2: vec3<f32>,
    pad2: u32,
}

// `ShearedRay`: the axes permuted so that z is the direction's largest, and the shear.
struct ShearedRay {
    origin: vec3<f32>,
    axes: vec3<u32>,
    shear: vec3<f32>,
}

fn shear_ray(origin: vec3<f32>, d: vec3<f32>) -> ShearedRay {
    let a = abs(d);
    // `max_position`: the first of the largest components.
    var kz = 0u;
    if a.y > a.x {
        kz = 1u;
    }
    if a.z > a[kz] {
        kz = 2u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kz + 2u) % 3u;
    if d[kz] < 0.0 {
        let swap = kx;
        kx = ky;
        ky = swap;
    }
    return ShearedRay(origin, vec3<u32>(kx, ky, kz), vec3<f32>(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]));
}

fn sheared_local(ray: ShearedRay, p: vec3<f32>) -> vec3<f32> {
    let a = p - ray.origin;
    return vec3<f32>(a[ray.axes.x], a[ray.axes.y], a[ray.axes.z]);
}

// `px·qy − py·qx` rounded once, as the CPU computes it in double precision where single
// precision gives exactly zero: each product split into its rounded value and its rounding
// error by `fma`, the differences of both summed.
fn exact_edge(px: f32, py: f32, qx: f32, qy: f32) -> f32 {
    let a = px * qy;
    let b = py * qx;
    let a_error = fma(px, qy, -a);
    let b_error = fma(py, qx, -b);
    return (a - b) + (a_error - b_error);
}

// A triangle hit: `t` and the barycentric coordinates of p1 and p2.
struct TriangleHit {
    t: f32,
    bary: vec2<f32>,
    found: bool,
}

// `Triangle::intersect_sheared`.
fn intersect_triangle(tri: Triangle, ray: ShearedRay, t_min: f32, t_max: f32) -> TriangleHit {
    let miss = TriangleHit(0.0, vec2<f32>(0.0), false);
    let a = sheared_local(ray, tri.p0);
    let b = sheared_local(ray, tri.p1);
    let c = sheared_local(ray, tri.p2);
    let s = ray.shear;
    let ax = a.x - s.x * a.z;
    let ay = a.y - s.y * a.z;
    let bx = b.x - s.x * b.z;
    let by = b.y - s.y * b.z;
    let cx = c.x - s.x * c.z;
    let cy = c.y - s.y * c.z;
    var u = cx * by - cy * bx;
    var v = ax * cy - ay * cx;
    var w = bx * ay - by * ax;
    if u == 0.0 || v == 0.0 || w == 0.0 {
        u = exact_edge(cx, cy, bx, by);
        v = exact_edge(ax, ay, cx, cy);
        w = exact_edge(bx, by, ax, ay);
    }
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return miss;
    }
    let det = u + v + w;
    if det == 0.0 {
        return miss;
    }
    let t = s.z * (u * a.z + v * b.z + w * c.z) / det;
    if !(t > t_min && t < t_max) {
        return miss;
    }
    return TriangleHit(t, vec2<f32>(v, w) / det, true);
}

// `Triangle::normal`: the unit geometric normal by the winding (zero for a degenerate one).
fn triangle_normal(tri: Triangle) -> vec3<f32> {
    let n = cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
    if dot(n, n) > 0.0 {
        return normalize(n);
    }
    return vec3<f32>(0.0);
}
