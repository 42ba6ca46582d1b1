// The traced image on a two-triangle quad. The quad fills the viewport, which the viewer sets
// to the letterboxed image rectangle. The textures hold the film's linear colours (floats); each
// screen pixel shows its nearest texel (coarse passes show as fat pixels) through the exposure
// and tone curve, encoded as sRGB exactly as the library's `raylab::tone::Tone::srgb8` does, and
// goes to the (non-sRGB) target unchanged. Left of the divider the snapshot is shown instead.

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

// How the image is shown; written by `src/viewer/gpu/quad.rs` (same layout).
struct Display {
    // What the linear values are multiplied by: 2^exposure.
    scale: f32,
    // The tone curve: 0 clamp, 1 Reinhard, 2 filmic (`ToneCurve::shader_index`).
    curve: u32,
    // Image x (0 left, 1 right) left of which the snapshot is shown; 0 shows none of it.
    divider: f32,
    unused: f32,
    // `raylab::color::srgb8_steps`, four to a vector: step k is the least linear value whose
    // sRGB byte is k + 1 (the last of the 256 slots is never read).
    srgb_steps: array<vec4<f32>, 64>,
};

@group(0) @binding(0) var live: texture_2d<f32>;
@group(0) @binding(1) var snapshot: texture_2d<f32>;
@group(0) @binding(2) var<uniform> display: Display;

// `raylab::tone::ToneCurve::apply`.
fn tone_curve(v: f32) -> f32 {
    let x = min(max(v, 0.0), 1e6);
    switch display.curve {
        case 1u: {
            return x / (1.0 + x);
        }
        case 2u: {
            return min((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 1.0);
        }
        default: {
            return min(x, 1.0);
        }
    }
}

fn srgb_step(k: u32) -> f32 {
    return display.srgb_steps[k / 4u][k % 4u];
}

// `raylab::color::srgb8` as a fraction of 255: the number of steps at or below `v`, found by
// halving the table eight times.
fn srgb_encode(v: f32) -> f32 {
    var count = 0u;
    for (var half = 128u; half > 0u; half = half / 2u) {
        if srgb_step(count + half - 1u) <= v {
            count = count + half;
        }
    }
    return f32(count) / 255.0;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let size = textureDimensions(live);
    let texel = min(vec2<u32>(in.uv * vec2<f32>(size)), size - 1u);
    var linear = textureLoad(live, texel, 0).rgb;
    if in.uv.x < display.divider {
        linear = textureLoad(snapshot, texel, 0).rgb;
    }
    let scaled = linear * display.scale;
    let shown = vec3<f32>(
        srgb_encode(tone_curve(scaled.r)),
        srgb_encode(tone_curve(scaled.g)),
        srgb_encode(tone_curve(scaled.b)),
    );
    return vec4<f32>(shown, 1.0);
}
