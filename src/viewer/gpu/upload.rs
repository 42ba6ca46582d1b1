//! Texture upload: copies the film into the GPU texture, at most once per frame and only when the
//! film's [`version`](raylab::film::Film::version) says its pixels changed, in one write of the
//! whole image. Linear floats become sRGB bytes through a table indexed by the float's top bits,
//! which gives exactly the library's conversion without a `powf` per channel.

use std::sync::Arc;

use raylab::color::srgb8 as srgb_byte;
use raylab::film::Film;

/// Bucket of a linear value in [0, 1): its bit pattern without the lowest bits. Each bucket is
/// 1/128 of an octave wide, narrower than the gap between two byte thresholds, so it holds at
/// most one of them.
const BUCKET_SHIFT: u32 = 16;

/// Linear → sRGB byte by table: for each bucket of values, the byte of its lowest value and the
/// value (if any) from which the byte is one more.
pub struct SrgbEncoder {
    buckets: Vec<(u8, f32)>,
}

impl SrgbEncoder {
    pub fn new() -> SrgbEncoder {
        let buckets = (0..1f32.to_bits() >> BUCKET_SHIFT)
            .map(|k| {
                let (lo, hi) = (k << BUCKET_SHIFT, ((k + 1) << BUCKET_SHIFT) - 1);
                let base = srgb_byte(f32::from_bits(lo));
                if srgb_byte(f32::from_bits(hi)) == base {
                    return (base, f32::INFINITY);
                }
                // Bit patterns of non-negative floats are ordered like the floats.
                let (mut lo, mut hi) = (lo, hi);
                while lo < hi {
                    let mid = lo + (hi - lo) / 2;
                    if srgb_byte(f32::from_bits(mid)) > base {
                        hi = mid;
                    } else {
                        lo = mid + 1;
                    }
                }
                (base, f32::from_bits(lo))
            })
            .collect();
        SrgbEncoder { buckets }
    }

    pub fn encode(&self, v: f32) -> u8 {
        if v.is_nan() || v <= 0.0 {
            // Zero, negative or NaN, as the library clamps them.
            return 0;
        }
        if v >= 1.0 {
            return 255;
        }
        let (base, step) = self.buckets[(v.to_bits() >> BUCKET_SHIFT) as usize];
        base + u8::from(v >= step)
    }
}

/// Keeps the texture in step with a film.
pub struct Uploader {
    encoder: SrgbEncoder,
    /// The film last uploaded and its version then.
    uploaded: Option<(Arc<Film>, u64)>,
    bytes: Vec<u8>,
}

impl Uploader {
    pub fn new() -> Uploader {
        Uploader {
            encoder: SrgbEncoder::new(),
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

    /// The film as RGBA8 sRGB bytes, row 0 at the top, if it changed since the last call; the
    /// caller writes them to the texture. Returns the version they show.
    pub fn changed_pixels(&mut self, film: &Arc<Film>) -> Option<&[u8]> {
        if !self.is_stale(film) {
            return None;
        }
        // Read the version first: pixels written later may be included, never missed.
        let version = film.version();
        let (w, h) = (film.width(), film.height());
        self.bytes.resize(w as usize * h as usize * 4, 255);
        for (i, rgba) in self.bytes.chunks_exact_mut(4).enumerate() {
            let c = film.get(i as u32 % w, i as u32 / w);
            rgba[0] = self.encoder.encode(c.x);
            rgba[1] = self.encoder.encode(c.y);
            rgba[2] = self.encoder.encode(c.z);
        }
        self.uploaded = Some((film.clone(), version));
        Some(&self.bytes)
    }
}

/// Writes RGBA8 rows into the whole of `texture`.
pub fn write_texture(queue: &wgpu::Queue, texture: &wgpu::Texture, rgba: &[u8]) {
    let size = texture.size();
    queue.write_texture(
        texture.as_image_copy(),
        rgba,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(size.width * 4),
            rows_per_image: Some(size.height),
        },
        size,
    );
}

#[cfg(test)]
mod tests {
    use raylab::color::Color;

    use super::*;

    #[test]
    fn the_table_encodes_exactly_like_the_library() {
        let encoder = SrgbEncoder::new();
        let mut v = 1e-7f32;
        while v < 1.5 {
            assert_eq!(encoder.encode(v), srgb_byte(v), "{v}");
            v *= 1.0007;
        }
        for &(base, step) in &encoder.buckets {
            if step.is_finite() {
                let below = f32::from_bits(step.to_bits() - 1);
                assert_eq!(encoder.encode(step), srgb_byte(step));
                assert_eq!(encoder.encode(step), base + 1, "one step per bucket");
                assert_eq!(encoder.encode(below), srgb_byte(below));
            }
        }
        let steps = encoder.buckets.iter().filter(|b| b.1.is_finite()).count();
        assert_eq!(steps, 255, "every byte boundary is in the table once");
        for v in [-1.0, 0.0, f32::NAN, f32::INFINITY, 1.0] {
            assert_eq!(encoder.encode(v), srgb_byte(v), "{v}");
        }
    }

    #[test]
    fn pixels_are_given_once_per_change() {
        let film = Arc::new(Film::new(2, 1));
        film.set(1, 0, Color::ONE);
        film.touch();
        let mut uploader = Uploader::new();
        assert_eq!(
            uploader.changed_pixels(&film),
            Some(&[0, 0, 0, 255, 255, 255, 255, 255][..])
        );
        assert_eq!(uploader.changed_pixels(&film), None);
        film.touch();
        assert!(uploader.changed_pixels(&film).is_some());
        let other = Arc::new(Film::new(2, 1));
        assert!(uploader.is_stale(&other));
        uploader.invalidate();
        assert!(uploader.is_stale(&film));
    }
}
