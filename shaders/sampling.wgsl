// Where the samples of a pixel lie: the twin of src/sampling.rs, bit for bit (integer hashes).

// A 32-bit integer hash (PCG output permutation): `hash`.
fn hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The top 24 bits of `v` as a number in [0, 1): `to_unit`.
fn to_unit(v: u32) -> f32 {
    return f32(v >> 8u) / f32(1u << 24u);
}

// The offset within pixel (x, y) of sample k (k ≥ 1; sample 0 is the centre): `jitter`.
fn jitter(x: u32, y: u32, k: u32) -> vec2<f32> {
    let h = hash(x ^ hash(y ^ hash(k)));
    return vec2<f32>(to_unit(h), to_unit(hash(h)));
}
