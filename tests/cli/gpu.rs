//! `--device gpu` as a user meets it: `render` writes the CPU's image and names the adapter,
//! `bench` names it too, and what the GPU cannot do (no such adapter, a debug view, a scene it
//! does not trace yet) is a clear error with exit code 1, never a panic. These need a GPU
//! adapter (Mesa's lavapipe will do): without one they fail, saying what to install.

use std::process::Command;

use crate::common::run::{raylab, stderr};
use crate::harness::mean_level_difference;

/// `raylab render` of the default scene at 64 × 48 on `device`, as 8-bit sRGB pixels, and its
/// summary line and what it said on stderr.
fn render_on(device: &str, dir: &std::path::Path) -> (Vec<u8>, String, String) {
    let out = raylab(
        &[
            "render", "--device", device, "--size", "64x48", "-o", "out.png",
        ],
        dir,
    );
    assert!(out.status.success(), "{device}: {}", stderr(&out));
    let pixels = image::open(dir.join("out.png"))
        .unwrap()
        .to_rgb8()
        .into_raw();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    (pixels, stdout, stderr(&out))
}

#[test]
fn render_on_the_gpu_writes_the_cpus_image_and_names_the_adapter() {
    let dir = tempfile::tempdir().unwrap();
    let (on_gpu, gpu_summary, said) = render_on("gpu", dir.path());
    let (on_cpu, cpu_summary, _) = render_on("cpu", dir.path());
    assert!(gpu_summary.contains("(gpu: "), "{gpu_summary}");
    // The compile that a software adapter takes minutes for is announced, not silent.
    assert!(said.contains("compiling the GPU tracer for "), "{said}");
    assert!(
        cpu_summary.contains("(cpu: ") && cpu_summary.contains(" threads)"),
        "{cpu_summary}"
    );
    let mean = mean_level_difference(&on_gpu, &on_cpu);
    assert!(mean <= 0.5, "mean difference {mean} levels");
}

#[test]
fn bench_on_the_gpu_names_the_adapter() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "bench", "--device", "gpu", "--scenes", "default", "--size", "32", "--repeat", "1",
    ];
    let out = raylab(&args, dir.path());
    assert!(out.status.success(), "{}", stderr(&out));
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(report.starts_with("32×32 pixels, gpu: "), "{report}");
    let scaling = raylab(&[&args[..], &["--scaling"]].concat(), dir.path());
    assert_eq!(scaling.status.code(), Some(1), "{}", stderr(&scaling));
    assert!(stderr(&scaling).contains("--scaling measures the CPU's threads"));
    // The other layout of the BVH's nodes traces the same rays, and says so in the header.
    let binary = raylab(
        &[&args[..], &["--gpu-nodes", "binary"]].concat(),
        dir.path(),
    );
    assert!(binary.status.success(), "{}", stderr(&binary));
    let binary_report = String::from_utf8_lossy(&binary.stdout);
    assert!(
        binary_report
            .lines()
            .next()
            .unwrap()
            .ends_with("; BVH nodes: binary"),
        "{binary_report}"
    );
    let rays = |report: &str| {
        let row = report.lines().find(|l| l.starts_with("default")).unwrap();
        let columns: Vec<String> = row.split_whitespace().map(String::from).collect();
        columns[6..10].to_vec()
    };
    assert_eq!(
        rays(&binary_report),
        rays(&report),
        "{binary_report}\n{report}"
    );
    let on_cpu = raylab(&["bench", "--gpu-nodes", "binary"], dir.path());
    assert_eq!(on_cpu.status.code(), Some(1), "{}", stderr(&on_cpu));
    assert!(stderr(&on_cpu).contains("--gpu-nodes lays out the GPU's BVH: add --device gpu"));
}

#[test]
fn what_the_gpu_cannot_do_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let no_adapter = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(["render", "--device", "gpu", "--size", "16", "-o", "out.png"])
        .current_dir(dir.path())
        .env("WGPU_ADAPTER_NAME", "no-such-gpu")
        .output()
        .unwrap();
    for (out, expected) in [
        (no_adapter, "WGPU_ADAPTER_NAME=\"no-such-gpu\""),
        (
            raylab(
                &[
                    "render", "--device", "gpu", "--view", "rays", "--size", "16", "-o", "out.png",
                ],
                dir.path(),
            ),
            "--view rays traces on the CPU only",
        ),
        (
            raylab(&["render", "--device", "tpu", "-o", "out.png"], dir.path()),
            "unknown device `tpu`",
        ),
    ] {
        let message = stderr(&out);
        assert!(message.contains(expected), "{message}");
        assert!(!message.contains("panicked"), "{message}");
        assert!(matches!(out.status.code(), Some(1 | 2)), "{message}");
    }
    assert!(
        !dir.path().join("out.png").exists(),
        "no image for a refused render"
    );
}
