//! Texture upload: copies the film into the GPU texture, at most once per frame and only when the
//! film's [`version`](raylab::film::Film::version) says its pixels changed, and then only the
//! rows the film says changed ([`Film::take_changed_rows`]), one write per run of rows (the
//! whole image for a new film, a new texture or a new [`Tone`]). Each pixel goes up as the bytes
//! the display shows: its linear colour through the exposure and tone curve, then sRGB through
//! the library's table ([`SrgbEncoder`]), which gives exactly [`Tone::map`]'s bytes without a
//! `powf` per channel, as a saved image does. In the difference display each pixel goes up
//! instead as the heat-map colour of its largest channel difference from the image compared with
//! ([`Uploader::show_difference`]), from black (equal) to light yellow ([`DIFFERENCE_TOP`] levels
//! or more). Done here, on the rows that changed, rather than in
//! the quad's shader for every screen pixel of every frame, it spares a software GPU (lavapipe)
//! that work on every frame, and what is saved is what is shown by construction.

use std::ops::Range;
use std::sync::Arc;

use raylab::color::{Color, SrgbEncoder};
use raylab::compare::difference::pixel_difference;
use raylab::film::Film;
use raylab::inspect::heat;
use raylab::srgb_image::SrgbImage;
use raylab::tone::{Tone, ToneCurve};

/// Bytes of one texel of [`IMAGE_FORMAT`](super::quad::IMAGE_FORMAT): red, green, blue, alpha.
pub const TEXEL_BYTES: usize = 4;

/// One film pixel as its texel: the bytes a [`Tone`] of `scale` ([`Tone::scale`]) and `curve`
/// makes of its colour, through the sRGB table, opaque.
pub fn texel(encoder: &SrgbEncoder, c: Color, scale: f32, curve: ToneCurve, out: &mut [u8]) {
    for (byte, v) in out.iter_mut().zip(c.to_array()) {
        *byte = encoder.encode(curve.apply(v * scale));
    }
    out[3] = 255;
}

/// The difference, in levels, that the difference display shows at the top of its heat ramp.
pub const DIFFERENCE_TOP: f32 = 32.0;

/// Keeps the texture in step with a film.
pub struct Uploader {
    /// The film last uploaded, its version then and the tone its bytes were made with.
    uploaded: Option<(Arc<Film>, u64, Tone)>,
    /// The image whose difference from the film the texels show, in the difference display.
    against: Option<Arc<SrgbImage>>,
    bytes: Vec<u8>,
}

impl Uploader {
    pub fn new() -> Uploader {
        Uploader {
            uploaded: None,
            against: None,
            bytes: Vec::new(),
        }
    }

    /// Shows the film's difference from `against` (of the film's size) from now on, or its
    /// colours (`None`); a change uploads the whole film again.
    pub fn show_difference(&mut self, against: Option<Arc<SrgbImage>>) {
        let same = match (&self.against, &against) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        if !same {
            self.against = against;
            self.invalidate();
        }
    }

    /// Whether the texels show a difference (which only [`Self::changed_pixels`] makes).
    pub fn shows_difference(&self) -> bool {
        self.against.is_some()
    }

    /// Whether the texture does not show `film` through `tone` yet.
    pub fn is_stale(&self, film: &Arc<Film>, tone: Tone) -> bool {
        match &self.uploaded {
            Some((last, version, made_with)) => {
                !Arc::ptr_eq(last, film) || *version != film.version() || *made_with != tone
            }
            None => true,
        }
    }

    /// Forgets what was uploaded (the texture was recreated).
    pub fn invalidate(&mut self) {
        self.uploaded = None;
    }

    /// The runs of rows of `film` the texture does not show through `tone` yet (all of them for
    /// a film not shown before, or a new tone), if any; from now on they count as shown.
    pub fn changed_rows(&mut self, film: &Arc<Film>, tone: Tone) -> Option<Vec<Range<u32>>> {
        if !self.is_stale(film, tone) {
            return None;
        }
        // Read the version and take the rows first: pixels written later may be included, never
        // missed.
        let version = film.version();
        let changed = film.take_changed_rows();
        let rows = match &self.uploaded {
            Some((last, _, made_with)) if Arc::ptr_eq(last, film) && *made_with == tone => changed,
            _ => std::iter::once(0..film.height()).collect(),
        };
        self.uploaded = Some((film.clone(), version, tone));
        Some(rows)
    }

