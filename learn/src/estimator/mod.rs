//! The motion estimator of thesis 3.1: per-point GP predictions from map patches, merged per cluster.

mod merge;
mod model_file;
mod motion_estimator;
mod params;

pub use merge::{Gaussian, HeadingVote, MergeRule, MergedHeading, merge_heading, merge_scalar};
pub use model_file::{MOTION_MODEL_FORMAT, MOTION_MODEL_VERSION};
pub use motion_estimator::{ClusterEstimate, ClusterMotion, MotionEstimator, TrainingRecord};
pub use params::EstimatorParams;
