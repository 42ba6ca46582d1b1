//! The render settings that `render`, `inspect` and `view` let the command line override, with
//! the same flags in each, and the one function that applies them to a scene's settings.

use clap::Args;
use raylab::settings::RenderSettings;

/// Overrides of the scene's render settings.
#[derive(Args, Debug, Default)]
pub struct SettingsOverrides {
    /// Image width in pixels.
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels.
    #[arg(long)]
    height: Option<u32>,
    /// Image size: N for N×N, or WIDTHxHEIGHT; instead of --width and --height (giving both is
    /// an error).
    #[arg(long, value_name = "N|WxH", value_parser = parse_size, conflicts_with_all = ["width", "height"])]
    size: Option<(u32, u32)>,
    /// Deepest level of the ray tree (the eye ray is depth 1).
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// Adaptive depth control: skip branches whose weight is below this (0 = off). Not in the
    /// viewer, which has it in its Tracing panel.
    #[arg(long)]
    pub min_weight: Option<f32>,
    /// Starting block size of progressive refinement (power of two, 1 to 64).
    #[arg(long)]
    pub block_size: Option<u32>,
    /// Samples per pixel (more than 1 anti-aliases after block size 1).
    #[arg(long)]
    pub samples: Option<u32>,
}

impl SettingsOverrides {
    /// The image width and height asked for, each `None` where the scene's stays.
    pub fn size(&self) -> (Option<u32>, Option<u32>) {
        match self.size {
            Some((width, height)) => (Some(width), Some(height)),
            None => (self.width, self.height),
        }
    }

    /// Applies the overrides to `settings` and checks the result.
    pub fn apply(&self, settings: &mut RenderSettings) -> Result<(), String> {
        let s = settings;
        let (width, height) = self.size();
        s.width = width.unwrap_or(s.width);
        s.height = height.unwrap_or(s.height);
        s.max_depth = self.max_depth.unwrap_or(s.max_depth);
        s.min_weight = self.min_weight.unwrap_or(s.min_weight);
        s.block_size = self.block_size.unwrap_or(s.block_size);
        s.samples = self.samples.unwrap_or(s.samples);
        s.validate()
    }
}

/// `N` or `WxH` (also `W×H`), each side at least 1.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let side = |s: &str| match s.trim().parse::<u32>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "`{s}` is not a size (use N or WIDTHxHEIGHT, e.g. 512 or 640x480)"
        )),
    };
    match text.split_once(['x', 'X', '×']) {
        Some((w, h)) => Ok((side(w)?, side(h)?)),
        None => side(text).map(|n| (n, n)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_n_or_w_by_h() {
        assert_eq!(parse_size("512"), Ok((512, 512)));
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("640×480"), Ok((640, 480)));
        assert!(parse_size("0").is_err());
        assert!(parse_size("12xq").unwrap_err().contains("`q`"));
    }

    #[test]
    fn size_sets_both_sides_and_width_or_height_one() {
        let mut settings = RenderSettings::default();
        let square = SettingsOverrides {
            size: Some((64, 64)),
            ..SettingsOverrides::default()
        };
        square.apply(&mut settings).unwrap();
        assert_eq!((settings.width, settings.height), (64, 64));
        let wide = SettingsOverrides {
            width: Some(100),
            ..SettingsOverrides::default()
        };
        wide.apply(&mut settings).unwrap();
        assert_eq!((settings.width, settings.height), (100, 64));
    }
}
