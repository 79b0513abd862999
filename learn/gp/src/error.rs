//! The one error type of the GP crate.

use std::path::PathBuf;

/// Errors of GP fitting, prediction, classification and model files.
#[derive(Debug, thiserror::Error)]
pub enum GpError {
    /// An operating-system error on a file.
    #[error("{path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
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

/// Result alias for the GP crate.
pub type Result<T> = std::result::Result<T, GpError>;
