//! The viewer as a process: idle once refined it uses no CPU, without a display it says so and
//! fails, and its help documents its options.

use std::process::Command;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use crate::harness::run_viewer_watching;

/// The viewer's process: `pid` itself or its child named raylab (under xvfb-run).
fn viewer_pid(pid: u32) -> Option<u32> {
    let comm = |p: u32| std::fs::read_to_string(format!("/proc/{p}/comm")).unwrap_or_default();
    if comm(pid).trim() == "raylab" {
        return Some(pid);
    }
    std::fs::read_dir("/proc")
        .ok()?
        .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
        .find(|&p| comm(p).trim() == "raylab" && stat_fields(p).get(1) == Some(&pid.to_string()))
}

/// The fields of /proc/PID/stat after the command's name: state, parent, …
fn stat_fields(pid: u32) -> Vec<String> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
    let after_name = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    after_name.split_whitespace().map(String::from).collect()
}

/// User and system CPU time of a process so far, in clock ticks.
fn cpu_ticks(pid: u32) -> u64 {
    let fields = stat_fields(pid);
    let field = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<u64>().ok())
            .unwrap_or(0)
    };
    field(11) + field(12)
}

#[test]
fn an_idle_viewer_uses_no_cpu() {
    let measured = Arc::new(Mutex::new(None));
    let result = measured.clone();
    // Once refinement is done (anti-aliasing included), measure the viewer's CPU time for two
    // seconds, then close it.
    let on_line = move |line: &str, child: u32| {
        if line.contains("refined at") && result.lock().unwrap().is_none() {
            let pid = viewer_pid(child).expect("the viewer's process");
            std::thread::sleep(Duration::from_millis(500));
            let before = cpu_ticks(pid);
            std::thread::sleep(Duration::from_secs(2));
            let used = cpu_ticks(pid) - before;
            *result.lock().unwrap() = Some(used);
            let _ = Command::new("kill").arg(pid.to_string()).status();
        }
    };
    let run = run_viewer_watching(&["--size", "64", "--stats"], &[], on_line);
    let used = measured
        .lock()
        .unwrap()
        .unwrap_or_else(|| panic!("{}", run.stderr));
    assert!(
        used <= 5,
        "an idle viewer used {used} clock ticks of CPU in 2 s"
    );
}

#[test]
fn without_a_display_the_viewer_says_so_and_fails() {
    let output = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(["view", "--exit-when-done"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success());
    assert!(stderr.contains("display"), "{stderr}");
    assert!(stderr.contains("raylab render"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn help_documents_the_viewer() {
    for args in [&["--help"][..], &["view", "--help"][..]] {
        let output = Command::new(env!("CARGO_BIN_EXE_raylab"))
            .args(args)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&output.stdout);
        assert!(output.status.success());
        for option in [
            "--size",
            "--block-size",
            "--screenshot",
            "--exit-when-done",
            "--script",
            "--view",
        ] {
            assert!(text.contains(option), "{args:?} lacks {option}: {text}");
        }
    }
}
