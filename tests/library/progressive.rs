//! Progressive rendering by block size: every pixel traced exactly once over all passes, the
//! finished image independent of the starting block size, blocks clipped at the edges; then
//! uniform or adaptive anti-aliasing.

use raylab::bvh::Bvh;
use raylab::camera::PIXEL_CENTRE;
use raylab::color::{Color, to_srgb8};
use raylab::film::Film;
use raylab::item_buffer::Item;
use raylab::progressive::{
    self, Cancelled, Pass, RenderControl, RenderStats, SampleColoring, Shaded, passes,
    traces_pixel, unwatched_passes,
};
use raylab::ray::Ray;
use raylab::sampling::jitter;
use raylab::stats::RayCounts;
use raylab::whitted::Tracer;

#[test]
fn passes_halve_the_block_size_then_add_samples() {
    assert_eq!(
        passes(8, 3, false),
        vec![
            Pass::Block(8),
            Pass::Block(4),
            Pass::Block(2),
            Pass::Block(1),
            Pass::Sample(1),
            Pass::Sample(2)
        ]
    );
    assert_eq!(passes(1, 1, false), vec![Pass::Block(1)]);
}

#[test]
fn every_pixel_is_traced_exactly_once_across_all_passes() {
    for start in [1, 2, 4, 8, 16, 32, 64] {
        for (w, h) in [(1, 1), (37, 23), (64, 64), (100, 7)] {
            let mut count = vec![0u32; w * h];
            for pass in passes(start, 1, false) {
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
    let scene = crate::common::spheres_on_a_floor(45, 31);
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
    let scene = crate::common::spheres_on_a_floor(50, 37);
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
    let scene = crate::common::spheres_on_a_floor(21, 13);
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
    let mut scene = crate::common::spheres_on_a_floor(24, 16);
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
    let mut scene = crate::common::spheres_on_a_floor(width, height);
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
    let scene = crate::common::spheres_on_a_floor(64, 64);
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
    let scene = crate::common::spheres_on_a_floor(48, 40);
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

/// The default scene at `width × height` with `samples` per pixel and `aa_threshold`.
fn default_scene(width: u32, height: u32, samples: u32, aa_threshold: f32) -> raylab::scene::Scene {
    let mut scene = raylab::formats::load_any("assets/scenes/default.toml").unwrap();
    let s = &mut scene.settings;
    (s.width, s.height, s.samples, s.aa_threshold) = (width, height, samples, aa_threshold);
    scene
}

/// Renders `scene`, returning its pixels, how many samples each took and the render's stats.
fn render_counting(scene: &raylab::scene::Scene) -> (Vec<Color>, Vec<u32>, RenderStats) {
    render_counting_as(scene, Watched::Yes)
}

/// Whether a test renders as the viewer does, pass by pass ([`progressive::render`]), or as
/// `raylab render` does ([`progressive::render_unwatched`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Watched {
    Yes,
    No,
}

/// [`render_counting`], watched or not.
fn render_counting_as(
    scene: &raylab::scene::Scene,
    watched: Watched,
) -> (Vec<Color>, Vec<u32>, RenderStats) {
    let bvh = Bvh::build(&scene.geometry);
    let (width, height) = (scene.settings.width, scene.settings.height);
    let film = Film::new(width, height);
    let (tracer, control) = (Tracer::new(scene, &bvh), RenderControl::default());
    let stats = match watched {
        Watched::Yes => progressive::render(&tracer, &Shaded, &film, &control, |_| {}),
        Watched::No => progressive::render_unwatched(&tracer, &Shaded, &film, &control),
    }
    .unwrap();
    let counts = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| film.samples(x, y))
        .collect();
    (film.pixels(), counts, stats)
}

/// Root mean square difference of two images as shown (sRGB, 0 to 1).
fn display_rmse(a: &[Color], b: &[Color]) -> f64 {
    let (a, b) = (to_srgb8(a), to_srgb8(b));
    let sum: f64 = a
        .iter()
        .zip(&b)
        .map(|(&p, &q)| ((f64::from(p) - f64::from(q)) / 255.0).powi(2))
        .sum();
    (sum / a.len() as f64).sqrt()
}

#[test]
fn anti_aliasing_rounds_double_the_samples_up_to_the_cap() {
    let rounds = |samples| passes(4, samples, true)[2..].to_vec();
    assert_eq!(rounds(1), vec![Pass::Block(1)]);
    assert_eq!(rounds(2), vec![Pass::Block(1), Pass::Refine(2)]);
    let to_16 = [1, 2, 4, 8, 16].map(|n| {
        if n == 1 {
            Pass::Block(1)
        } else {
            Pass::Refine(n)
        }
    });
    assert_eq!(rounds(16), to_16);
    assert_eq!(
        rounds(6),
        vec![
            Pass::Block(1),
            Pass::Refine(2),
            Pass::Refine(4),
            Pass::Refine(6)
        ]
    );
}

#[test]
fn a_threshold_of_zero_samples_every_pixel_alike_as_before() {
    let scene = default_scene(40, 30, 3, 0.0);
    let (image, counts, stats) = render_counting(&scene);
    assert!(
        counts.iter().all(|&n| n == 3),
        "every pixel takes every sample"
    );
    assert_eq!(stats.rays.primary, 40 * 30 * 3);
    let kinds: Vec<Pass> = stats.passes.iter().map(|p| p.pass).collect();
    assert_eq!(kinds, passes(16, 3, false));
    // Each pixel is the mean of its centre and jittered samples 1 and 2, added in that order.
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let trace = |x, y, offset| {
        let ray = scene.camera.eye_ray((x, y), offset, (40, 30));
        let mut color = [Color::ZERO];
        Shaded.shade(
            &tracer,
            &[ray],
            &[None],
            &mut color,
            &mut Default::default(),
        );
        color[0]
    };
    for (x, y) in [(0, 0), (17, 11), (39, 29), (25, 20)] {
        let mut mean = trace(x, y, PIXEL_CENTRE);
        for k in 1..3 {
            mean += (trace(x, y, jitter(x, y, k)) - mean) / (k + 1) as f32;
        }
        assert_eq!(image[(y * 40 + x) as usize], mean, "pixel ({x}, {y})");
    }
}

#[test]
fn adaptive_pixels_at_the_cap_are_the_uniform_renders_and_the_rest_the_one_sample_ones() {
    let (uniform, _, _) = render_counting(&default_scene(64, 48, 4, 0.0));
    let (one, _, _) = render_counting(&default_scene(64, 48, 1, 0.0));
    let (adaptive, counts, stats) = render_counting(&default_scene(64, 48, 4, 0.03));
    let total: u64 = counts.iter().map(|&n| u64::from(n)).sum();
    assert_eq!(stats.rays.primary, total, "each sample is one eye ray");
    let mut at_cap = 0;
    for (i, &n) in counts.iter().enumerate() {
        match n {
            1 => assert_eq!(adaptive[i], one[i], "pixel {i}"),
            4 => {
                assert_eq!(adaptive[i], uniform[i], "pixel {i}");
                at_cap += 1;
            }
            // Joined in the last round: one sample, then straight to the cap.
            _ => assert!(n == 2, "pixel {i} took {n} samples"),
        }
    }
    assert!(at_cap > 100, "the edges take the cap: {at_cap} pixels");
    // PassStats: each round tells how many pixels it refined, fewer than there are.
    for pass in &stats.passes[5..] {
        assert!(matches!(pass.pass, Pass::Refine(_)));
        assert!(pass.pixels > 0 && pass.pixels < 64 * 48, "{pass:?}");
    }
}

/// Shows a vertical edge through the middle of the image: white right of the camera's view
/// direction, black left of it.
struct Edge;

impl SampleColoring for Edge {
    fn shade(
        &self,
        tracer: &Tracer,
        rays: &[Ray],
        _: &[Option<Item>],
        colors: &mut [Color],
        counts: &mut RayCounts,
    ) {
        for (ray, color) in rays.iter().zip(colors) {
            let right = ray.dir.dot(tracer.scene.camera.u) > 0.0;
            *color = if right { Color::ONE } else { Color::ZERO };
            counts.primary += 1;
        }
    }
}

#[test]
fn flat_regions_take_one_sample_and_edges_the_cap() {
    // 33 columns: the edge runs through the middle of column 16.
    let mut scene = crate::common::spheres_on_a_floor(33, 20);
    (scene.settings.samples, scene.settings.aa_threshold) = (16, 0.03);
    let bvh = Bvh::build(&scene.geometry);
    let film = Film::new(33, 20);
    let control = RenderControl::default();
    let stats =
        progressive::render(&Tracer::new(&scene, &bvh), &Edge, &film, &control, |_| {}).unwrap();
    for y in 0..20 {
        for x in 0..33 {
            let n = film.samples(x, y);
            if x == 16 {
                assert_eq!(n, 16, "the edge's pixel ({x}, {y}) takes the cap");
                let grey = film.get(x, y).x;
                assert!(grey > 0.2 && grey < 0.8, "and is anti-aliased: {grey}");
            } else if x.abs_diff(16) >= 2 {
                assert_eq!(n, 1, "flat pixel ({x}, {y})");
            }
        }
    }
    // At most three columns refined: far fewer eye rays than uniform sampling's 16 per pixel.
    assert!(
        stats.rays.primary <= 33 * 20 + 3 * 20 * 15,
        "{}",
        stats.rays.primary
    );
}

#[test]
fn adaptive_sampling_traces_fewer_rays_for_nearly_the_uniform_error() {
    let (width, height) = (192, 144);
    let (reference, _, _) = render_counting(&default_scene(width, height, 64, 0.0));
    let (one, _, _) = render_counting(&default_scene(width, height, 1, 0.0));
    let (uniform, _, uniform_stats) = render_counting(&default_scene(width, height, 8, 0.0));
    let (adaptive, _, adaptive_stats) = render_counting(&default_scene(width, height, 8, 0.03));
    let rays = |s: &RenderStats| s.rays.primary;
    let errors = [&one, &uniform, &adaptive].map(|image| display_rmse(image, &reference));
    let [one_error, uniform_error, adaptive_error] = errors;
    // 192×144 is 61% of the rays (the checkered floor is edges all the way to the horizon).
    assert!(
        rays(&adaptive_stats) * 10 < rays(&uniform_stats) * 7,
        "adaptive {} eye rays against uniform {}",
        rays(&adaptive_stats),
        rays(&uniform_stats)
    );
    assert!(
        adaptive_error < 1.1 * uniform_error && adaptive_error < 0.5 * one_error,
        "RMSE: 1 spp {one_error:.4}, uniform {uniform_error:.4}, adaptive {adaptive_error:.4}"
    );
}

#[test]
fn adaptive_renders_are_the_same_whatever_the_thread_count() {
    let scene = default_scene(80, 60, 8, 0.02);
    let render_on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| render_counting(&scene))
    };
    let (image, counts, _) = render_on(1);
    for threads in [2, 5] {
        let (other, other_counts, _) = render_on(threads);
        assert!(other == image, "{threads} threads: other pixels");
        assert!(other_counts == counts, "{threads} threads: other samples");
    }
    assert!(counts.contains(&8) && counts.contains(&1));
}

