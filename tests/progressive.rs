//! Progressive rendering by block size: every pixel traced exactly once over all passes, the
//! finished image independent of the starting block size, blocks clipped at the edges.

mod common;

use raylab::bvh::Bvh;
use raylab::film::Film;
use raylab::progressive::{self, Cancelled, Pass, RenderControl, Shaded, passes, traces_pixel};
use raylab::whitted::Tracer;

#[test]
fn passes_halve_the_block_size_then_add_samples() {
    assert_eq!(
        passes(8, 3),
        vec![
            Pass::Block(8),
            Pass::Block(4),
            Pass::Block(2),
            Pass::Block(1),
            Pass::Sample(1),
            Pass::Sample(2)
        ]
    );
    assert_eq!(passes(1, 1), vec![Pass::Block(1)]);
}

#[test]
fn every_pixel_is_traced_exactly_once_across_all_passes() {
    for start in [1, 2, 4, 8, 16, 32, 64] {
        for (w, h) in [(1, 1), (37, 23), (64, 64), (100, 7)] {
            let mut count = vec![0u32; w * h];
            for pass in passes(start, 1) {
                let Pass::Block(b) = pass else { unreachable!() };
                for y in 0..h {
                    for x in 0..w {
                        if traces_pixel(b, start, x as u32, y as u32) {
                            // A traced pixel is always the top-left of its block.
                            assert!(x % b as usize == 0 && y % b as usize == 0);
                            count[y * w + x] += 1;
                        }
                    }
                }
            }
            assert!(count.iter().all(|&c| c == 1), "start {start}, {w}×{h}");
        }
    }
}

#[test]
fn the_renderer_traces_exactly_width_times_height_eye_rays() {
    let scene = common::spheres_on_a_floor(45, 31);
    let bvh = Bvh::build(&scene.geometry);
    for start in [1, 4, 16, 64] {
        let mut scene = scene.clone();
        scene.settings.block_size = start;
        let (_, stats) = progressive::render_image(&Tracer::new(&scene, &bvh));
        assert_eq!(stats.rays.primary, 45 * 31, "start {start}");
        let per_pass: u64 = stats.passes.iter().map(|p| p.pixels).sum();
        assert_eq!(per_pass, 45 * 31);
    }
}

#[test]
fn finished_image_is_the_same_from_any_starting_block_size() {
    let scene = common::spheres_on_a_floor(50, 37);
    let bvh = Bvh::build(&scene.geometry);
    let (reference, _) = progressive::render_image(&Tracer::new(&scene, &bvh));
    for start in [2, 8, 32, 64] {
        let mut scene = scene.clone();
        scene.settings.block_size = start;
        let (image, _) = progressive::render_image(&Tracer::new(&scene, &bvh));
        assert!(
            image == reference,
            "start {start} differs from block size 1"
        );
    }
}

#[test]
fn a_coarse_pass_paints_whole_blocks_clipped_at_the_edges() {
    let scene = common::spheres_on_a_floor(21, 13);
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let film = Film::new(21, 13);
    let control = RenderControl::default();
    progressive::render_pass(&tracer, &Shaded, &film, &control, Pass::Block(8), 8).unwrap();
    // 21×13 at block 8: blocks start at x = 0, 8, 16 and y = 0, 8; the last ones are clipped.
    for y in 0..13 {
        for x in 0..21 {
            let corner = film.get(x / 8 * 8, y / 8 * 8);
            assert_eq!(film.get(x, y), corner, "pixel ({x}, {y})");
        }
    }
    // The painted values are the traced pixel's colour, which a full render agrees with.
    let (full, _) = progressive::render_image(&tracer);
    assert_eq!(film.get(16, 8), full[8 * 21 + 16]);
}

#[test]
fn samples_average_jittered_rays_and_stay_deterministic() {
    let mut scene = common::spheres_on_a_floor(24, 16);
    scene.settings.samples = 4;
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let (a, stats) = progressive::render_image(&tracer);
    assert_eq!(stats.rays.primary, 24 * 16 * 4);
    let (b, _) = progressive::render_image(&tracer);
    assert!(a == b, "the same samples every time");
    scene.settings.samples = 1;
    let (one, _) = progressive::render_image(&Tracer::new(&scene, &bvh));
    assert!(a != one, "anti-aliasing changes edge pixels");
}

