//! The output files of one run, each written once with the atomic write: a second write of the
//! same file within the run is an error, so no stage patches a file that another stage wrote
//! (issue 29: the report used to be reopened and rewritten four times).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::error::EvalError;
use crate::report::files::write_atomic;

/// The files written so far in one run.
#[derive(Debug, Default)]
pub(crate) struct WriteOnce {
    written: BTreeSet<PathBuf>,
}

impl WriteOnce {
    /// Nothing written yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Writes `bytes` to `path` atomically, unless this run wrote `path` before.
    pub fn write(&mut self, path: &Path, bytes: &[u8]) -> Result<(), EvalError> {
        if !self.written.insert(path.to_owned()) {
            return Err(EvalError::BadResult {
                situation: path.display().to_string(),
                reason: "the run writes this file a second time (each output file is written \
                         once)"
                    .into(),
            });
        }
        write_atomic(path, bytes)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_write_of_the_same_file_is_refused_and_leaves_the_first() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("report.md");
        let mut files = WriteOnce::new();
        files.write(&path, b"first").unwrap();
        files
            .write(&dir.path().join("metrics.json"), b"{}")
            .unwrap();
        let err = files.write(&path, b"second").unwrap_err();
        assert!(err.to_string().contains("second time"), "{err}");
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
    }
}
