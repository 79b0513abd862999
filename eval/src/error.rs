//! The one error type of `patchflow-eval`: every failure is a value that names its file or input.

use std::path::PathBuf;

/// Everything that can go wrong while running baselines, scoring them or writing reports.
#[derive(Debug, thiserror::Error)]
pub enum EvalError {
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder involved.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// Encoding or decoding JSON failed.
    #[error("{path}: JSON: {source}")]
    Json {
        /// The JSON file involved.
        path: PathBuf,
        /// The underlying serde_json error.
        source: serde_json::Error,
    },
    /// Drawing a plot failed.
    #[error("{path}: plot: {message}")]
    Plot {
        /// The PNG being drawn.
        path: PathBuf,
        /// What the plotting backend reported.
        message: String,
    },
    /// The observations handed to a baseline are unusable (e.g. time stamps that do not increase).
    #[error("situation {situation}, scan {scan}: {reason}")]
    BadObservation {
        /// Name of the situation (or `"-"` when unknown).
        situation: String,
        /// Scan number (`ScanObservation::scan`).
        scan: usize,
        /// What is wrong.
        reason: String,
    },
    /// A result handed to the metrics or the report writer is inconsistent.
    #[error("situation {situation}: {reason}")]
    BadResult {
        /// Name of the situation.
        situation: String,
        /// What is wrong.
        reason: String,
    },
    /// A file read back (a study point, a prediction) does not fit what reads it.
    #[error("{}: {reason}", path.display())]
    BadFile {
        /// The file.
        path: std::path::PathBuf,
        /// What is wrong, in a user's words.
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
    /// Feature extraction, GP training or prediction, or a model file failed.
    #[error(transparent)]
    Learn(#[from] patchflow_learn::LearnError),
    /// GP fitting or prediction failed (patchflow-gp, re-exported by patchflow-learn).
    #[error(transparent)]
    Gp(#[from] patchflow_learn::GpError),
    /// Building or scoring an occupancy map failed.
    #[error(transparent)]
    Occupancy(#[from] patchflow_occupancy::OccupancyError),
    /// Reading a dataset failed.
    #[error(transparent)]
    Dataset(#[from] patchflow_dataset::DatasetError),
    /// Simulating scenarios into a dataset failed.
    #[error("generating into {out}: {source}")]
    Sim {
        /// The dataset folder being written.
        out: PathBuf,
        /// What the simulator reported.
        source: patchflow_sim::SimError,
    },
}

impl EvalError {
    /// An I/O error about `path`.
    pub fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Self::Io {
            path: path.into(),
            source,
        }
    }
}