#[test]
fn a_render_cancelled_from_another_thread_stops_within_a_band() {
    // Seconds of work: 1200 × 1200 pixels, 8 samples each (a render that ignored the cancel
    // would end, and fail, rather than run on for minutes).
    let (width, height) = (1200, 1200);
    let mut scene = common::spheres_on_a_floor(width, height);
    scene.settings.block_size = 1;
    scene.settings.samples = 8;
    let bvh = Bvh::build(&scene.geometry);
    let control = RenderControl::default();
    let film = Film::new(width, height);
    let (result, traced_when_cancelled) = std::thread::scope(|s| {
        let canceller = s.spawn(|| {
            // Once the render is under way: cancel, then count what is traced.
            while control.pixels_traced() == 0 {
                std::thread::yield_now();
            }
            control.cancel();
            control.pixels_traced()
        });
        let result =
            progressive::render(&Tracer::new(&scene, &bvh), &Shaded, &film, &control, |_| {});
        (result, canceller.join().unwrap())
    });
    assert_eq!(result.unwrap_err(), Cancelled);
    assert!(!control.progress().finished);
    // Each thread finishes the band it is tracing (at most 8 rows of traced pixels), and starts
    // no other. How fast that is: `cargo bench --bench progressive`.
    let after = control.pixels_traced() - traced_when_cancelled;
    let bands_in_flight = rayon::current_num_threads() as u64;
    assert!(
        after <= bands_in_flight * 8 * u64::from(width),
        "{after} pixels traced after the cancel"
    );
}

#[test]
fn progress_is_visible_while_a_render_runs() {
    let scene = common::spheres_on_a_floor(64, 64);
    let bvh = Bvh::build(&scene.geometry);
    let control = RenderControl::default();
    let film = Film::new(64, 64);
    let mut seen = Vec::new();
    progressive::render(
        &Tracer::new(&scene, &bvh),
        &Shaded,
        &film,
        &control,
        |pass| {
            seen.push((pass.pass, control.progress()));
        },
    )
    .unwrap();
    let blocks: Vec<u32> = seen.iter().map(|(_, p)| p.block_size).collect();
    assert_eq!(blocks, vec![16, 8, 4, 2, 1]);
    for (_, p) in &seen {
        assert_eq!(p.rows_done, p.rows, "a finished pass has done all its rows");
    }
    assert!(control.progress().finished);
    assert!(film.version() > 0);
}

#[test]
fn a_paused_render_waits_until_resumed_and_a_cancel_wakes_it() {
    let scene = common::spheres_on_a_floor(48, 40);
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let control = RenderControl::default();
    let film = Film::new(48, 40);
    control.pause();
    let traced_while_paused = std::thread::scope(|s| {
        let render = s.spawn(|| progressive::render(&tracer, &Shaded, &film, &control, |_| {}));
        std::thread::sleep(std::time::Duration::from_millis(100));
        let traced = control.pixels_traced();
        assert!(control.is_paused() && !control.progress().finished);
        control.resume();
        assert!(render.join().unwrap().is_ok());
        traced
    });
    assert_eq!(traced_while_paused, 0, "nothing is traced while paused");
    assert!(control.progress().finished);
    // Every row the passes wrote is marked changed for the viewer, once.
    assert_eq!(
        film.take_changed_rows(),
        std::iter::once(0..40).collect::<Vec<_>>()
    );
    assert!(film.take_changed_rows().is_empty());
    // A cancel ends a paused render.
    let paused = RenderControl::default();
    paused.pause();
    let result = std::thread::scope(|s| {
        let render = s.spawn(|| progressive::render(&tracer, &Shaded, &film, &paused, |_| {}));
        std::thread::sleep(std::time::Duration::from_millis(20));
        paused.cancel();
        render.join().unwrap()
    });
    assert_eq!(result.unwrap_err(), Cancelled);
}
