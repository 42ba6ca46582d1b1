//! Running the `raylab` binary as a user does, for the tests of its command line: its output, a
//! bound on how long it may take, and the most memory it held.

use std::io::Read;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

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

/// GNU time, which measures the command it runs. The peak memory of a process this test starts
/// itself would not do: Linux counts the starting process's own resident memory (a test binary's,
/// with its images) into the peak of the process it starts, up to that process's `exec`.
const TIME: &str = "/usr/bin/time";

/// Runs `raylab ARGS` in `dir` with the environment variables `env` set, under GNU time, and
/// measures the peak of its resident memory. The run fails the test if it takes longer than
/// `limit`: it is killed and the test says so.
pub fn raylab_measured(
    args: &[&str],
    dir: &Path,
    env: &[(&str, &str)],
    limit: Duration,
) -> Measured {
    let report = tempfile::NamedTempFile::new().expect("a file for the measurement");
    let mut child = Command::new(TIME)
        .args(["-f", "%M", "-o"])
        .arg(report.path())
        .arg(env!("CARGO_BIN_EXE_raylab"))
        .args(args)
        .current_dir(dir)
        .envs(env.iter().copied())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| {
            panic!("{TIME} runs the measured commands ({e}); install it: apt-get install time")
        });
    let drain = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            let _ = pipe.read_to_end(&mut bytes);
            bytes
        })
    };
    let stdout = drain(Box::new(child.stdout.take().expect("piped")));
    let stderr = drain(Box::new(child.stderr.take().expect("piped")));
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("the run can be waited for") {
            break status;
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
    let text = std::fs::read_to_string(report.path()).expect("GNU time's report");
    // The last line: a killed command's report starts with a line saying so. In kilobytes.
    let kilobytes: u64 = text
        .lines()
        .last()
        .and_then(|line| line.trim().parse().ok())
        .unwrap_or_else(|| panic!("no peak memory in GNU time's report: {text:?}"));
    Measured {
        output: Output {
            status,
            stdout: stdout.join().expect("read stdout"),
            stderr: stderr.join().expect("read stderr"),
        },
        peak_bytes: kilobytes * 1024,
    }
}
