//! The command-line flags that override a scene's render settings, the same in `render`,
//! `inspect` and `view`; they become the library's [`SettingsOverrides`], which applies them.

use clap::Args;
use raylab::settings::SettingsOverrides;

/// Overrides of the scene's render settings.
#[derive(Args, Clone, Copy, Debug, Default)]
pub struct OverrideArgs {
    /// Image width in pixels (the scene's height stays unless --height is given).
    #[arg(long)]
    width: Option<u32>,
    /// Image height in pixels (the scene's width stays unless --width is given).
    #[arg(long)]
    height: Option<u32>,
    /// Image size: N for N×N, or WIDTHxHEIGHT; instead of --width and --height (giving both is
    /// an error).
    #[arg(long, value_name = "N|WxH", value_parser = parse_size, conflicts_with_all = ["width", "height"])]
    size: Option<(u32, u32)>,
    /// Deepest level of the ray tree (the eye ray is depth 1).
    #[arg(long)]
    max_depth: Option<u32>,
    /// Adaptive depth control: skip branches whose weight is below this (0 = off).
    #[arg(long)]
    min_weight: Option<f32>,
    /// Starting block size of progressive refinement (power of two, 1 to 64).
    #[arg(long)]
    block_size: Option<u32>,
    /// Samples per pixel (more than 1 anti-aliases after block size 1).
    #[arg(long)]
    samples: Option<u32>,
}

impl From<OverrideArgs> for SettingsOverrides {
    /// `--size` gives both the width and the height.
    fn from(args: OverrideArgs) -> SettingsOverrides {
        let (width, height) = match args.size {
            Some((width, height)) => (Some(width), Some(height)),
            None => (args.width, args.height),
        };
        SettingsOverrides {
            width,
            height,
            max_depth: args.max_depth,
            min_weight: args.min_weight,
            block_size: args.block_size,
            samples: args.samples,
        }
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
    fn size_gives_both_sides_and_width_or_height_one() {
        let sized = OverrideArgs {
            size: Some((64, 48)),
            ..OverrideArgs::default()
        };
        let overrides = SettingsOverrides::from(sized);
        assert_eq!((overrides.width, overrides.height), (Some(64), Some(48)));
        let wide = OverrideArgs {
            width: Some(100),
            ..OverrideArgs::default()
        };
        let overrides = SettingsOverrides::from(wide);
        assert_eq!((overrides.width, overrides.height), (Some(100), None));
    }
}
