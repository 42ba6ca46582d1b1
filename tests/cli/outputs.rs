//! Where the commands' output goes: a closed standard output, output paths refused before any
//! work, a symbolic link kept, and no temporary file left behind by a signal during a save.

use std::path::Path;
use std::process::{Command, Output};

use crate::common::run::{raylab, stderr};
use crate::harness::SMALL_BENCH;

/// Runs raylab with its standard output a pipe whose reader has gone (as `raylab … | head`
/// after `head` has read enough).
fn raylab_into_a_closed_pipe(args: &[&str], dir: &Path) -> Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .stdout(writer)
        .output()
        .expect("the binary runs")
}

/// The temporary files of unfinished writes in `dir`.
fn temporary_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with(".raylab-"))
        .collect()
}

/// Renders an image large enough that saving it takes a while, sends `signal` as soon as the
/// save has begun (its temporary file has data), and returns the exit code.
#[cfg(unix)]
fn signal_during_the_save(signal: &str, dir: &Path) -> Option<i32> {
    use std::time::{Duration, Instant};
    std::fs::write(dir.join("empty.toml"), "").unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args([
            "render",
            "empty.toml",
            "-o",
            "big.exr",
            "--width",
            "2000",
            "--height",
            "2000",
        ])
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // The probe of the path's folder makes an empty temporary file; the save's one has data.
    let saving = || {
        std::fs::read_dir(dir).unwrap().any(|e| {
            let e = e.unwrap();
            e.file_name().to_string_lossy().starts_with(".raylab-")
                && e.metadata().is_ok_and(|m| m.len() > 0)
        })
    };
    let deadline = Instant::now() + Duration::from_secs(120);
    while !saving() {
        if let Some(status) = child.try_wait().unwrap() {
            return status.code(); // Done before the save could be seen.
        }
        if Instant::now() > deadline {
            child.kill().unwrap();
            panic!("the save did not begin");
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    let pid = child.id().to_string();
    let sent = Command::new("kill")
        .args(["-s", signal, &pid])
        .status()
        .unwrap();
    assert!(sent.success());
    let deadline = Instant::now() + Duration::from_secs(60);
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            child.kill().unwrap();
            panic!("raylab did not stop after SIG{signal}");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    status.code()
}

#[test]
fn a_closed_standard_output_ends_every_command_quietly() {
    let dir = tempfile::tempdir().unwrap();
    let inspect = ["inspect", "--pixel", "1,1", "--width", "4", "--height", "4"];
    let cases: [&[&str]; 5] = [
        &["gen", "tree", "--size", "2"],
        &inspect,
        &[&inspect[..], &["--json"][..]].concat(),
        &["render", "--width", "8", "--height", "8", "-o", "a.png"],
        &SMALL_BENCH,
    ];
    for args in cases {
        let out = raylab_into_a_closed_pipe(args, dir.path());
        assert_eq!(out.status.code(), Some(0), "{args:?}: {}", stderr(&out));
        assert_eq!(stderr(&out), "", "{args:?}");
    }
    assert!(
        image::open(dir.path().join("a.png")).is_ok(),
        "saved before printing"
    );
}

#[test]
fn bad_output_paths_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("folder.png")).unwrap();
    std::fs::write(dir.path().join("locked.png"), b"keep").unwrap();
    let locked = dir.path().join("locked.png");
    let mut permissions = std::fs::metadata(&locked).unwrap().permissions();
    permissions.set_readonly(true);
    std::fs::set_permissions(&locked, permissions).unwrap();
    // The scene is missing too: the output's error coming first shows that it is checked
    // before the scene is read, let alone rendered.
    let cases: [(&[&str], &str); 6] = [
        (
            &["render", "missing.toml", "-o", "x.gif"],
            "unknown image format",
        ),
        (
            &["render", "missing.toml", "-o", "no/x.png"],
            "no/x.png: the folder no does not exist",
        ),
        (
            &["render", "missing.toml", "-o", "folder.png"],
            "folder.png: is a folder",
        ),
        (
            &["render", "missing.toml", "-o", "locked.png"],
            "locked.png: is read-only",
        ),
        (
            &["bench", "--scenes", "missing.toml", "--json", "no/b.json"],
            "no/b.json: the folder no does not exist",
        ),
        (
            &[
                "view",
                "missing.toml",
                "--exit-when-done",
                "--screenshot",
                "no/s.png",
            ],
            "no/s.png: the folder no does not exist",
        ),
    ];
    for (args, expected) in cases {
        let out = raylab(args, dir.path());
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let err = stderr(&out);
        assert!(err.contains(expected), "{args:?}: {err}");
    }
    assert_eq!(std::fs::read(&locked).unwrap(), b"keep");

    // The legend beside a debug view's image is checked before the render too: nothing is
    // written when it cannot be.
    std::fs::create_dir(dir.path().join("cost.legend.png")).unwrap();
    let out = raylab(
        &[
            "render", "-o", "cost.png", "--view", "bvh-cost", "--width", "8", "--height", "8",
        ],
        dir.path(),
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(
        stderr(&out).contains("cost.legend.png: is a folder"),
        "{}",
        stderr(&out)
    );
    assert!(!dir.path().join("cost.png").exists());
}

#[cfg(unix)]
#[test]
fn an_output_through_a_symbolic_link_keeps_the_link() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("renders")).unwrap();
    std::os::unix::fs::symlink("renders/latest.png", dir.path().join("out.png")).unwrap();
    let out = raylab(
        &["render", "-o", "out.png", "--width", "8", "--height", "8"],
        dir.path(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let link = std::fs::symlink_metadata(dir.path().join("out.png")).unwrap();
    assert!(link.file_type().is_symlink());
    assert!(image::open(dir.path().join("renders/latest.png")).is_ok());
}

#[cfg(unix)]
#[test]
fn a_signal_during_the_save_leaves_no_temporary_file() {
    for (signal, number) in [("TERM", 15), ("INT", 2)] {
        let dir = tempfile::tempdir().unwrap();
        let code = signal_during_the_save(signal, dir.path());
        // Stopped by the signal (128 + its number, as a shell reports it), or done just before.
        assert!(
            code == Some(128 + number) || code == Some(0),
            "SIG{signal}: exit code {code:?}"
        );
        assert_eq!(
            temporary_files(dir.path()),
            Vec::<String>::new(),
            "SIG{signal}"
        );
        if code == Some(0) {
            assert!(image::open(dir.path().join("big.exr")).is_ok());
        }
    }
}
