// The lecture's modified Z-buffer (src/gpu/item_raster.rs draws it): one raster pass over the
// scene from the camera into an item buffer that holds, for each pixel of the film, the
// primitive seen first along the eye ray through the pixel's centre and how far along it.
//
// Mesh triangles are drawn as themselves. Every object is drawn as a proxy that covers it: the
// faces of its bounding box, or the whole film for an object without bounds (a plane). Each
// fragment intersects the exact primitive along its pixel's eye ray and writes `1/t` as its
// depth, or is discarded where the ray misses, so the depth test (greater wins) keeps the
// nearest exact surface. Eye rays see only what lies beyond the image plane (t ≥ 1), so the
// depth lies in (0, 1], and no fragment nearer than the image plane is drawn.

// An object's proxy: its bounding box (PROXY_BOX), or the whole film (PROXY_FULL_FILM); or an
// instance's bounding box (PROXY_INSTANCE), `object` then where its record starts in `refs`.
struct Proxy {
    lo: vec3<f32>,
    object: u32,
    hi: vec3<f32>,
    kind: u32,
}

// The film's size in pixels (where it lies in the image is the frame's `film_left`, `film_top`).
struct RasterFilm {
    width: u32,
    height: u32,
    pad0: u32,
    pad1: u32,
}

@group(1) @binding(WORK_PROXIES) var<storage, read> proxies: array<Proxy>;
@group(1) @binding(WORK_RASTER_FILM) var<storage, read> raster_film: RasterFilm;

// What a fragment writes: the primitive (`PrimId`), the bits of `t`, the part of an object hit,
// and a triangle's slot in `triangles`. A pixel nothing was drawn on keeps the primitive
// `NO_ITEM`.
struct ItemOutput {
    @location(0) item: vec4<u32>,
    @builtin(frag_depth) depth: f32,
}

// The clip-space position of the world point `p` on the film: the camera's projection, the
// twin of `eye_ray_dir` (camera.wgsl), with `w` the distance along the view direction. The film
// may be a window of the image.
fn clip_position(p: vec3<f32>) -> vec4<f32> {
    let d = p - frame.eye;
    let w = -dot(d, frame.n);
    let image = vec2<f32>(f32(frame.width), f32(frame.height));
    let film = vec2<f32>(f32(raster_film.width), f32(raster_film.height));
    let h = frame.half_height;
    // The image's normalised coordinates (−1 to 1, y up), times w.
    let x_image = frame.near * dot(d, frame.u) / (h * image.x / image.y);
    let y_image = frame.near * dot(d, frame.v) / h;
    // The film's pixel coordinates (y down), times w.
    let column = (x_image + w) * 0.5 * image.x - f32(frame.film_left) * w;
    let row = (w - y_image) * 0.5 * image.y - f32(frame.film_top) * w;
    let x = column * 2.0 / film.x - w;
    let y = w - row * 2.0 / film.y;
    return vec4<f32>(x, y, w - NEAR_SHARE * frame.near, w);
}

// The direction of the eye ray through the centre of the film pixel a fragment covers.
fn fragment_ray_dir(position: vec4<f32>) -> vec3<f32> {
    let x = frame.film_left + u32(position.x);
    let y = frame.film_top + u32(position.y);
    return eye_ray_dir(x, y, PIXEL_CENTRE);
}

// The corners of a box's twelve triangles, two per face; corner bits: x 1, y 2, z 4.
const BOX_CORNERS = array<u32, 36>(
    0u, 2u, 6u, 0u, 6u, 4u,
    1u, 3u, 7u, 1u, 7u, 5u,
    0u, 1u, 5u, 0u, 5u, 4u,
    2u, 3u, 7u, 2u, 7u, 6u,
    0u, 1u, 3u, 0u, 3u, 2u,
    4u, 5u, 7u, 4u, 7u, 6u,
);

struct ProxyCorner {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) instance: u32,
}

// Corner `vertex` of proxy `instance`'s triangles: 36 per proxy. A proxy of the whole film uses
// the first three for one triangle over it, and puts the rest on one point, drawing nothing.
@vertex
fn proxy_corner(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> ProxyCorner {
    let proxy = proxies[instance];
    if proxy.kind == PROXY_FULL_FILM {
        var corner = vec2<f32>(-1.0, -1.0);
        if vertex == 1u {
            corner = vec2<f32>(3.0, -1.0);
        } else if vertex == 2u {
            corner = vec2<f32>(-1.0, 3.0);
        }
        return ProxyCorner(vec4<f32>(corner, 0.5, 1.0), instance);
    }
    let bits = BOX_CORNERS[vertex];
    let p = select(proxy.lo, proxy.hi, vec3<bool>((bits & 1u) != 0u, (bits & 2u) != 0u, (bits & 4u) != 0u));
    return ProxyCorner(clip_position(p), instance);
}

// An object's fragment: where its exact shape meets the pixel's eye ray, if it does; an
// instance's: the nearest of its triangles the ray meets, found by walking into it.
@fragment
fn proxy_item(corner: ProxyCorner) -> ItemOutput {
    let dir = fragment_ray_dir(corner.position);
    let proxy = proxies[corner.instance];
    if proxy.kind == PROXY_INSTANCE {
        let hit = walk_from(frame.eye, dir, EYE_RAY_T_MIN, T_FAR, FIND_CLOSEST, proxy.object).hit;
        if !hit.found {
            discard;
        }
        let item = vec4<u32>(hit.prim, bitcast<u32>(hit.t), 0u, hit.slot);
        return ItemOutput(item, 1.0 / hit.t);
    }
    let h = intersect_object(objects[proxy.object], frame.eye, dir, EYE_RAY_T_MIN, T_FAR);
    if !h.found {
        discard;
    }
    let item = vec4<u32>(proxy.object | OBJECT_BIT, bitcast<u32>(h.t), h.part, 0u);
    return ItemOutput(item, 1.0 / h.t);
}

struct TriangleCorner {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) slot: u32,
}

// Corner `vertex % 3` of the triangle `vertex / 3` in `triangles`.
@vertex
fn triangle_corner(@builtin(vertex_index) vertex: u32) -> TriangleCorner {
    let slot = vertex / 3u;
    let tri = triangles[slot];
    var p = tri.p0;
    if vertex % 3u == 1u {
        p = tri.p1;
    } else if vertex % 3u == 2u {
        p = tri.p2;
    }
    return TriangleCorner(clip_position(p), slot);
}

// A triangle's fragment: the watertight test's `t` along the pixel's eye ray. Where the raster's
// coverage and the test's rounding disagree (a pixel centre on an edge), the distance to the
// triangle's plane, so that no pixel between two triangles is left empty.
@fragment
fn triangle_item(corner: TriangleCorner) -> ItemOutput {
    let dir = fragment_ray_dir(corner.position);
    let tri = triangles[corner.slot];
    let h = intersect_triangle(tri, shear_ray(frame.eye, dir), EYE_RAY_T_MIN, T_FAR);
    var t = h.t;
    if !h.found {
        let normal = cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
        t = dot(tri.p0 - frame.eye, normal) / dot(dir, normal);
        if !(t > EYE_RAY_T_MIN && t < T_FAR) {
            discard;
        }
    }
    let item = vec4<u32>(tri.index, bitcast<u32>(t), 0u, corner.slot);
    return ItemOutput(item, 1.0 / t);
}
