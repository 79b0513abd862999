//! The one error type of the simulator: every variant names the file (and, for scenario files, the line).

use std::path::PathBuf;

/// Errors of the simulator and of dataset generation.
#[derive(Debug, thiserror::Error)]
pub enum SimError {
    /// A scenario file is malformed or asks for something impossible.
    #[error("{file}:{line}: {reason}")]
    Scenario {
        /// The scenario file (or the embedded scenario's name).
        file: String,
        /// 1-based line the problem is on.
        line: usize,
        /// What is wrong, in plain words.
        reason: String,
    },
    /// A scenario file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// Reading or writing the dataset failed.
    #[error(transparent)]
    Dataset(#[from] patchflow_dataset::DatasetError),
    /// Options of a generation run are inconsistent (bad shard, duplicate sequence names, ...).
    #[error("{0}")]
    Options(String),
}

/// Result alias of the simulator.
pub type Result<T> = std::result::Result<T, SimError>;

impl SimError {
    /// A scenario error at byte `offset` of `text`, reported as a line number.
    pub(crate) fn at_offset(
        file: &str,
        text: &str,
        offset: usize,
        reason: impl Into<String>,
    ) -> Self {
        Self::Scenario {
            file: file.to_owned(),
            line: line_of_offset(text, offset),
            reason: reason.into(),
        }
    }
}

/// The 1-based line that byte `offset` of `text` lies on.
pub(crate) fn line_of_offset(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_offsets_become_one_based_lines() {
        let text = "a = 1\nb = 2\nc = 3\n";
        assert_eq!(line_of_offset(text, 0), 1);
        assert_eq!(line_of_offset(text, 6), 2);
        assert_eq!(line_of_offset(text, 13), 3);
        assert_eq!(line_of_offset(text, 1000), 4);
    }
}