#[test]
fn the_progress_says_how_many_samples_each_pass_brings_pixels_to() {
    let mut seen = Vec::new();
    for aa_threshold in [0.0, 0.03] {
        let scene = default_scene(24, 16, 4, aa_threshold);
        let bvh = Bvh::build(&scene.geometry);
        let film = Film::new(24, 16);
        let control = RenderControl::default();
        let mut samples = Vec::new();
        progressive::render(&Tracer::new(&scene, &bvh), &Shaded, &film, &control, |_| {
            samples.push(control.progress().samples)
        })
        .unwrap();
        seen.push(samples);
    }
    // Block passes 16 → 1 take one sample; then uniform sampling adds samples 2, 3 and 4, while
    // the adaptive rounds bring pixels to 2 and then 4 samples.
    assert_eq!(seen[0], [1, 1, 1, 1, 1, 2, 3, 4]);
    assert_eq!(seen[1], [1, 1, 1, 1, 1, 2, 4]);
}

#[test]
fn an_unwatched_render_sweeps_the_pixels_once_then_runs_the_adaptive_rounds() {
    assert_eq!(unwatched_passes(1, false), [Pass::Sweep(1)]);
    assert_eq!(unwatched_passes(4, false), [Pass::Sweep(4)]);
    assert_eq!(unwatched_passes(1, true), [Pass::Sweep(1)]);
    assert_eq!(
        unwatched_passes(6, true),
        [
            Pass::Sweep(1),
            Pass::Refine(2),
            Pass::Refine(4),
            Pass::Refine(6)
        ]
    );
}

