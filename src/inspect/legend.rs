//! The scales of the debug views: the heat-map colour ramp ([`heat`]), the [`Legend`] that
//! explains a view's colours (a sampled colour bar and labelled ticks), and the scene's depth
//! range for the depth view.

use glam::Vec3;

use crate::color::Color;
use crate::color::srgb_to_linear;
use crate::whitted::Tracer;

/// Colours sampled along a legend's bar.
const BAR_SAMPLES: usize = 64;

/// The BVH cost the heat map's top stands for (nodes plus primitives per pixel, log scale).
pub const BVH_COST_MAX: f32 = 4096.0;

/// The inferno ramp's colours at 0, ¼, ½, ¾ and 1 (sRGB), after matplotlib's.
const INFERNO: [[f32; 3]; 5] = [
    [0.001, 0.000, 0.014],
    [0.258, 0.039, 0.406],
    [0.578, 0.148, 0.404],
    [0.865, 0.317, 0.226],
    [0.988, 0.998, 0.645],
];

/// The heat-map colour (linear RGB) of `value01` in [0, 1], dark purple to light yellow
/// (clamped outside).
pub fn heat(value01: f32) -> Color {
    let x = if value01.is_nan() {
        0.0
    } else {
        value01.clamp(0.0, 1.0)
    };
    let scaled = x * (INFERNO.len() - 1) as f32;
    let i = (scaled as usize).min(INFERNO.len() - 2);
    let f = scaled - i as f32;
    let (a, b) = (Color::from(INFERNO[i]), Color::from(INFERNO[i + 1]));
    (a + (b - a) * f).map(srgb_to_linear)
}

/// The grey of the depth view for `value01` in [0, 1]: white near, black far.
pub fn depth_grey(value01: f32) -> Color {
    Color::splat(1.0 - value01.clamp(0.0, 1.0))
}

/// What a view's colours mean: a colour bar from low to high and labelled ticks along it.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    pub label: String,
    /// (position along the bar in [0, 1], label).
    pub ticks: Vec<(f32, String)>,
    /// The bar, sampled from low to high (linear RGB).
    pub colors: Vec<Color>,
}

impl Legend {
    /// The depth view's grey bar over `(near, far)`.
    pub fn depth((near, far): (f32, f32)) -> Legend {
        Legend {
            label: "depth: distance along the view direction".into(),
            ticks: [0.0, 0.5, 1.0]
                .map(|p| (p, format!("{:.3}", near + (far - near) * p)))
                .into(),
            colors: bar(depth_grey),
        }
    }

    /// Tree depth 1 ..= `max_depth`, one tick per level (at most about eight).
    pub fn tree_depth(max_depth: u32) -> Legend {
        let top = max_depth.max(2) - 1;
        let step = top.div_ceil(8).max(1) as usize;
        Legend {
            label: "ray-tree depth reached".into(),
            ticks: (1..=max_depth)
                .step_by(step)
                .map(|d| (tree_depth_position(d, max_depth), d.to_string()))
                .collect(),
            colors: bar(heat),
        }
    }

    /// Rays per pixel, log scale from 1 to `max_rays`.
    pub fn ray_count(max_rays: u64) -> Legend {
        Legend {
            label: "rays traced per pixel (log scale)".into(),
            ticks: log_ticks(max_rays as f32),
            colors: bar(heat),
        }
    }

    /// BVH nodes plus primitives tested per pixel, log scale from 1 to [`BVH_COST_MAX`].
    pub fn bvh_cost() -> Legend {
        Legend {
            label: "BVH nodes visited + primitives tested per pixel (log scale)".into(),
            ticks: log_ticks(BVH_COST_MAX),
            colors: bar(heat),
        }
    }

    /// The bar as a `width × height` image (row-major, top row first): the colours in the top
    /// three quarters, white tick marks on black below.
    pub fn bar_image(&self, width: u32, height: u32) -> Vec<Color> {
        let bar_rows = height - height / 4;
        let last = (width.max(2) - 1) as f32;
        let tick_columns: Vec<u32> = self
            .ticks
            .iter()
            .map(|(p, _)| (p.clamp(0.0, 1.0) * last).round() as u32)
            .collect();
        let mut pixels = Vec::with_capacity((width * height) as usize);
        for y in 0..height {
            for x in 0..width {
                pixels.push(if y < bar_rows {
                    let i = (x as f32 / last * (self.colors.len() - 1) as f32).round();
                    self.colors[i as usize]
                } else if tick_columns.contains(&x) {
                    Color::ONE
                } else {
                    Color::ZERO
                });
            }
        }
        pixels
    }

    /// One line: the label and the ticks, as the CLI prints it.
    pub fn to_text(&self) -> String {
        let ticks: Vec<String> = self
            .ticks
            .iter()
            .map(|(p, label)| format!("{p:.2}={label}"))
            .collect();
        format!("{}: {}", self.label, ticks.join(" "))
    }
}

/// The position of tree depth `depth` on a bar over 1 ..= `max_depth`.
pub fn tree_depth_position(depth: u32, max_depth: u32) -> f32 {
    if max_depth <= 1 {
        return 1.0;
    }
    (depth.saturating_sub(1)) as f32 / (max_depth - 1) as f32
}

/// The position of `value` ≥ 1 on a log-scale bar from 1 to `max`.
pub fn log_position(value: f32, max: f32) -> f32 {
    if max <= 1.0 {
        return 1.0;
    }
    value.max(1.0).ln() / max.ln()
}

/// Ticks at 1, `max` and the powers of 4 (or 16, 256, … when there are many) between them.
fn log_ticks(max: f32) -> Vec<(f32, String)> {
    let mut base = 4.0f32;
    while max.log(base) > 6.0 {
        base *= base;
    }
    let mut ticks = Vec::new();
    let mut value = 1.0f32;
    while value < max {
        ticks.push((log_position(value, max), format!("{value}")));
        value *= base;
    }
    ticks.push((1.0, format!("{max}")));
    ticks
}

/// The heat ramp sampled along a legend's bar.
pub fn heat_bar() -> Vec<Color> {
    bar(heat)
}

fn bar(ramp: fn(f32) -> Color) -> Vec<Color> {
    (0..BAR_SAMPLES)
        .map(|i| ramp(i as f32 / (BAR_SAMPLES - 1) as f32))
        .collect()
}

/// The depth view's range: the distances along the view direction (from the eye) of the nearest
/// and farthest corners of the BVH's root box (around the scene's bounded primitives), the
/// nearest no closer than the image plane. Scenes with only unbounded primitives (planes) get
/// the image plane to twice the distance to the look-at point.
pub fn depth_range(tracer: &Tracer) -> (f32, f32) {
    let camera = &tracer.scene.camera;
    let to_look_at = (camera.spec.look_at - camera.eye).length();
    let fallback = (camera.near, 2.0 * to_look_at.max(camera.near));
    let Some(bounds) = tracer.bvh.bounds() else {
        return fallback;
    };
    let depth = |p: Vec3| (p - camera.eye).dot(-camera.n);
    let corners = bounds.corners();
    let far = corners
        .map(depth)
        .into_iter()
        .fold(f32::NEG_INFINITY, f32::max);
    let near = corners
        .map(depth)
        .into_iter()
        .fold(far, f32::min)
        .max(camera.near);
    if far > near { (near, far) } else { fallback }
}
