//! Texture upload: copies the film into the GPU texture, at most once per frame and only when the
//! film's [`version`](raylab::film::Film::version) says its pixels changed, and then only the
//! rows the film says changed ([`Film::take_changed_rows`]), one write per run of rows (the
//! whole image for a new film or texture). The texture holds the film's linear floats unchanged ([`texel`]); the quad's
//! shader applies exposure, tone curve and sRGB encoding.

use std::ops::Range;
use std::sync::Arc;

use raylab::color::Color;
use raylab::film::Film;

/// Bytes of one texel of [`IMAGE_FORMAT`](super::quad::IMAGE_FORMAT): four floats.
pub const TEXEL_BYTES: usize = 16;

/// One film pixel as its texel of [`IMAGE_FORMAT`](super::quad::IMAGE_FORMAT): the linear colour and an opaque alpha.
pub fn texel(c: Color, out: &mut [u8]) {
    for (bytes, v) in out.chunks_exact_mut(4).zip([c.x, c.y, c.z, 1.0]) {
        bytes.copy_from_slice(&v.to_ne_bytes());
    }
}

/// Keeps the texture in step with a film.
pub struct Uploader {
    /// The film last uploaded and its version then.
    uploaded: Option<(Arc<Film>, u64)>,
    bytes: Vec<u8>,
}

impl Uploader {
    pub fn new() -> Uploader {
        Uploader {
            uploaded: None,
            bytes: Vec::new(),
        }
    }

    /// Whether `film` has pixels the texture does not show yet.
    pub fn is_stale(&self, film: &Arc<Film>) -> bool {
        match &self.uploaded {
            Some((last, version)) => !Arc::ptr_eq(last, film) || *version != film.version(),
            None => true,
        }
    }

    /// Forgets what was uploaded (the texture was recreated).
    pub fn invalidate(&mut self) {
        self.uploaded = None;
    }

    /// The film as texels of [`IMAGE_FORMAT`](super::quad::IMAGE_FORMAT), row 0 at the top,
    /// with the runs of rows that changed since the last call (all of them for a film not
    /// uploaded before), if any did; the caller writes those rows to the texture
    /// ([`write_rows`]).
    pub fn changed_pixels(&mut self, film: &Arc<Film>) -> Option<(&[u8], Vec<Range<u32>>)> {
        if !self.is_stale(film) {
            return None;
        }
        // Read the version and take the rows first: pixels written later may be included, never
        // missed.
        let version = film.version();
        let changed = film.take_changed_rows();
        let (w, h) = (film.width() as usize, film.height());
        let rows = match &self.uploaded {
            Some((last, _)) if Arc::ptr_eq(last, film) => changed,
            _ => std::iter::once(0..h).collect(),
        };
        self.bytes.resize(w * h as usize * TEXEL_BYTES, 0);
        let row_bytes = w * TEXEL_BYTES;
        for y in rows.iter().flat_map(|run| run.clone()) {
            let row = &mut self.bytes[y as usize * row_bytes..(y as usize + 1) * row_bytes];
            for (x, out) in row.chunks_exact_mut(TEXEL_BYTES).enumerate() {
                texel(film.get(x as u32, y), out);
            }
        }
        self.uploaded = Some((film.clone(), version));
        Some((&self.bytes, rows))
    }
}

/// Writes the runs of rows `rows` of the whole image `texels` (rows of the texture's width, row
/// 0 at the top) into `texture`.
pub fn write_rows(
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    texels: &[u8],
    rows: &[Range<u32>],
) {
    let width = texture.width();
    let row_bytes = texels.len() / texture.height().max(1) as usize;
    for run in rows {
        let data = &texels[run.start as usize * row_bytes..run.end as usize * row_bytes];
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                origin: wgpu::Origin3d {
                    x: 0,
                    y: run.start,
                    z: 0,
                },
                ..texture.as_image_copy()
            },
            data,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row_bytes as u32),
                rows_per_image: Some(run.len() as u32),
            },
            wgpu::Extent3d {
                width,
                height: run.len() as u32,
                depth_or_array_layers: 1,
            },
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_are_given_once_per_change() {
        let film = Arc::new(Film::new(2, 1));
        film.set(1, 0, Color::ONE);
        film.touch();
        let mut uploader = Uploader::new();
        let mut expected = [0; 2 * TEXEL_BYTES];
        texel(Color::ZERO, &mut expected[..TEXEL_BYTES]);
        texel(Color::ONE, &mut expected[TEXEL_BYTES..]);
        assert_eq!(
            uploader.changed_pixels(&film),
            Some((&expected[..], std::iter::once(0..1).collect()))
        );
        let floats: Vec<f32> = expected
            .chunks_exact(4)
            .map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        assert_eq!(floats, [0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(uploader.changed_pixels(&film), None);
        film.touch();
        assert!(uploader.changed_pixels(&film).is_some());
        let other = Arc::new(Film::new(2, 1));
        assert!(uploader.is_stale(&other));
        uploader.invalidate();
        assert!(uploader.is_stale(&film));
    }

    #[test]
    fn only_the_changed_rows_are_converted_and_given() {
        let film = Arc::new(Film::new(1, 4));
        let mut uploader = Uploader::new();
        film.touch_rows(1..2);
        // A film not uploaded before goes up whole.
        let (_, rows) = uploader.changed_pixels(&film).unwrap();
        assert_eq!(rows, std::iter::once(0..4).collect::<Vec<_>>());
        // Row 3 is written but not marked: it is not converted.
        film.set(0, 2, Color::ONE);
        film.set(0, 3, Color::ONE);
        film.touch_rows(2..3);
        let (bytes, rows) = uploader.changed_pixels(&film).unwrap();
        assert_eq!(rows, std::iter::once(2..3).collect::<Vec<_>>());
        let (mut one, mut zero) = ([0; TEXEL_BYTES], [0; TEXEL_BYTES]);
        texel(Color::ONE, &mut one);
        texel(Color::ZERO, &mut zero);
        assert_eq!(bytes[2 * TEXEL_BYTES..3 * TEXEL_BYTES], one);
        assert_eq!(bytes[3 * TEXEL_BYTES..], zero, "row 3 is as first uploaded");
    }
}
