//! The one error type of the occupancy crate: every failure is a value that says what input it
//! is about (the sequence folder or file, or the parameter).

use std::path::PathBuf;

/// Everything that can go wrong while building occupancy maps or scoring them.
#[derive(Debug, thiserror::Error)]
pub enum OccupancyError {
    /// Reading the dataset failed (a missing `static.json` or `sensor.json` names the file).
    #[error(transparent)]
    Dataset(#[from] patchflow_dataset::DatasetError),
    /// The dataset cannot be mapped as asked (wrong sensor, too few scans, ...).
    #[error("{path}: {reason}")]
    Unsupported {
        /// The sequence folder concerned.
        path: PathBuf,
        /// What is wrong, in plain words.
        reason: String,
    },
    /// A parameter is out of its valid range.
    #[error("invalid parameter {name}: {reason}")]
    BadParameter {
        /// Name of the parameter (`struct.field`).
        name: &'static str,
        /// Why it is invalid.
        reason: String,
    },
    /// The training data of a map cannot be fitted (no occupied or no free sample, a factorisation
    /// that failed even with jitter, ...).
    #[error("map {method} at scan {scan}: {reason}")]
    Degenerate {
        /// The map method.
        method: String,
        /// The query scan.
        scan: usize,
        /// What is wrong.
        reason: String,
    },
}

/// Result alias of the occupancy crate.
pub type Result<T> = std::result::Result<T, OccupancyError>;
