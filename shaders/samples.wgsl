// The records of a list of pixel samples and of what the tracer made of each, read by the
// tracer's entry point (trace_samples.wgsl) and by the film's (film.wgsl): `PixelSample` and
// `SampleColor` in src/gpu/tracer.rs.

// Sample `k` of film pixel (x, y), and the distance of its pixel's item in the item buffer
// (0: none).
struct PixelSample {
    x: u32,
    y: u32,
    k: u32,
    item_t: f32,
}

// What a sample's tree gave: its colour and the rays it traced, or that the driver cut its
// work short (`cut_short`, 1).
struct SampleColor {
    color: vec3<f32>,
    primary_hits: u32,
    shadow: u32,
    reflected: u32,
    transmitted: u32,
    over_budget: u32,
    cut_short: u32,
    // 1 where the eye ray's first hit is its pixel's item in the item buffer.
    from_item_buffer: u32,
    pad1: u32,
    pad2: u32,
}
