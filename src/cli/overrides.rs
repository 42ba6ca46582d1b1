//! The command-line flags that override a scene's render settings and camera, the same in
//! `render`, `inspect` and `view`; they become the library's [`SettingsOverrides`], which applies
//! them.

use clap::Args;
use glam::Vec3;
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
    /// Samples per pixel (more than 1 anti-aliases after block size 1); with --aa-threshold, the
    /// most a pixel takes. The viewer, given neither, refines a scene that asks for 1 up to 16
    /// with --aa-threshold 0.03.
    #[arg(long)]
    samples: Option<u32>,
    /// Adaptive anti-aliasing: only pixels whose colour differs from a neighbour's by more than
    /// this (0 to 1, e.g. 0.03) take more samples, up to --samples; 0 samples every pixel alike.
    #[arg(long, value_name = "T", value_parser = parse_number)]
    aa_threshold: Option<f32>,
    /// Steps along each ray through fog, each gathering the light the fog scatters into it.
    #[arg(long)]
    fog_steps: Option<u32>,
    /// Photons shot for caustics (light focused by mirrors and glass); 0 turns them off.
    #[arg(long)]
    caustic_photons: Option<u32>,
    /// Photons each caustic estimate gathers (1 to 512).
    #[arg(long)]
    caustic_gather: Option<u32>,
    /// Where the camera's eye is (instead of the scene's camera, or its NAME.camera.toml).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vector, allow_hyphen_values = true)]
    eye: Option<Vec3>,
    /// The point the camera looks at.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vector, allow_hyphen_values = true)]
    look_at: Option<Vec3>,
    /// Which way is up in the image.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vector, allow_hyphen_values = true)]
    up: Option<Vec3>,
    /// Vertical view angle in degrees (between 0 and 180).
    #[arg(long, value_name = "DEG", value_parser = parse_number, allow_hyphen_values = true)]
    view_angle: Option<f32>,
}

impl OverrideArgs {
    /// Takes `--look-at` out: for `inspect --draw`, where it is the observer's.
    pub fn take_look_at(&mut self) -> Option<Vec3> {
        self.look_at.take()
    }
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
            aa_threshold: args.aa_threshold,
            fog_steps: args.fog_steps,
            caustic_photons: args.caustic_photons,
            caustic_gather: args.caustic_gather,
            eye: args.eye,
            look_at: args.look_at,
            up: args.up,
            view_angle: args.view_angle,
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

/// A finite number.
pub fn parse_number(text: &str) -> Result<f32, String> {
    match text.trim().parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("`{text}` is not a finite number")),
    }
}

/// `X,Y,Z`: three finite numbers, spaces allowed around the commas.
pub fn parse_vector(text: &str) -> Result<Vec3, String> {
    let numbers: Vec<&str> = text.split(',').collect();
    let [x, y, z] = numbers[..] else {
        return Err(format!(
            "`{text}` is not a point or vector (use X,Y,Z, e.g. 0,1.5,-4)"
        ));
    };
    Ok(Vec3::new(
        parse_number(x)?,
        parse_number(y)?,
        parse_number(z)?,
    ))
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
    fn vectors_are_three_finite_numbers() {
        assert_eq!(parse_vector("1,-2.5,3e1"), Ok(Vec3::new(1.0, -2.5, 30.0)));
        assert_eq!(parse_vector("1, 2,  3"), Ok(Vec3::new(1.0, 2.0, 3.0)));
        assert!(parse_vector("1,2").unwrap_err().contains("X,Y,Z"));
        assert!(parse_vector("1,2,3,4").unwrap_err().contains("X,Y,Z"));
        assert!(parse_vector("1,nan,3").unwrap_err().contains("`nan`"));
        assert!(parse_vector("1,2,inf").unwrap_err().contains("finite"));
        assert!(parse_number("NaN").is_err());
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
