//! Progressive rendering's answer to a cancel: the time from `RenderControl::cancel` to
//! `progressive::render` returning, on a render far too large to finish (1200 × 1200 pixels,
//! 64 samples each). Each thread finishes the band it is tracing, so this stays within a few
//! milliseconds; `tests/library/progressive.rs` checks that no thread starts another band.

use std::time::{Duration, Instant};

use criterion::{Criterion, criterion_group, criterion_main};
use raylab::film::Film;
use raylab::formats::toml::default_scene;
use raylab::progressive::{self, RenderControl, Shaded};
use raylab::render::assemble;

fn cancel(c: &mut Criterion) {
    let (width, height) = (1200, 1200);
    let mut scene = default_scene().expect("the built-in scene loads");
    scene.settings.width = width;
    scene.settings.height = height;
    scene.settings.block_size = 1;
    scene.settings.samples = 64;
    let assembled = assemble(scene).expect("the built-in scene has no caustics to shoot");
    let tracer = assembled.tracer();
    let mut group = c.benchmark_group("progressive");
    // Only the stopping is timed, yet each iteration also starts a render and waits for its
    // first band: keep the measured time short.
    group.sample_size(20);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group.bench_function("stop a 1200×1200 render once cancelled", |b| {
        b.iter_custom(|iterations| {
            let mut total = Duration::ZERO;
            for _ in 0..iterations {
                let control = RenderControl::default();
                let film = Film::new(width, height);
                std::thread::scope(|s| {
                    let canceller = s.spawn(|| {
                        while control.pixels_traced() == 0 {
                            std::thread::yield_now();
                        }
                        control.cancel();
                        Instant::now()
                    });
                    let result = progressive::render(&tracer, &Shaded, &film, &control, |_| {});
                    let stopped = Instant::now();
                    assert!(result.is_err(), "the render was cancelled");
                    total += stopped.saturating_duration_since(canceller.join().unwrap());
                });
            }
            total
        })
    });
    group.finish();
}

criterion_group!(benches, cancel);
criterion_main!(benches);
