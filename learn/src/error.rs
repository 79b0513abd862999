//! The one error type of the learn crate. File, model-file, parameter, data and numerical
//! failures are the GP crate's [`GpError`] kinds, wrapped rather than copied; the constructors
//! below build them for learn's own code.

use std::path::Path;

use patchflow_gp::GpError;

/// Errors of feature extraction, GP training and prediction, and model files.
#[derive(Debug, thiserror::Error)]
pub enum LearnError {
    /// Reading a dataset failed (the message names the file).
    #[error(transparent)]
    Dataset(#[from] patchflow_dataset::DatasetError),
    /// A file, model-file, parameter, data or numerical failure, of the GP crate or of learn's
    /// own code (the message names the file where there is one).
    #[error(transparent)]
    Gp(#[from] GpError),
}

impl LearnError {
    /// A model file that is corrupt, of another kind, or of another version.
    pub(crate) fn model(path: &Path, reason: String) -> Self {
        Self::Gp(GpError::Model {
            path: path.to_path_buf(),
            reason,
        })
    }

    /// Parameters that failed validation.
    pub(crate) fn invalid_params(reason: String) -> Self {
        Self::Gp(GpError::InvalidParams(reason))
    }

    /// Training data that cannot be learned from (too few samples, non-finite values, ...).
    pub(crate) fn degenerate_data(reason: String) -> Self {
        Self::Gp(GpError::DegenerateData(reason))
    }
}

/// Result alias for the learn crate.
pub type Result<T> = std::result::Result<T, LearnError>;
