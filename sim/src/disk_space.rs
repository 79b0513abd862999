//! Free space where a dataset is written, and what a run would still write there: `generate`
//! refuses up front a run whose bytes do not fit, instead of failing hours in with a full disk.

use std::path::Path;

use crate::error::{Result, SimError};
use crate::scenario::gigabytes;

/// Bytes free for this user on the file system holding `path` (or its nearest existing
/// ancestor, as the output folder may not exist yet); `None` where it cannot be read.
pub(crate) fn free_bytes(path: &Path) -> Option<u64> {
    // A relative path's last ancestor is "": the working folder.
    let existing = path
        .ancestors()
        .map(|p| match p.as_os_str().is_empty() {
            true => Path::new("."),
            false => p,
        })
        .find(|p| p.exists())?;
    #[cfg(unix)]
    {
        let stat = rustix::fs::statvfs(existing).ok()?;
        Some(stat.f_bavail.saturating_mul(stat.f_frsize))
    }
    #[cfg(not(unix))]
    {
        let _ = existing;
        None
    }
}

/// Bytes of the regular files under `dir` (0 if it does not exist): what an earlier run already
/// wrote and a resumed one keeps. Symbolic links are not followed.
pub(crate) fn bytes_under(dir: &Path) -> u64 {
    let mut total = 0u64;
    let mut stack = vec![dir.to_owned()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            if kind.is_dir() {
                stack.push(entry.path());
            } else if kind.is_file() {
                total = total.saturating_add(entry.metadata().map_or(0, |m| m.len()));
            }
        }
    }
    total
}

/// Refuses a run that would write `needed` bytes into `out` when `free` (bytes free there, if
/// known) is less.
pub(crate) fn check_disk_space(out: &Path, needed: u64, free: Option<u64>) -> Result<()> {
    match free {
        Some(free) if needed > free => Err(SimError::Options(format!(
            "{}: this run would write up to {} (every ray a point), but only {} is free there; free some space, write elsewhere, or generate fewer sweeps or rays",
            out.display(),
            gigabytes(needed),
            gigabytes(free)
        ))),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_space_is_read_for_a_folder_that_does_not_exist_yet() {
        let dir = tempfile::tempdir().unwrap();
        let free = free_bytes(&dir.path().join("not/yet/there")).unwrap();
        assert!(free > 0);
    }

    #[test]
    fn free_space_is_read_for_a_relative_folder_that_does_not_exist_yet() {
        assert!(free_bytes(Path::new("no-such-folder-here/data")).is_some_and(|b| b > 0));
    }

    #[test]
    fn a_run_larger_than_the_free_space_is_refused_naming_the_folder_and_both_sizes() {
        let out = Path::new("/data/out");
        let err = check_disk_space(out, 10_000_000_000_000, Some(2_000_000_000))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("/data/out") && err.contains("10000.0 GB") && err.contains("2.0 GB"),
            "{err}"
        );
        assert!(check_disk_space(out, 1_000, Some(2_000)).is_ok());
        assert!(check_disk_space(out, u64::MAX, None).is_ok());
    }

    #[test]
    fn the_bytes_under_a_folder_count_every_file() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("a/b")).unwrap();
        std::fs::write(dir.path().join("a/x"), [0u8; 10]).unwrap();
        std::fs::write(dir.path().join("a/b/y"), [0u8; 5]).unwrap();
        assert_eq!(bytes_under(dir.path()), 15);
        assert_eq!(bytes_under(&dir.path().join("missing")), 0);
    }
}