#[test]
fn an_unwatched_render_ends_with_the_watched_renders_film_on_any_thread_count() {
    // One sample, uniform samples, adaptive rounds; blocks clipped at the edges of 37 × 23.
    for (samples, aa_threshold, block_size) in [(1, 0.0, 16), (4, 0.0, 8), (8, 0.02, 4)] {
        let mut scene = default_scene(37, 23, samples, aa_threshold);
        scene.settings.block_size = block_size;
        let (watched, watched_counts, watched_stats) = render_counting(&scene);
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let (image, counts, stats) = pool.install(|| render_counting_as(&scene, Watched::No));
            let case = format!("{samples} samples, threshold {aa_threshold}, {threads} threads");
            assert!(image == watched, "{case}: other pixels");
            assert!(counts == watched_counts, "{case}: other samples");
            assert_eq!(stats.rays, watched_stats.rays, "{case}");
        }
    }
}

#[test]
fn the_decision_reach_is_one_pixel_per_adaptive_round() {
    let mut settings = raylab::settings::RenderSettings::default();
    for (samples, aa_threshold, reach) in [(16, 0.03, 4), (5, 0.03, 3), (16, 0.0, 0), (1, 0.03, 0)]
    {
        (settings.samples, settings.aa_threshold) = (samples, aa_threshold);
        assert_eq!(
            progressive::decision_reach(&settings),
            reach,
            "{samples} samples, threshold {aa_threshold}"
        );
    }
}

