// The GPU tracer's entry point: the colour of each pixel sample of a list, the twin of the
// CPU sweep's `trace_tile` (src/progressive/cpu.rs): the eye ray through the sample's point of
// its pixel (sample 0 at the centre, sample k ≥ 1 at its jittered point), traced by the ray
// tree, its first hit searched for only up to its pixel's item where the render has an item
// buffer (the sample's `item_t`). Bind group 1 holds the list and the colours.

@group(1) @binding(WORK_INPUT) var<storage, read> samples: array<PixelSample>;
@group(1) @binding(WORK_OUTPUT) var<storage, read_write> colors: array<SampleColor>;

@compute @workgroup_size(WORKGROUP)
fn trace_samples(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= arrayLength(&samples) {
        return;
    }
    let s = samples[i];
    let traced = trace_eye(sample_ray_dir(s.x, s.y, s.k), s.item_t);
    let c = traced.counts;
    colors[i] = SampleColor(traced.color, c.primary_hits, c.shadow, c.reflected, c.transmitted, c.over_budget, u32(cut_short), c.from_item_buffer, 0u, 0u);
}
