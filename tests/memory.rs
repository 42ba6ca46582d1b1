//! Memory in proportion: saving a rendered film, in every format, takes no copy of the image,
//! only a band of rows at a time, as `OutputFormat::save_bytes` says (the README's limit of 17
//! bytes a pixel is the film's 16 and this). Measured by counting the bytes this test program
//! has allocated, at their peak.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use raylab::color::Color;
use raylab::film::Film;
use raylab::formats::image::{OutputFormat, save_toned_pixels};
use raylab::tone::Tone;

/// The system's allocator, counting the bytes held now and at the most.
struct Counting;

static HELD: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn held(grown: usize) {
    let now = HELD.fetch_add(grown, Ordering::Relaxed) + grown;
    PEAK.fetch_max(now, Ordering::Relaxed);
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        held(layout.size());
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        held(layout.size());
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        HELD.fetch_sub(layout.size(), Ordering::Relaxed);
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // Both blocks may be held at once while the old one is copied.
        held(new_size);
        HELD.fetch_sub(layout.size(), Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most bytes held beyond those held before, while `work` runs.
fn peak_during(work: impl FnOnce()) -> usize {
    let before = HELD.load(Ordering::Relaxed);
    PEAK.store(before, Ordering::Relaxed);
    work();
    PEAK.load(Ordering::Relaxed) - before
}

#[test]
fn saving_a_film_takes_a_band_of_rows_not_a_copy_of_the_image() {
    let (width, height) = (4096, 2048);
    let film = Film::new(width, height);
    for y in 0..height {
        for x in 0..width {
            let c = Color::new(x as f32 / width as f32, y as f32 / height as f32, 0.25);
            film.set(x, y, c);
        }
    }
    let pixel = |x, y| film.get(x, y);
    let dir = tempfile::tempdir().unwrap();
    // Once first, so that the thread pool and the encoders' tables exist before counting.
    let warm_up = dir.path().join("small.png");
    save_toned_pixels(&warm_up, 4, 4, &pixel, Tone::default()).unwrap();
    let pixels = (width * height) as usize;
    for ext in ["png", "ppm", "exr", "hdr"] {
        let path = dir.path().join(format!("film.{ext}"));
        let format = OutputFormat::from_path(&path).unwrap();
        let peak = peak_during(|| {
            save_toned_pixels(&path, width, height, &pixel, Tone::default()).unwrap();
        });
        let allowed = format.save_bytes(width) as usize;
        eprintln!("{ext}: {peak} bytes at the peak, {allowed} allowed");
        assert!(
            peak <= allowed,
            "{ext}: saving took {peak} bytes, more than the {allowed} it is said to take"
        );
        // What a copy of the linear pixels alone would take is 12 bytes a pixel.
        assert!(
            peak < pixels,
            "{ext}: {:.2} bytes a pixel",
            peak as f64 / pixels as f64
        );
        assert!(std::fs::metadata(&path).unwrap().len() > 0);
    }
}
