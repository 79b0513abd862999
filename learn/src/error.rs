//! The one error type of the learn crate.

use std::path::PathBuf;

/// Errors of feature extraction, GP training and prediction, and model files.
#[derive(Debug, thiserror::Error)]
pub enum LearnError {
    /// Reading a dataset failed (the message names the file).
    #[error(transparent)]
    Dataset(#[from] patchflow_dataset::DatasetError),
    /// GP fitting, prediction or a GP model file failed (the message names the file).
    #[error(transparent)]
    Gp(#[from] patchflow_gp::GpError),
    /// An operating-system error on a file.
    #[error("{path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A CSV or other input file has bad content.
    #[error("{path}: line {line}: {reason}")]
    Parse {
        /// The file concerned.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A model file is corrupt, of another kind, or of another version.
    #[error("{path}: {reason}")]
    Model {
        /// The model file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// Parameters failed validation.
    #[error("invalid parameters: {0}")]
    InvalidParams(String),
    /// The training data cannot be learned from (too few samples, non-finite values, ...).
    #[error("degenerate training data: {0}")]
    DegenerateData(String),
    /// A factorisation failed even after the jitter retries.
    #[error("numerical failure: {0}")]
    Numerical(String),
}

/// Result alias for the learn crate.
pub type Result<T> = std::result::Result<T, LearnError>;
