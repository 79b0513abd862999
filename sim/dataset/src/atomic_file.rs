//! The one atomic file write of the workspace: a temporary file beside the target, then a rename.
//! The dataset writer, the model files of `patchflow-learn` and the reports of `patchflow-eval`
//! all write through it, so a crash never leaves a truncated file under a real name.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::{DatasetError, Result};

/// Writes `bytes` to `path` atomically: a temporary file beside it, then a rename.
///
/// A crash leaves either the old file, the new file, or a stray `*.tmp`; never a truncated file
/// under the real name. The temporary name is unique to this process and call, so two writers
/// never share one; on an error it is removed, and [`crate::FolderLock::acquire`] removes any a
/// crashed run left behind.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut tmp = path.as_os_str().to_owned();
    let unique = COUNTER.fetch_add(1, Ordering::Relaxed);
    tmp.push(format!(".{}-{unique}.tmp", std::process::id()));
    let tmp = PathBuf::from(tmp);
    let written = std::fs::write(&tmp, bytes)
        .map_err(|e| DatasetError::io(&tmp, e))
        .and_then(|()| std::fs::rename(&tmp, path).map_err(|e| DatasetError::io(path, e)));
    if written.is_err() {
        // Best effort: the error being reported is the write's, not this clean-up's.
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_atomic_write_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        // Renaming a file onto a folder fails after the temporary file was written.
        let target = dir.path().join("000000.bin");
        std::fs::create_dir(&target).unwrap();
        assert!(write_atomic(&target, b"data").is_err());
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().flatten().collect();
        assert_eq!(left.len(), 1, "{left:?}");
    }
}
