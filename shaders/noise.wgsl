// Noise for solid textures: the twin of src/noise.rs, bit for bit in its lattice (the same
// integer hash of the same i32 lattice coordinates, `hash` in sampling.wgsl).

// `lattice`: the random value in [0, 1) fixed at lattice point (i, j, k). `u32(i)` keeps the
// bits of i, as Rust's `i as u32` does.
fn lattice(i: i32, j: i32, k: i32) -> f32 {
    return to_unit(hash(u32(i) ^ hash(u32(j) ^ hash(u32(k)))));
}

// `noise`: the values at the eight corners of p's lattice cell, blended with smoothstep
// weights. `i32(…)` saturates as Rust's `as i32` does.
fn noise(p: vec3<f32>) -> f32 {
    let cell = floor(p);
    let f = p - cell;
    let w = f * f * (3.0 - 2.0 * f);
    let c = vec3<i32>(i32(cell.x), i32(cell.y), i32(cell.z));
    var sum = 0.0;
    for (var corner = 0; corner < 8; corner++) {
        let d = vec3<i32>(corner & 1, (corner >> 1u) & 1, corner >> 2u);
        // The weight of the corner at offset d: w where d is 1, 1 − w where it is 0.
        let along = select(1.0 - w, w, d == vec3<i32>(1));
        sum += along.x * along.y * along.z * lattice(c.x + d.x, c.y + d.y, c.z + d.z);
    }
    return sum;
}

// `turbulence`: noise at frequency `scale`, twice it and four times it, at ½, ¼ and ⅛.
fn turbulence(scale: f32, p: vec3<f32>) -> f32 {
    return 0.5 * noise(scale * p) + 0.25 * noise(2.0 * scale * p) + 0.125 * noise(4.0 * scale * p);
}
