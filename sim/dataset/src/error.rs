//! The one error type of the dataset crate: every variant names the file it is about.

use std::path::PathBuf;

/// Errors from reading or writing a dataset. Each names the file concerned.
#[derive(Debug, thiserror::Error)]
pub enum DatasetError {
    /// An operating-system error while reading or writing a file.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A file exists but its content is not what the format says.
    #[error("{path}: corrupt dataset file: {reason}")]
    Corrupt {
        /// The offending file.
        path: PathBuf,
        /// What is wrong, in plain words.
        reason: String,
    },
    /// A file is larger than its kind may be: refused before it is read.
    #[error("{path}: too large ({len} bytes, limit {limit})")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size.
        len: u64,
        /// The most such a file may hold.
        limit: u64,
    },
    /// A path given as input does not lead to a regular file (a folder, pipe, device, socket,
    /// or a loop of symbolic links).
    #[error("{path}: {what}")]
    NotRegular {
        /// The path.
        path: PathBuf,
        /// What it is instead, in words.
        what: String,
    },
    /// The dataset was written by an incompatible version of the format.
    #[error(
        "{path}: dataset format version {found} is not supported (this build reads version {expected})"
    )]
    Version {
        /// The manifest or marker file.
        path: PathBuf,
        /// Version found in the file.
        found: u32,
        /// Version this build reads and writes.
        expected: u32,
    },
    /// A sequence or sweep that was asked for is not in the dataset.
    #[error("{path}: {what} not found")]
    Missing {
        /// Where it was looked for.
        path: PathBuf,
        /// What was looked for.
        what: String,
    },
    /// The caller handed the writer inconsistent data (for example per-point arrays of different lengths).
    #[error("{path}: invalid data: {reason}")]
    Invalid {
        /// The file that would have been written.
        path: PathBuf,
        /// What is inconsistent.
        reason: String,
    },
}

/// Result alias for the dataset crate.
pub type Result<T> = std::result::Result<T, DatasetError>;

impl DatasetError {
    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }

    pub(crate) fn corrupt(path: impl Into<PathBuf>, reason: impl Into<String>) -> Self {
        Self::Corrupt {
            path: path.into(),
            reason: reason.into(),
        }
    }
}
