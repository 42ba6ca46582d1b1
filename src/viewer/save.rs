//! Saving what the viewer shows: the image as a PNG, through the exposure and tone curve shown
//! (atomically, through the library's [`save_toned_pixels`]) and the camera as a `[camera]` snippet to paste into a scene file.

use std::io::Write;
use std::path::Path;

use raylab::camera::CameraSpec;
use raylab::film::Film;
use raylab::formats::camera_path;
use raylab::formats::image::save_toned_pixels;
use raylab::formats::toml::camera_table;
use raylab::output::write_atomically;
use raylab::tone::Tone;

/// The camera as a scene file's `[camera]` table. Numbers are written in full (Rust's shortest
/// round-tripping form), so reading the snippet back gives exactly this camera.
pub fn camera_snippet(spec: &CameraSpec) -> String {
    camera_table("camera", spec)
}

/// Saves the film at `path` (its extension picks the format; PNG and PPM through `tone`, as the
/// window shows it) and the camera beside it; returns a line saying what was written.
pub fn save_view(
    path: &Path,
    film: &Film,
    camera: &CameraSpec,
    tone: Tone,
) -> Result<String, String> {
    let pixel = |x, y| film.get(x, y);
    save_toned_pixels(path, film.width(), film.height(), &pixel, tone)
        .map_err(|e| e.to_string())?;
    let snippet_path = camera_path(path);
    let snippet = camera_snippet(camera);
    write_atomically(
        &snippet_path,
        |e| format!("{}: {e}", snippet_path.display()),
        |out| out.write_all(snippet.as_bytes()).map_err(|e| e.to_string()),
    )?;
    Ok(format!(
        "saved {} and {}",
        path.display(),
        snippet_path.display()
    ))
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use raylab::color::Color;

    use super::*;

    fn spec() -> CameraSpec {
        CameraSpec {
            eye: Vec3::new(0.1, -2.5, 1e-3),
            look_at: Vec3::new(1.0 / 3.0, 0.0, 7.0),
            up: Vec3::Y,
            view_angle: 47.25,
            near: 0.5,
        }
    }

    #[test]
    fn the_snippet_reads_back_as_the_same_camera() {
        let text = camera_snippet(&spec());
        let table: toml::Table = text.parse().unwrap();
        let camera = table["camera"].as_table().unwrap();
        let vector = |key: &str| {
            let a = camera[key].as_array().unwrap();
            Vec3::from_array([0, 1, 2].map(|i| a[i].as_float().unwrap() as f32))
        };
        assert_eq!(vector("eye"), spec().eye);
        assert_eq!(vector("look_at"), spec().look_at);
        assert_eq!(vector("up"), spec().up);
        assert_eq!(camera["view_angle"].as_float().unwrap() as f32, 47.25);
        assert_eq!(camera["near"].as_float().unwrap() as f32, 0.5);
    }

    #[test]
    fn saving_writes_the_png_and_the_snippet() {
        let dir = tempfile::tempdir().unwrap();
        let film = Film::new(3, 2);
        film.set(0, 0, Color::ONE);
        let path = dir.path().join("view.png");
        let message = save_view(&path, &film, &spec(), Tone::default()).unwrap();
        assert!(message.contains("view.png"), "{message}");
        let image = image::open(&path).unwrap().to_rgb8();
        assert_eq!(image.dimensions(), (3, 2));
        assert_eq!(image.get_pixel(0, 0).0, [255, 255, 255]);
        let snippet = std::fs::read_to_string(dir.path().join("view.camera.toml")).unwrap();
        assert_eq!(snippet, camera_snippet(&spec()));
    }

    #[test]
    fn saving_to_a_missing_folder_is_an_error() {
        let film = Film::new(1, 1);
        assert!(
            save_view(
                Path::new("/no/such/dir/x.png"),
                &film,
                &spec(),
                Tone::default()
            )
            .is_err()
        );
    }
}
