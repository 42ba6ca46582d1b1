// The lecture's camera: the twin of `Camera::eye_ray` and `Camera::dir_rc` in src/camera.rs.
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
