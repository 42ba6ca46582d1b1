//! raylab's images of one scene, each traced once: its own image (the reference an image is
//! compared with) and, as [`super::check`] asks for them, its images traced with mistakes
//! ([`trace_with`]), kept up to a number of them so that every image checked against the scene
//! (a class's, when grading) shares them.

use std::sync::{Arc, Mutex};

use super::mistakes::{Mistake, Written, trace_with};
use crate::film::Film;
use crate::render::Assembled;
use crate::srgb_image::SrgbImage;

/// One scene's traced images.
pub struct Traces {
    pub assembled: Assembled,
    /// raylab's image as traced.
    pub film: Arc<Film>,
    /// raylab's image as written: the reference.
    pub reference: SrgbImage,
    /// The images traced with mistakes, each under the mistakes it was traced with (those
    /// that [`Mistake::retraces`], in the order of [`Mistake`]).
    kept: Mutex<Vec<(Vec<Mistake>, Arc<Film>)>>,
    /// How many images traced with mistakes are kept at most.
    most_kept: usize,
}

impl Traces {
    /// Traces raylab's image of `assembled`'s scene; up to `most_kept` images traced with
    /// mistakes are to be kept.
    pub fn new(assembled: Assembled, most_kept: usize) -> Traces {
        let film = trace_with(&assembled, &[]);
        let reference = Written {
            colors: &film,
            mistakes: &[],
            scale: 1.0,
        }
        .image();
        Traces {
            assembled,
            film: Arc::new(film),
            reference,
            kept: Mutex::new(Vec::new()),
            most_kept,
        }
    }

    /// The memory an image traced with mistakes takes, and so each one kept.
    pub fn film_bytes(&self) -> u64 {
        let settings = &self.assembled.scene.settings;
        Film::memory_bytes(settings.width, settings.height)
    }

    /// raylab's image traced with the mistakes among `mistakes` that retrace: kept, or traced
    /// now (`step` hears why) and kept while there is room.
    pub fn traced(&self, mistakes: &[Mistake], step: &mut dyn FnMut(&str)) -> Arc<Film> {
        let mut key: Vec<Mistake> = mistakes.iter().copied().filter(|m| m.retraces()).collect();
        key.sort();
        key.dedup();
        if key.is_empty() {
            return self.film.clone();
        }
        let kept = |list: &[(Vec<Mistake>, Arc<Film>)]| {
            list.iter()
                .find(|(made, _)| *made == key)
                .map(|(_, film)| film.clone())
        };
        if let Some(film) = kept(&self.lock()) {
            return film;
        }
        let words: Vec<&str> = key.iter().map(|m| m.describe()).collect();
        step(&format!(
            "tracing raylab's image as if {}",
            words.join(", and ")
        ));
        // Traced with the list unlocked: other images' checks go on meanwhile, and may trace the
        // same image at the same time; the first kept is the one kept.
        let film = Arc::new(trace_with(&self.assembled, &key));
        let mut list = self.lock();
        if let Some(film) = kept(&list) {
            return film;
        }
        if list.len() < self.most_kept {
            list.push((key, film.clone()));
        }
        film
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<(Vec<Mistake>, Arc<Film>)>> {
        self.kept
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}
