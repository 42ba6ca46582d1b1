//! How much memory raylab may use, and refusing work that would need more. Readers and the
//! renderer estimate what they are about to allocate (a texture, an image, a file's parse tree)
//! and call [`check`] first, so that a small file that asks for too much gets a message saying
//! how much it would take instead of exhausting the machine.
//!
//! Every file raylab reads comes through [`read_file`]: only a regular file (not `/dev/zero`,
//! a pipe or a folder), its size checked against the limit before a byte is read.
//!
//! The limit is the memory the machine has available (Linux: `MemAvailable`, and the cgroup's
//! `memory.max` when a scheduler set one), or the environment variable `RAYLAB_MAX_MEMORY`
//! (bytes, or with a `K`, `M`, `G` or `T` suffix) when it is set.

use std::fmt;
use std::io::Read;
use std::path::Path;

/// The environment variable that sets the limit.
pub const LIMIT_VARIABLE: &str = "RAYLAB_MAX_MEMORY";

/// Bytes, printed for people (`7.2 GB`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let units = ["bytes", "KB", "MB", "GB", "TB"];
        let mut value = self.0 as f64;
        let mut unit = 0;
        while value >= 1000.0 && unit + 1 < units.len() {
            value /= 1000.0;
            unit += 1;
        }
        if unit == 0 {
            write!(f, "{} bytes", self.0)
        } else {
            write!(f, "{value:.1} {}", units[unit])
        }
    }
}

/// The memory raylab may use now, `None` where it cannot be told (no limit is enforced then).
pub fn available() -> Result<Option<u64>, String> {
    match std::env::var(LIMIT_VARIABLE) {
        Ok(text) => parse_size(&text)
            .map(Some)
            .ok_or_else(|| format!("{LIMIT_VARIABLE}={text}: expected bytes, like 512M or 8G")),
        Err(_) => Ok(system_available()),
    }
}

/// Checks that `what` (`a 16384×16384 image`), needing `needed` bytes, fits in [`available`].
pub fn check(what: &str, needed: u64) -> Result<(), String> {
    match available()? {
        Some(limit) if needed > limit => Err(format!(
            "{what} would take about {}, more than the {} of memory available \
             (set {LIMIT_VARIABLE} to change the limit)",
            Bytes(needed),
            Bytes(limit)
        )),
        _ => Ok(()),
    }
}

/// The bytes of the file at `path`, if it is a regular file (links followed) whose size fits in
/// memory: a device such as `/dev/zero`, a pipe or a folder is refused before reading, and so is
/// a file larger than [`available`] allows. The error says which (without the path: the caller
/// names the file).
pub fn read_file(path: &Path) -> Result<Vec<u8>, String> {
    let (file, size) = open_file(path)?;
    check(&format!("reading this {} file", Bytes(size)), size)?;
    let mut bytes = Vec::with_capacity(size as usize);
    // A file that grows while it is read is read only as far as its size was.
    file.take(size)
        .read_to_end(&mut bytes)
        .map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// The regular file at `path` (links followed), opened for reading, and its size; anything else
/// (a device, a pipe, a folder) is refused, as [`read_file`] refuses it.
pub fn open_file(path: &Path) -> Result<(std::fs::File, u64), String> {
    let metadata = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !metadata.is_file() {
        let kind = if metadata.is_dir() {
            "a folder"
        } else {
            "a device, a pipe or a socket"
        };
        return Err(format!(
            "it is {kind}, not a regular file; raylab reads only regular files"
        ));
    }
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    Ok((file, metadata.len()))
}

/// `512M`, `8G`, `1.5G`, `1000000`: a size in bytes with an optional binary suffix.
pub fn parse_size(text: &str) -> Option<u64> {
    let text = text.trim();
    let (number, scale) = match text.char_indices().last()? {
        (i, c) if c.is_ascii_alphabetic() => {
            let power = match c.to_ascii_uppercase() {
                'K' => 1,
                'M' => 2,
                'G' => 3,
                'T' => 4,
                _ => return None,
            };
            (&text[..i], 1024f64.powi(power))
        }
        _ => (text, 1.0),
    };
    let bytes = number.trim().parse::<f64>().ok()? * scale;
    (bytes.is_finite() && bytes >= 0.0 && bytes < u64::MAX as f64).then_some(bytes as u64)
}

/// What the operating system says is available: on Linux the smaller of `MemAvailable` and
/// what the cgroup (a container's or a scheduler job's limit) still allows.
fn system_available() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let available = meminfo
        .lines()
        .find_map(|line| line.strip_prefix("MemAvailable:"))
        .and_then(|rest| rest.trim().strip_suffix("kB"))
        .and_then(|kb| kb.trim().parse::<u64>().ok())?
        * 1024;
    let read = |name: &str| -> Option<u64> {
        let text = std::fs::read_to_string(format!("/sys/fs/cgroup/{name}")).ok()?;
        text.trim().parse().ok()
    };
    let cgroup_left =
        read("memory.max").map(|max| max.saturating_sub(read("memory.current").unwrap_or(0)));
    Some(cgroup_left.map_or(available, |left| left.min(available)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_with_and_without_suffixes() {
        assert_eq!(parse_size("1000"), Some(1000));
        assert_eq!(parse_size("512M"), Some(512 << 20));
        assert_eq!(parse_size(" 2g "), Some(2 << 30));
        assert_eq!(parse_size("1.5K"), Some(1536));
        assert_eq!(parse_size("lots"), None);
        assert_eq!(parse_size("-1G"), None);
        assert_eq!(parse_size("5X"), None);
    }

    #[test]
    fn bytes_print_for_people() {
        assert_eq!(Bytes(999).to_string(), "999 bytes");
        assert_eq!(Bytes(7_200_000_000).to_string(), "7.2 GB");
        assert_eq!(Bytes(1_500).to_string(), "1.5 KB");
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn only_regular_files_are_read() {
        for special in ["/dev/zero", "/dev/urandom"] {
            let error = read_file(Path::new(special)).unwrap_err();
            assert!(error.contains("not a regular file"), "{special}: {error}");
        }
        let error = read_file(Path::new("/")).unwrap_err();
        assert!(error.contains("a folder"), "{error}");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.txt");
        std::fs::write(&path, b"abc").unwrap();
        assert_eq!(read_file(&path).unwrap(), b"abc");
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn linux_reports_the_memory_available() {
        assert!(system_available().is_some_and(|bytes| bytes > 0));
    }
}
