//! patchflow's learner: reflection and difference maps, single-link clusters, map-patch and Gabor
//! features (thesis Chapter 2), and sparse heteroscedastic Gaussian processes (thesis Chapter 3).

mod error;
mod estimator;
mod features;
mod gp;
mod timing;

pub use error::{LearnError, Result};
pub use estimator::*;
pub use features::*;
pub use gp::*;
