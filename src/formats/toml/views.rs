//! The views file beside a scene, `NAME.views.toml`: the viewer's bookmarked cameras
//! ([`Views`]), each a `[view.N]` table (N from 1 to 9) with the keys of the scene file's
//! `[camera]` table. [`views_text`] writes one, [`load_views`] and [`parse_views`] read it back,
//! with errors at the file's line and column.
//!
//! ```toml
//! [view.1]
//! eye = [0.0, 1.5, 6.0]
//! look_at = [0.0, 0.5, 0.0]
//! up = [0.0, 1.0, 0.0]
//! view_angle = 45.0
//! near = 1.0
//! ```

use std::path::Path;

use serde::Deserialize;

use super::build::build_camera;
use super::file::ViewsFile;
use super::load::parse_toml;
use crate::camera::CameraSpec;
use crate::formats::{SceneError, Source, utf8_text};
use crate::views::{VIEW_NUMBERS, Views};

/// The camera as a TOML table headed `[name]`, every key written. Numbers are written in full
/// (Rust's shortest round-tripping form), so reading the table back gives exactly this camera.
pub fn camera_table(name: &str, spec: &CameraSpec) -> String {
    let v = |v: glam::Vec3| format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z);
    format!(
        "[{name}]\neye = {}\nlook_at = {}\nup = {}\nview_angle = {:?}\nnear = {:?}\n",
        v(spec.eye),
        v(spec.look_at),
        v(spec.up),
        spec.view_angle,
        spec.near
    )
}

/// The text of a views file holding `views`, one `[view.N]` table each, in order.
pub fn views_text(views: &Views) -> String {
    let mut text = String::from(
        "# raylab's views of the scene beside this file: Ctrl+1…9 in the viewer stores the\n\
         # camera as view 1…9, the keys 1…9 recall it.\n",
    );
    for (number, camera) in views.iter() {
        text += "\n";
        text += &camera_table(&format!("view.{number}"), &camera);
    }
    text
}

/// Reads the views file at `path`; the keys a view leaves out are `base`'s.
pub fn load_views(path: &Path, base: CameraSpec) -> Result<Views, SceneError> {
    let bytes = crate::memory::read_file(path)
        .map_err(|e| SceneError::whole_file(path, format!("cannot read the views file: {e}")))?;
    parse_views(utf8_text(&bytes, path)?, path, base)
}

/// Reads a views file from `text`; `origin` names it in error messages, and the keys a view
/// leaves out are `base`'s.
pub fn parse_views(text: &str, origin: &Path, base: CameraSpec) -> Result<Views, SceneError> {
    let source = Source { origin, text };
    let document = parse_toml(source)?;
    let file = ViewsFile::deserialize(toml::de::Deserializer::from(document))
        .map_err(|e| source.toml_error(&e))?;
    let mut views = Views::default();
    for (number, camera) in file.view {
        let bad_number = || {
            source.error(
                number.span(),
                format!(
                    "views are numbered {} to {}, got `{}`",
                    VIEW_NUMBERS.start(),
                    VIEW_NUMBERS.end(),
                    number.get_ref()
                ),
            )
        };
        let n = number
            .get_ref()
            .parse::<u8>()
            .ok()
            .filter(|n| VIEW_NUMBERS.contains(n))
            .ok_or_else(bad_number)?;
        let camera = build_camera(Some(camera), base, source)?;
        views.set(n, camera.spec).map_err(|_| bad_number())?;
    }
    Ok(views)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn views() -> Views {
        let mut views = Views::default();
        views
            .set(
                3,
                CameraSpec {
                    eye: Vec3::new(0.1, -2.5, 1e-3),
                    look_at: Vec3::new(1.0 / 3.0, 0.0, 7.0),
                    up: Vec3::new(0.0, 1.0, 0.2),
                    view_angle: 47.25,
                    near: 0.5,
                },
            )
            .unwrap();
        views.set(1, CameraSpec::default()).unwrap();
        views
    }

    fn parse(text: &str) -> Result<Views, SceneError> {
        parse_views(text, Path::new("room.views.toml"), CameraSpec::default())
    }

    #[test]
    fn a_views_file_reads_back_as_the_same_views() {
        let text = views_text(&views());
        assert!(
            text.contains("[view.1]") && text.contains("[view.3]"),
            "{text}"
        );
        assert!(text.find("[view.1]") < text.find("[view.3]"));
        assert_eq!(parse(&text).unwrap(), views());
        assert_eq!(parse("").unwrap(), Views::default());
    }

    #[test]
    fn keys_left_out_are_the_base_cameras() {
        let views = parse("[view.2]\neye = [0, 0, 9]\n").unwrap();
        let expected = CameraSpec {
            eye: Vec3::new(0.0, 0.0, 9.0),
            ..CameraSpec::default()
        };
        assert_eq!(views.get(2), Some(expected));
    }

    #[test]
    fn errors_are_at_their_line_and_column() {
        for (text, expected) in [
            (
                "[view.0]\n",
                "room.views.toml:1:7: views are numbered 1 to 9, got `0`",
            ),
            (
                "[view.x1]\n",
                "room.views.toml:1:7: views are numbered 1 to 9, got `x1`",
            ),
            (
                "[view.1]\neye = [0, 0]\n",
                "room.views.toml:2:7: expected 3 values, got 2",
            ),
            (
                "[view.1]\neye = [0, 0, 0]\n",
                "room.views.toml:2:7: the eye and the look-at point coincide",
            ),
            (
                "[view.1]\nfov = 3\n",
                "room.views.toml:2:1: unknown field `fov`",
            ),
            ("[views.1]\n", "room.views.toml:1:2: unknown field `views`"),
            ("[view.1\n", "room.views.toml:1:"),
            ("view = 3\n", "room.views.toml:1:8:"),
        ] {
            let error = parse(text).unwrap_err().to_string();
            assert!(error.starts_with(expected), "{text:?}: {error}");
        }
    }
}