    /// The film through `tone` as texels of [`IMAGE_FORMAT`](super::quad::IMAGE_FORMAT), row 0
    /// at the top, with the runs of rows that changed since the last call
    /// ([`Self::changed_rows`]), if any did; the caller writes those rows to the texture
    /// ([`write_rows`]).
    pub fn changed_pixels(
        &mut self,
        film: &Arc<Film>,
        tone: Tone,
    ) -> Option<(&[u8], Vec<Range<u32>>)> {
        let rows = self.changed_rows(film, tone)?;
        let (w, h) = (film.width() as usize, film.height());
        self.bytes.resize(w * h as usize * TEXEL_BYTES, 0);
        let row_bytes = w * TEXEL_BYTES;
        let (encoder, scale) = (SrgbEncoder::shared(), tone.scale());
        let size = (film.width(), film.height());
        let against = self
            .against
            .as_deref()
            .filter(|a| (a.width, a.height) == size);
        for y in rows.iter().flat_map(|run| run.clone()) {
            let row = &mut self.bytes[y as usize * row_bytes..(y as usize + 1) * row_bytes];
            for (x, out) in row.chunks_exact_mut(TEXEL_BYTES).enumerate() {
                texel(encoder, film.get(x as u32, y), scale, tone.curve, out);
                if let Some(against) = against {
                    let shown = [out[0], out[1], out[2]];
                    let levels = pixel_difference(shown, against.at(x as u32, y));
                    let color = heat(f32::from(levels) / DIFFERENCE_TOP);
                    texel(encoder, color, 1.0, ToneCurve::Clamp, out);
                }
            }
        }
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
    use strum::IntoEnumIterator;

    #[test]
    fn texels_are_the_librarys_tone_mapping() {
        let encoder = SrgbEncoder::shared();
        let mut out = [0; TEXEL_BYTES];
        for curve in ToneCurve::iter() {
            for exposure in [-2.0, 0.0, 0.5, 1.0, 3.0] {
                let tone = Tone::new(exposure, curve).unwrap();
                let mut v = 1e-5f32;
                while v < 64.0 {
                    let c = Color::new(v, v * 0.5, v * 3.0);
                    texel(encoder, c, tone.scale(), tone.curve, &mut out);
                    let [r, g, b] = tone.map(c);
                    assert_eq!(out, [r, g, b, 255], "{tone:?} at {c}");
                    v *= 1.01;
                }
            }
        }
    }

    #[test]
    fn pixels_are_given_once_per_change_and_again_through_a_new_tone() {
        let film = Arc::new(Film::new(2, 1));
        film.set(1, 0, Color::splat(0.5));
        film.touch();
        let mut uploader = Uploader::new();
        let plain = Tone::default();
        let once = std::iter::once(0..1).collect::<Vec<_>>();
        assert_eq!(
            uploader.changed_pixels(&film, plain),
            Some((&[0, 0, 0, 255, 188, 188, 188, 255][..], once.clone()))
        );
        assert_eq!(uploader.changed_pixels(&film, plain), None);
        // One stop brighter: the same rows again, brighter, though the film did not change.
        let brighter = Tone::new(1.0, ToneCurve::Clamp).unwrap();
        assert!(uploader.is_stale(&film, brighter));
        assert_eq!(
            uploader.changed_pixels(&film, brighter),
            Some((&[0, 0, 0, 255, 255, 255, 255, 255][..], once))
        );
        film.touch();
        assert!(uploader.changed_pixels(&film, brighter).is_some());
        let other = Arc::new(Film::new(2, 1));
        assert!(uploader.is_stale(&other, brighter));
        uploader.invalidate();
        assert!(uploader.is_stale(&film, brighter));
    }

    #[test]
    fn only_the_changed_rows_are_converted_and_given() {
        let film = Arc::new(Film::new(1, 4));
        let mut uploader = Uploader::new();
        let tone = Tone::default();
        film.touch_rows(1..2);
        // A film not uploaded before goes up whole.
        let (_, rows) = uploader.changed_pixels(&film, tone).unwrap();
        assert_eq!(rows, std::iter::once(0..4).collect::<Vec<_>>());
        // Row 3 is written but not marked: it is not converted.
        film.set(0, 2, Color::ONE);
        film.set(0, 3, Color::ONE);
        film.touch_rows(2..3);
        let (bytes, rows) = uploader.changed_pixels(&film, tone).unwrap();
        assert_eq!(rows, std::iter::once(2..3).collect::<Vec<_>>());
        assert_eq!(bytes[2 * TEXEL_BYTES..3 * TEXEL_BYTES], [255; 4]);
        assert_eq!(
            bytes[3 * TEXEL_BYTES..],
            [0, 0, 0, 255],
            "row 3 is as first uploaded"
        );
    }
}
