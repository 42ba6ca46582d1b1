//! Texture upload: copies the film into the GPU texture, at most once per frame and only when the
//! film's [`version`](raylab::film::Film::version) says its pixels changed, in one write of the
//! whole image. The texture holds the film's linear floats unchanged ([`texel`]); the quad's
//! shader applies exposure, tone curve and sRGB encoding.

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

    /// The film as texels of [`IMAGE_FORMAT`](super::quad::IMAGE_FORMAT), row 0 at the top, if it changed since the last call; the
    /// caller writes them to the texture. Returns the version they show.
    pub fn changed_pixels(&mut self, film: &Arc<Film>) -> Option<&[u8]> {
        if !self.is_stale(film) {
            return None;
        }
        // Read the version first: pixels written later may be included, never missed.
        let version = film.version();
        let (w, h) = (film.width(), film.height());
        self.bytes.resize(w as usize * h as usize * TEXEL_BYTES, 0);
        for (i, out) in self.bytes.chunks_exact_mut(TEXEL_BYTES).enumerate() {
            texel(film.get(i as u32 % w, i as u32 / w), out);
        }
        self.uploaded = Some((film.clone(), version));
        Some(&self.bytes)
    }
}

/// Writes rows of texels (from [`texel`]) into the whole of `texture`.
pub fn write_texture(queue: &wgpu::Queue, texture: &wgpu::Texture, rgba: &[u8]) {
    let size = texture.size();
    queue.write_texture(
        texture.as_image_copy(),
        rgba,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(size.width * TEXEL_BYTES as u32),
            rows_per_image: Some(size.height),
        },
        size,
    );
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
        assert_eq!(uploader.changed_pixels(&film), Some(&expected[..]));
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
}
