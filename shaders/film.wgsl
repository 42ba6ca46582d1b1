// The film on the GPU, the twin of src/film.rs: each pixel's mean colour and the number of
// samples averaged into it. `add_samples` puts the colours the tracer gave a list of samples
// into it as `Film::fill_block` and `Film::add_sample` do, and counts their rays (the sweep in
// src/progressive/gpu.rs); `show_rows` makes rows of it the bytes the display shows, through
// the exposure and tone curve of src/tone.rs and the sRGB table of `SrgbEncoder`
// (src/color.rs), into a buffer the viewer copies into the texture its quad samples.

// A pixel: `Film::get` and `Film::samples`.
struct FilmPixel {
    color: vec3<f32>,
    samples: u32,
}

// The film's size and the pass the samples belong to (its block side).
struct FilmPass {
    width: u32,
    height: u32,
    step: u32,
    pad: u32,
}

// The rays of the samples of one list, added up (`RayCounts`), and how many samples the driver
// cut short: their places in the list are `cut[0 .. cut_short]`.
struct Tally {
    primary: atomic<u32>,
    primary_hits: atomic<u32>,
    shadow: atomic<u32>,
    reflected: atomic<u32>,
    transmitted: atomic<u32>,
    over_budget: atomic<u32>,
    cut_short: atomic<u32>,
    from_item_buffer: atomic<u32>,
}

// Rows `first_row .. first_row + rows` of the film as shown: `Tone::map` of each pixel, with
// `scale` the exposure's factor (`Tone::scale`) and `curve` the tone curve (0 clamp, 1
// Reinhard, 2 filmic), one texel per pixel in rows of `row_texels`.
struct ShowRows {
    width: u32,
    first_row: u32,
    rows: u32,
    row_texels: u32,
    scale: f32,
    curve: u32,
    pad0: u32,
    pad1: u32,
}

@group(0) @binding(FILM_SAMPLES) var<storage, read> samples: array<PixelSample>;
@group(0) @binding(FILM_COLORS) var<storage, read> colors: array<SampleColor>;
@group(0) @binding(FILM_PIXELS) var<storage, read_write> pixels: array<FilmPixel>;
@group(0) @binding(FILM_TALLY) var<storage, read_write> tally: Tally;
@group(0) @binding(FILM_CUT) var<storage, read_write> cut: array<u32>;
@group(0) @binding(FILM_FILM_PASS) var<storage, read> film_pass: FilmPass;

@group(0) @binding(FILM_TEXELS) var<storage, read_write> texels: array<u32>;
@group(0) @binding(FILM_SRGB_TABLE) var<storage, read> srgb_table: array<vec2<u32>>;
@group(0) @binding(FILM_SHOW) var<storage, read> show: ShowRows;

fn same_pixel(a: PixelSample, b: PixelSample) -> bool {
    return a.x == b.x && a.y == b.y;
}

// `Film::fill_block` for sample 0 of a pixel of the pass's grid, `Film::add_sample` for the
// others.
fn put_sample(s: PixelSample, color: vec3<f32>) {
    let width = film_pass.width;
    if s.k == 0u {
        let x_end = min(s.x + film_pass.step, width);
        let y_end = min(s.y + film_pass.step, film_pass.height);
        for (var y = s.y; y < y_end; y++) {
            for (var x = s.x; x < x_end; x++) {
                pixels[y * width + x] = FilmPixel(color, 0u);
            }
        }
        pixels[s.y * width + s.x].samples = 1u;
    } else {
        let p = s.y * width + s.x;
        let old = pixels[p];
        let n = old.samples;
        pixels[p] = FilmPixel(old.color + (color - old.color) / f32(n + 1u), n + 1u);
    }
}

// Counts each sample's rays, lists those cut short, and puts the others into the film. A
// pixel's samples lie next to each other in the list, in the order the CPU adds them: the
// invocation of a pixel's first sample adds them all, so no two invocations write a pixel.
@compute @workgroup_size(WORKGROUP)
fn add_samples(@builtin(global_invocation_id) id: vec3<u32>) {
    let n = arrayLength(&samples);
    let i = id.x;
    if i >= n {
        return;
    }
    let c = colors[i];
    if c.cut_short != 0u {
        cut[atomicAdd(&tally.cut_short, 1u)] = i;
    } else {
        atomicAdd(&tally.primary, 1u);
        atomicAdd(&tally.primary_hits, c.primary_hits);
        atomicAdd(&tally.shadow, c.shadow);
        atomicAdd(&tally.reflected, c.reflected);
        atomicAdd(&tally.transmitted, c.transmitted);
        atomicAdd(&tally.over_budget, c.over_budget);
        atomicAdd(&tally.from_item_buffer, c.from_item_buffer);
    }
    let s = samples[i];
    if i > 0u && same_pixel(samples[i - 1u], s) {
        return;
    }
    for (var j = i; j < n && same_pixel(samples[j], s); j++) {
        if colors[j].cut_short == 0u {
            put_sample(samples[j], colors[j].color);
        }
    }
}

fn is_nan(v: f32) -> bool {
    return (bitcast<u32>(v) & 0x7fffffffu) > 0x7f800000u;
}

// `ToneCurve::apply`.
fn tone_curve(curve: u32, v: f32) -> f32 {
    var x = 0.0;
    if !is_nan(v) {
        x = clamp(v, 0.0, CURVE_INPUT_MAX);
    }
    switch curve {
        case CURVE_REINHARD: {
            return x / (1.0 + x);
        }
        case CURVE_FILMIC: {
            return min((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 1.0);
        }
        case CURVE_CLAMP, default: {
            return min(x, 1.0);
        }
    }
}

// `SrgbEncoder::encode`: the table's byte for the value's bucket, one more from its step on.
fn srgb_byte(v: f32) -> u32 {
    if is_nan(v) || v <= 0.0 {
        return 0u;
    }
    if v >= 1.0 {
        return 255u;
    }
    let bucket = srgb_table[bitcast<u32>(v) >> SRGB_BUCKET_SHIFT];
    return bucket.x + u32(v >= bitcast<f32>(bucket.y));
}

// One texel of the shown rows: red, green, blue and an opaque alpha, a byte each in that order.
@compute @workgroup_size(WORKGROUP)
fn show_rows(@builtin(global_invocation_id) id: vec3<u32>) {
    let x = id.x;
    let y = show.first_row + id.y;
    if x >= show.width || id.y >= show.rows {
        return;
    }
    let c = pixels[y * show.width + x].color;
    var texel = 0xff000000u;
    for (var channel = 0u; channel < 3u; channel++) {
        texel |= srgb_byte(tone_curve(show.curve, c[channel] * show.scale)) << (8u * channel);
    }
    texels[y * show.row_texels + x] = texel;
}
