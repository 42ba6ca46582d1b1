//! Running the `raylab` binary as a user does, for the tests of its command line: its output, a
//! bound on how long it may take, and the most memory it held.

use std::io::Read;
use std::path::Path;
use std::process::{Command, ExitStatus, Output, Stdio};
use std::time::Duration;

/// Runs `raylab ARGS` in `dir` and returns what it did.
pub fn raylab(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// What a run wrote to standard error.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A run of `raylab` measured: what it did and the most memory it held resident (bytes).
pub struct Measured {
    pub output: Output,
    pub peak_bytes: u64,
}

/// Runs `raylab ARGS` in `dir` with the environment variables `env` set, and measures the peak
/// of its resident memory (the kernel's count for the process, `ru_maxrss`). The run fails the
/// test if it takes longer than `limit`: it is killed and the test says so.
pub fn raylab_measured(
    args: &[&str],
    dir: &Path,
    env: &[(&str, &str)],
    limit: Duration,
) -> Measured {
    let mut child = Command::new(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .envs(env.iter().copied())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    let drain = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            bytes
        })
    };
    let stdout = drain(Box::new(child.stdout.take().expect("piped")));
    let stderr = drain(Box::new(child.stderr.take().expect("piped")));
    let pid = child.id() as libc::pid_t;
    let start = std::time::Instant::now();
    let (status, usage) = loop {
        let mut status = 0;
        // SAFETY: an all-zero rusage is a valid value for wait4 to fill.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        // SAFETY: `pid` is our child, not yet waited for; the pointers are to live locals.
        let done = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        assert!(done >= 0, "waiting for raylab {args:?} failed");
        if done == pid {
            break (status, usage);
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "raylab {args:?} ran for more than {limit:?}: it should have finished or refused"
            );
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    // wait4 reaped it; std's own wait then only learns that there is nothing left to wait for.
    let _ = child.wait();
    use std::os::unix::process::ExitStatusExt;
    Measured {
        output: Output {
            status: ExitStatus::from_raw(status),
            stdout: stdout.join().expect("read stdout"),
            stderr: stderr.join().expect("read stderr"),
        },
        // Linux counts it in kilobytes.
        peak_bytes: usage.ru_maxrss as u64 * 1024,
    }
}
