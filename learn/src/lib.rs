//! patchflow's learner: reflection and difference maps, single-link clusters, map-patch and Gabor
//! features (thesis Chapter 2), and sparse heteroscedastic Gaussian processes (thesis Chapter 3).

mod error;
mod estimator;
mod features;
mod table;

pub use error::{LearnError, Result};
pub use estimator::*;
pub use features::*;
pub use patchflow_gp::{
    FULL_GP_MAX_SAMPLES, FitReport, GP_MODEL_FORMAT, GP_MODEL_VERSION, GpError, GpKind, GpModel,
    GpObjective, GpParams, GpPrediction, GpValidParams, Standardiser,
};
pub use table::{Columns, Table, TrainingColumns};
