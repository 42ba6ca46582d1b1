//! Render settings: image size, the ray tree's limits, progressive refinement and the switches
//! that turn parts of the shading off (for teaching and for the viewer).

use crate::color::Color;

/// Largest starting block size.
pub const MAX_BLOCK_SIZE: u32 = 64;
/// Largest image side, to keep an absurd setting from allocating gigabytes.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// Deepest ray tree allowed.
pub const MAX_DEPTH_LIMIT: u32 = 64;
/// Most samples per pixel.
pub const MAX_SAMPLES: u32 = 4096;

#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Deepest level of the ray tree; the eye ray is depth 1.
    pub max_depth: u32,
    /// Adaptive depth control: a branch whose weight (product of the reflection and transmission
    /// coefficients from the eye) falls below this is not traced. 0 turns it off.
    pub min_weight: f32,
    /// Starting block size of progressive refinement: a power of two from 1 to 64.
    pub block_size: u32,
    /// Samples per pixel; more than 1 adds jittered samples after the block size 1 pass.
    pub samples: u32,
    pub background: Color,
    /// Global ambient light.
    pub ambient: Color,
    pub shadows: bool,
    pub reflections: bool,
    /// Whether transmitted rays are traced (through transparent objects, `kt > 0`).
    pub transmission: bool,
    pub textures: bool,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            width: 640,
            height: 480,
            max_depth: 5,
            min_weight: 0.01,
            block_size: 16,
            samples: 1,
            background: Color::new(0.05, 0.05, 0.08),
            ambient: Color::splat(0.2),
            shadows: true,
            reflections: true,
            transmission: true,
            textures: true,
        }
    }
}

impl RenderSettings {
    /// Checks every setting; the message says what is wrong and what is allowed.
    pub fn validate(&self) -> Result<(), String> {
        if self.width == 0 || self.height == 0 {
            return Err(format!(
                "image size must be at least 1×1, got {}×{}",
                self.width, self.height
            ));
        }
        if self.width > MAX_IMAGE_SIDE || self.height > MAX_IMAGE_SIDE {
            return Err(format!(
                "image sides must be at most {MAX_IMAGE_SIDE}, got {}×{}",
                self.width, self.height
            ));
        }
        if self.max_depth == 0 || self.max_depth > MAX_DEPTH_LIMIT {
            return Err(format!(
                "max_depth must be between 1 and {MAX_DEPTH_LIMIT}, got {}",
                self.max_depth
            ));
        }
        if !(0.0..=1.0).contains(&self.min_weight) {
            return Err(format!(
                "min_weight must be between 0 and 1, got {}",
                self.min_weight
            ));
        }
        if !self.block_size.is_power_of_two() || self.block_size > MAX_BLOCK_SIZE {
            return Err(format!(
                "block_size must be a power of two from 1 to {MAX_BLOCK_SIZE}, got {}",
                self.block_size
            ));
        }
        if self.samples == 0 || self.samples > MAX_SAMPLES {
            return Err(format!(
                "samples must be between 1 and {MAX_SAMPLES}, got {}",
                self.samples
            ));
        }
        Ok(())
    }
}