#[test]
fn a_window_grown_by_the_decision_reach_renders_its_pixels_as_the_whole_image() {
    use raylab::tiles::Rect;
    let scene = default_scene(37, 23, 16, 0.03);
    let (whole, _, _) = render_counting_as(&scene, Watched::No);
    let whole = &whole;
    let bvh = Bvh::build(&scene.geometry);
    let tracer = Tracer::new(&scene, &bvh);
    let image = Rect::image(37, 23);
    let reach = progressive::decision_reach(&scene.settings);
    let bits = |pixels: &[Color]| -> Vec<[u32; 3]> {
        pixels
            .iter()
            .map(|c| c.to_array().map(f32::to_bits))
            .collect()
    };
    // The pixels of `rect` rendered in a window `margin` pixels larger, as bits.
    let render_rect = |rect: Rect, margin: u32| {
        let film = Film::window(37, 23, rect.grown(margin, &image));
        progressive::render_unwatched(&tracer, &Shaded, &film, &RenderControl::default()).unwrap();
        bits(&film.pixels_in(rect))
    };
    let mut differs_without_margin = false;
    for rect in raylab::tiles::split(37, 23, 6)
        .unwrap()
        .into_iter()
        .chain([Rect {
            x0: 3,
            y0: 5,
            x1: 30,
            y1: 9,
        }])
    {
        let expected: Vec<Color> = (rect.y0..rect.y1)
            .flat_map(|y| (rect.x0..rect.x1).map(move |x| whole[(y * 37 + x) as usize]))
            .collect();
        assert_eq!(render_rect(rect, reach), bits(&expected), "{rect}");
        differs_without_margin |= render_rect(rect, 0) != bits(&expected);
    }
    assert!(
        differs_without_margin,
        "the windows' edges matter without a margin"
    );
}

/// The backend on the CPU runs the CPU sweep: the same passes and the same film, watched or
/// not, and says what it ran on.
#[test]
fn a_backend_on_the_cpu_renders_the_passes_and_film_of_the_cpu_sweep() {
    use raylab::backend::Backend;
    use raylab::inspect::DebugView;
    use raylab::render::assemble;

    let mut scene = crate::common::spheres_on_a_floor(48, 32);
    scene.settings.block_size = 8;
    let assembled = assemble(scene).unwrap();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build();
    let mut backend = Backend::new(std::sync::Arc::new(pool.unwrap()));
    let (expected, expected_stats) = progressive::render_image(&assembled.tracer());
    let (film, control) = (Film::new(48, 32), RenderControl::default());
    let mut passes = Vec::new();
    let stats = backend
        .render(&assembled, DebugView::Shaded, (&film, &control), |p| {
            passes.push(p.pass)
        })
        .unwrap();
    let expected_passes: Vec<_> = expected_stats.passes.iter().map(|p| p.pass).collect();
    assert_eq!(passes, expected_passes);
    assert_eq!(stats.rays, expected_stats.rays);
    assert!(film.pixels() == expected, "the watched render's film");
    let (unwatched, unwatched_stats) = backend.render_image(&assembled).unwrap();
    assert!(
        unwatched.pixels() == expected,
        "the unwatched render's film"
    );
    assert_eq!(unwatched_stats.passes.len(), 1);
    assert_eq!(backend.label(), "cpu: 2 threads");
}
