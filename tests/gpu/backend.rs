//! The one seam where a device is chosen ([`raylab::backend::Backend`]): one backend renders
//! scene after scene on either device (the GPU's upload following the scene), with first hits
//! from the rays or the item buffer, and what the GPU cannot do is an error, or with a fallback
//! a render on the CPU that says why.

use std::sync::Arc;

use raylab::backend::{Backend, RenderError};
use raylab::color::to_srgb8;
use raylab::film::Film;
use raylab::inspect::DebugView;
use raylab::progressive::{RenderControl, render_image, render_image_with};
use raylab::render::{Assembled, Device, FirstHit, assemble};

use crate::gpu;
use crate::images::difference;

const SIZE: (u32, u32) = (64, 48);

/// A shipped scene at [`SIZE`], assembled.
fn shipped(name: &str) -> Assembled {
    let path = format!("{}/assets/scenes/{name}", env!("CARGO_MANIFEST_DIR"));
    let mut scene = raylab::formats::load_any(&path).unwrap();
    (scene.settings.width, scene.settings.height) = SIZE;
    assemble(scene).unwrap()
}

/// A backend on two threads that renders on the GPU every test shares.
fn backend() -> Backend {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build();
    let mut backend = Backend::new(Arc::new(pool.unwrap()));
    backend.set_gpu(gpu());
    backend
}

/// `view` of `assembled` rendered by `backend`, as 8-bit sRGB.
fn rendered(backend: &mut Backend, assembled: &Assembled, view: DebugView) -> Vec<u8> {
    let film = Film::new(SIZE.0, SIZE.1);
    let control = RenderControl::default();
    let stats = backend
        .render(assembled, view, (&film, &control), |_| {})
        .unwrap_or_else(|e| panic!("{view}: {e}"));
    assert_eq!(stats.rays.primary, u64::from(SIZE.0 * SIZE.1));
    to_srgb8(&film.pixels())
}

#[test]
fn one_backend_renders_scene_after_scene_on_either_device_as_the_cpu_tracer_does() {
    let scenes = [shipped("default.toml"), shipped("csg_die.toml")];
    let mut backend = backend();
    // The GPU's upload follows the scene: the second scene is not drawn with the first's
    // objects, and going back to the first uploads it again.
    for device in [Device::Cpu, Device::Gpu, Device::Cpu, Device::Gpu] {
        backend.set_device(device);
        for (k, assembled) in scenes.iter().chain(&scenes[..1]).enumerate() {
            let image = rendered(&mut backend, assembled, DebugView::Shaded);
            let on_cpu = to_srgb8(&render_image(&assembled.tracer()).0);
            let (mean, close) = difference(&image, &on_cpu);
            assert!(
                mean <= 0.5 && close >= 0.99,
                "{device}, scene {k}: mean {mean:.3} levels, {close} within 3"
            );
            assert!(
                backend.label().starts_with(&format!("{device}: ")),
                "{}",
                backend.label()
            );
        }
    }
}

#[test]
fn a_view_the_gpu_does_not_draw_is_refused_or_with_a_fallback_drawn_on_the_cpu() {
    let assembled = shipped("default.toml");
    let mut backend = backend();
    backend.set_device(Device::Gpu);
    let view = DebugView::RayCount;
    let film = Film::new(SIZE.0, SIZE.1);
    let control = RenderControl::default();
    let refused = backend.render(&assembled, view, (&film, &control), |_| {});
    assert_eq!(refused, Err(RenderError::ViewOnCpuOnly(view)));
    backend.set_fallback(true);
    let image = rendered(&mut backend, &assembled, view);
    assert!(
        backend
            .label()
            .starts_with("cpu: 2 threads (not the GPU: the rays view"),
        "{}",
        backend.label()
    );
    let on_cpu = to_srgb8(&render_image_with(&assembled.tracer(), &view).0);
    assert!(image == on_cpu, "the fallback's image is the CPU's");
}

#[test]
fn first_hits_from_the_item_buffer_give_the_rays_image_on_either_device() {
    let assembled = shipped("glass.toml");
    let mut backend = backend();
    let rays = to_srgb8(&render_image(&assembled.tracer()).0);
    backend.set_first_hit(FirstHit::Raster);
    for device in [Device::Cpu, Device::Gpu] {
        backend.set_device(device);
        let film = Film::new(SIZE.0, SIZE.1);
        let control = RenderControl::default();
        let stats = backend
            .render_unwatched(&assembled, DebugView::Shaded, (&film, &control))
            .unwrap();
        let r = &stats.rays;
        assert!(
            r.from_item_buffer as f64 >= 0.95 * r.primary_hits as f64 && r.primary_hits > 0,
            "{device}: {} of {} eye rays that hit came from the item buffer",
            r.from_item_buffer,
            r.primary_hits
        );
        let image = to_srgb8(&film.pixels());
        let (mean, close) = difference(&image, &rays);
        match device {
            // The CPU finds the same hits, only sooner.
            Device::Cpu => assert!(image == rays, "from the item buffer on the CPU"),
            Device::Gpu => assert!(mean <= 0.5 && close >= 0.99, "{mean} levels, {close}"),
        }
        // The CPU's item buffer is drawn before its render, the GPU's within it.
        assert_eq!(stats.raster_time.is_zero(), device == Device::Gpu);
    }
    // The item buffer inspect starts from is the one the renders start from.
    let items = backend.item_buffer(&assembled, ((0, 0), SIZE)).unwrap();
    let pixels = (0..SIZE.1).flat_map(|y| (0..SIZE.0).map(move |x| (x, y)));
    let covered = |items: raylab::item_buffer::ItemBuffer| {
        pixels.filter(|&(x, y)| items.at(x, y).is_some()).count()
    };
    assert!(
        items.map(covered).unwrap_or(0) > 0,
        "the item buffer holds items"
    );
    backend.set_first_hit(FirstHit::Rays);
    assert!(
        backend
            .item_buffer(&assembled, ((0, 0), SIZE))
            .unwrap()
            .is_none()
    );
}

#[test]
fn a_cancelled_render_says_so_on_either_device() {
    let assembled = shipped("default.toml");
    let mut backend = backend();
    for device in [Device::Cpu, Device::Gpu] {
        backend.set_device(device);
        let film = Film::new(SIZE.0, SIZE.1);
        let control = RenderControl::default();
        control.cancel();
        let result = backend.render(&assembled, DebugView::Shaded, (&film, &control), |_| {});
        assert_eq!(result, Err(RenderError::Cancelled), "{device}");
        assert_eq!(
            RenderError::Cancelled.to_string(),
            "the render was cancelled"
        );
    }
}
