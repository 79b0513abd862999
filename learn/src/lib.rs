//! patchflow's learner: reflection and difference maps, single-link clusters, map-patch and Gabor
//! features (thesis Chapter 2), and the motion estimator on the sparse heteroscedastic Gaussian
//! processes of `patchflow-gp` (thesis Chapter 3), whose public names it re-exports.

mod error;
mod estimator;
mod features;
mod timing;

pub use error::{LearnError, Result};
pub use estimator::*;
pub use features::*;
pub use patchflow_gp::{
    FULL_GP_MAX_SAMPLES, FitReport, GP_MODEL_FORMAT, GP_MODEL_VERSION, GpError, GpKind, GpModel,
    GpObjective, GpParams, GpPrediction, GpValidParams, Standardiser,
};
