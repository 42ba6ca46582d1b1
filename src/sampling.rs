//! Where the samples of a pixel lie: deterministic sub-pixel offsets ([`jitter`]) from an
//! integer hash ([`hash`]), so that a render is the same whatever the thread count and order;
//! and deterministic random numbers for anything else that needs them ([`random`], photons).

/// A deterministic sub-pixel offset in [0, 1)² for sample `k` of pixel (x, y), so a render is
/// reproducible whatever the thread count.
pub fn jitter(x: u32, y: u32, k: u32) -> (f32, f32) {
    let h = hash(x ^ hash(y ^ hash(k)));
    (to_unit(h), to_unit(hash(h)))
}

/// Number `dim` of the random sequence `stream`, in [0, 1): the same whatever else was drawn
/// before, so that sequences can be used on any thread in any order.
pub fn random(stream: u32, dim: u32) -> f32 {
    to_unit(hash(hash(stream) ^ hash(dim ^ 0x9e37_79b9)))
}

/// The top 24 bits of `v` as a number in [0, 1).
fn to_unit(v: u32) -> f32 {
    (v >> 8) as f32 / (1u32 << 24) as f32
}

/// A 32-bit integer hash (PCG output permutation).
pub fn hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}
