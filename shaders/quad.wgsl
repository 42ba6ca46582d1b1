// The traced image on a two-triangle quad. The quad fills the viewport, which the viewer sets
// to the image rectangle. The textures hold the display's sRGB bytes (the upload applied
// exposure, tone curve and sRGB: `src/viewer/gpu/upload.rs`); each screen pixel shows its
// nearest texel (coarse passes show as fat pixels), unchanged, into the (non-sRGB) target. Left
// of the divider the snapshot is shown instead.

struct VertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

// Two triangles covering clip space, as (x, y) corners; uv (0, 0) is the image's top-left.
const CORNERS = array<vec2<f32>, 6>(
    vec2<f32>(-1.0, -1.0),
    vec2<f32>(1.0, -1.0),
    vec2<f32>(1.0, 1.0),
    vec2<f32>(-1.0, -1.0),
    vec2<f32>(1.0, 1.0),
    vec2<f32>(-1.0, 1.0),
);

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> VertexOut {
    let corner = CORNERS[index];
    var out: VertexOut;
    out.position = vec4<f32>(corner, 0.0, 1.0);
    out.uv = vec2<f32>(corner.x * 0.5 + 0.5, 0.5 - corner.y * 0.5);
    return out;
}

// Written by `src/viewer/gpu/quad.rs` (same layout).
struct Display {
    // Image x (0 left, 1 right) left of which the snapshot is shown; 0 shows none of it.
    divider: f32,
    unused0: f32,
    unused1: f32,
    unused2: f32,
};

@group(0) @binding(QUAD_LIVE) var live: texture_2d<f32>;
@group(0) @binding(QUAD_SNAPSHOT) var snapshot: texture_2d<f32>;
@group(0) @binding(QUAD_DISPLAY) var<uniform> display: Display;

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let size = textureDimensions(live);
    let texel = min(vec2<u32>(in.uv * vec2<f32>(size)), size - 1u);
    if in.uv.x < display.divider {
        return textureLoad(snapshot, texel, 0);
    }
    return textureLoad(live, texel, 0);
}
