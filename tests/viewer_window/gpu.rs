//! The viewer on the GPU tracer: the default scene rendered by the GPU shows what the CPU
//! renders, the window draws with the tracer's device and shows its film from the GPU (no
//! upload from the CPU), the status line says which traced it, and the device switch (script
//! step `device`) hands the render to the CPU.

use crate::harness::{cpu_render_sampled, image_rect, mismatches, run_to_screenshot};

#[test]
fn the_gpu_renders_in_the_window_what_the_cpu_renders_and_the_switch_hands_over() {
    let dir = tempfile::tempdir().unwrap();
    let size = 64;
    let (run, shot) = run_to_screenshot(
        dir.path(),
        &[
            "--device",
            "gpu",
            "--size",
            "64",
            "--samples",
            "4",
            "--aa-threshold",
            "0",
            "--window",
            "600x400",
            "--stats",
            "--script",
            "wait; print-status; device cpu; wait; print-status; device gpu; wait; print-status",
        ],
    );
    let statuses: Vec<&str> = run
        .stdout
        .lines()
        .filter(|l| l.starts_with("status: done"))
        .collect();
    assert_eq!(statuses.len(), 3, "{}", run.stdout);
    for (status, device) in statuses.iter().zip(["on gpu: ", "on cpu: ", "on gpu: "]) {
        assert!(status.contains(device), "{status}");
    }
    // The GPU's renders reached the texture from its film on the GPU, the CPU's by upload.
    let summary = run
        .stderr
        .lines()
        .find(|l| l.starts_with("stats: summary"))
        .unwrap_or_else(|| panic!("no summary in {}", run.stderr));
    let made = summary
        .split_once("ms on average (")
        .and_then(|(_, rest)| rest.split_once(" made on the GPU"))
        .map(|(counts, _)| counts)
        .unwrap_or_else(|| panic!("{summary}"));
    let (on_gpu, all) = made.split_once(" of ").unwrap();
    let (on_gpu, all): (u32, u32) = (on_gpu.parse().unwrap(), all.parse().unwrap());
    assert!(on_gpu >= 2 && on_gpu < all, "{summary}");
    // The GPU's colours may differ from the CPU's by rounding: a pixel in a hundred may be off
    // by more than 2 levels.
    let expected = cpu_render_sampled(size, 4, 0.0);
    let off = mismatches(&shot, image_rect(&run.stdout), size, &expected);
    assert!(off <= (size * size / 100) as usize, "{off} pixels differ");
}
