// Textures: the twin of `Texture::color`, `Texture::alpha`, `marble_spline` and
// `SrgbImage::bilinear` in src/texture.rs. The records are made by src/gpu/texture.rs; an
// image's texels lie in `texels` one u32 each (r | g << 8 | b << 16 | alpha << 24), after the
// sRGB decode table.

// A texture: its kind and the numbers that kind reads (`GpuTexture`).
struct Texture {
    // The first colour; Marble's colour.
    a: vec3<f32>,
    kind: u32,
    b: vec3<f32>,
    // Checker3d's cube side.
    size: f32,
    // An image's scale; CheckerUv's squares across and up.
    scale: vec2<f32>,
    offset: vec2<f32>,
    // Where an image's texels start in `texels`.
    first: u32,
    width: u32,
    height: u32,
    wrap: u32,
}

// `rem_euclid(2)` of `x as i64` for a whole number x, as 0 or 1: worked out in f32, where
// halving, flooring and doubling a whole number are exact, so it agrees with the CPU's i64 for
// every x the i64 holds (any f32 of 2²⁴ or more is even), and for NaN, which `as i64` makes 0.
fn parity(x: f32) -> f32 {
    return select(0.0, 1.0, x - 2.0 * floor(0.5 * x) == 1.0);
}

// `a` where the parity is even, else `b`.
fn alternate(a: vec3<f32>, b: vec3<f32>, parity: f32) -> vec3<f32> {
    return select(a, b, parity == 1.0);
}

// `marble_spline`: how bright the stone is at x = sin(…) in [−1, 1].
fn marble_spline(x: f32) -> f32 {
    if x < -0.4 {
        let d = x + 0.75;
        return 0.15 + 2.857 * (d * d);
    }
    if x < 0.4 {
        return 0.95 - 2.8125 * x * x;
    }
    let d = x - 0.7;
    return 0.26 + 2.666 * (d * d);
}

// `Color::lerp`: a · (1 − s) + b · s, of the colour and the alpha alike.
fn lerp(a: vec4<f32>, b: vec4<f32>, s: f32) -> vec4<f32> {
    return a * (1.0 - s) + b * s;
}

// `Wrap::texel`: texel i of a row or column of n, wrapped into 0..n.
fn wrapped(i: i32, n: i32, wrap: u32) -> i32 {
    if wrap == WRAP_CLAMP {
        return clamp(i, 0, n - 1);
    }
    // rem_euclid: `%` keeps the sign of i, as Rust's does.
    if wrap == WRAP_MIRROR {
        let m = ((i % (2 * n)) + 2 * n) % (2 * n);
        return select(2 * n - 1 - m, m, m < n);
    }
    return ((i % n) + n) % n;
}

// The linear colour and the alpha of texel (x, y) of image `t`, wrapped into it. The CPU
// wraps in i64, this in i32: the same for texel coordinates within ±2³¹ (|uv| below 2³¹ over
// the image's size).
fn texel(t: Texture, x: i32, y: i32) -> vec4<f32> {
    let wrap_u = extractBits(t.wrap, 0u, WRAP_V_SHIFT);
    let wrap_v = extractBits(t.wrap, WRAP_V_SHIFT, WRAP_V_SHIFT);
    let at = vec2<i32>(wrapped(x, i32(t.width), wrap_u), wrapped(y, i32(t.height), wrap_v));
    let packed = texels[t.first + u32(at.y) * t.width + u32(at.x)];
    // The decode table's entries are the first 256 of `texels`.
    let r = bitcast<f32>(texels[packed & 0xffu]);
    let g = bitcast<f32>(texels[(packed >> 8u) & 0xffu]);
    let b = bitcast<f32>(texels[(packed >> 16u) & 0xffu]);
    return vec4<f32>(r, g, b, f32(packed >> 24u) / 255.0);
}

// `SrgbImage::bilinear`: the bilinear sample of image `t`'s colour and alpha at `uv`; v = 0 is
// the bottom.
fn image_sample(t: Texture, uv: vec2<f32>) -> vec4<f32> {
    let x = uv.x * f32(t.width) - 0.5;
    let y = (1.0 - uv.y) * f32(t.height) - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let i = i32(x0);
    let j = i32(y0);
    let top = lerp(texel(t, i, j), texel(t, i + 1, j), fx);
    let bottom = lerp(texel(t, i, j + 1), texel(t, i + 1, j + 1), fx);
    return lerp(top, bottom, fy);
}

// `Texture::color`: the colour of texture `index` at texture coordinates `uv`, or at
// `object_point` for solid textures.
fn texture_color(index: u32, uv: vec2<f32>, object_point: vec3<f32>) -> vec3<f32> {
    let t = textures[index];
    switch t.kind {
        case TEXTURE_CHECKER3D: {
            // The small bias keeps a surface on a cell boundary in one cell.
            let cell = floor(object_point / t.size + 1e-4);
            return alternate(t.a, t.b, parity(cell.x + cell.y + cell.z));
        }
        case TEXTURE_CHECKER_UV: {
            // The parity of a sum of whole numbers is that of their parities' sum.
            let squares = floor(uv * t.scale);
            return alternate(t.a, t.b, parity(parity(squares.x) + parity(squares.y)));
        }
        case TEXTURE_WOOD: {
            let angle = atan2(object_point.y, object_point.x);
            let radius = length(object_point.xy) / WOOD_RING_WIDTH;
            let ring = radius + WOOD_WOBBLE.x * sin(angle * WOOD_WOBBLE.y + WOOD_WOBBLE.z * object_point.z);
            return alternate(t.a, t.b, parity(floor(ring)));
        }
        case TEXTURE_MARBLE: {
            let stir = MARBLE_TURBULENCE.y * turbulence(MARBLE_TURBULENCE.x, object_point);
            let vein = sin(TAU * object_point.z + stir);
            return t.a * marble_spline(vein);
        }
        case TEXTURE_IMAGE, default: {
            return image_sample(t, uv * t.scale + t.offset).xyz;
        }
    }
}

// `Texture::alpha`: the alpha of texture `index` at texture coordinates `uv` (1 but in an
// image with an alpha channel).
fn texture_alpha(index: u32, uv: vec2<f32>) -> f32 {
    let t = textures[index];
    if t.kind != TEXTURE_IMAGE {
        return 1.0;
    }
    return image_sample(t, uv * t.scale + t.offset).w;
}
