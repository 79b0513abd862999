//! What every reader checks before it opens a file: that the path leads to a regular file. A
//! FIFO or a character device would block the open or never end; a loop of symbolic links
//! would otherwise read as "no such file". The error says which, in words.

use std::path::Path;

use crate::{DatasetError, Result};

/// The size of the regular file at `path` (symbolic links followed), or an error naming it:
/// missing, a loop of links, a folder, or a pipe, device or socket.
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let err = patchflow_dataset::check_input_file(dir.path()).unwrap_err();
/// assert!(err.to_string().contains("is a folder"));
/// ```
pub fn check_input_file(path: &Path) -> Result<u64> {
    let meta = std::fs::metadata(path).map_err(|e| match e.raw_os_error() {
        Some(40) => DatasetError::NotRegular {
            path: path.to_owned(),
            what: "a loop of symbolic links: the path never reaches a file".to_owned(),
        },
        _ => DatasetError::io(path, e),
    })?;
    if meta.is_file() {
        return Ok(meta.len());
    }
    let what = if meta.is_dir() {
        "is a folder, not a file"
    } else {
        "is not a regular file (a pipe, device or socket); refusing to read from it, which could block forever"
    };
    Err(DatasetError::NotRegular {
        path: path.to_owned(),
        what: what.to_owned(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fifo_is_refused_without_being_opened() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("scenario.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            return; // no mkfifo on this machine: nothing to test
        }
        let err = crate::read_limited(&fifo, 1000).unwrap_err().to_string();
        assert!(
            err.contains("not a regular file") && err.contains("scenario.toml"),
            "{err}"
        );
    }

    #[test]
    fn a_device_and_a_symlink_loop_are_named_as_such() {
        let err = check_input_file(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("not a regular file"), "{err}");
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.toml"), dir.path().join("b.toml"));
        std::os::unix::fs::symlink(&b, &a).unwrap();
        std::os::unix::fs::symlink(&a, &b).unwrap();
        let err = check_input_file(&a).unwrap_err().to_string();
        assert!(err.contains("loop of symbolic links"), "{err}");
    }
}
