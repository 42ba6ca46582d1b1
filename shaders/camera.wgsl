// The lecture's camera: the twin of `Camera::eye_ray`, `Camera::dir_rc` and
// `Camera::backdrop_uv` in src/camera.rs.
// `dir_rc = −N·n + W(2c/nCols − 1)·u + H(2r/nRows − 1)·v`, rows counted from the bottom.

// The direction of the eye ray through the point `offset` of pixel (x, y) of the image, x from
// the left and y from the top; the ray reaches the image plane at t = 1.
fn eye_ray_dir(x: u32, y: u32, offset: vec2<f32>) -> vec3<f32> {
    let r = f32(frame.height - y) - offset.y;
    let c = f32(x) + offset.x;
    let n_rows = f32(frame.height);
    let n_cols = f32(frame.width);
    let h = frame.half_height;
    let w = h * n_cols / n_rows;
    return -frame.near * frame.n + w * (2.0 * c / n_cols - 1.0) * frame.u
        + h * (2.0 * r / n_rows - 1.0) * frame.v;
}

// Where a ray crosses the backdrop, if it does.
struct BackdropUv {
    uv: vec2<f32>,
    found: bool,
}

// `Camera::backdrop_uv`: where a ray in direction `dir` crosses an image of aspect ratio
// `aspect` (width over height) standing on the image plane, as tall as the view and centred:
// texture coordinates in [0, 1]² (v up); not found if the ray passes beside the image or points
// away from the plane.
fn backdrop_uv(dir: vec3<f32>, aspect: f32) -> BackdropUv {
    let depth = dot(dir, -frame.n);
    if depth <= F32_EPSILON * length(dir) {
        return BackdropUv(vec2<f32>(0.0), false);
    }
    // On the image plane at distance N, in units of the half height H.
    let y = frame.near * dot(dir, frame.v) / depth / frame.half_height;
    let x = frame.near * dot(dir, frame.u) / depth / (frame.half_height * aspect);
    let uv = (vec2<f32>(x, y) + 1.0) * 0.5;
    return BackdropUv(uv, all(uv >= vec2<f32>(0.0)) && all(uv <= vec2<f32>(1.0)));
}

// `sample_ray` (src/progressive/plan.rs): the direction of the eye ray of sample `k` of film
// pixel (x, y): through the pixel's centre for sample 0, through its jittered point for k ≥ 1,
// by the pixel's place in the whole image, of which the film may be a window.
fn sample_ray_dir(film_x: u32, film_y: u32, k: u32) -> vec3<f32> {
    let x = frame.film_left + film_x;
    let y = frame.film_top + film_y;
    var offset = PIXEL_CENTRE;
    if k != 0u {
        offset = jitter(x, y, k);
    }
    return eye_ray_dir(x, y, offset);
}
