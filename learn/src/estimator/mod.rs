//! The motion estimator of thesis 3.1: per-point GP predictions from map patches, merged per cluster.

mod merge;
mod motion_estimator;
mod params;

pub use merge::{Gaussian, HeadingVote, MergeRule, MergedHeading, merge_heading, merge_scalar};
pub use motion_estimator::{ClusterEstimate, ClusterMotion, MotionEstimator, TrainingRecord};
pub use params::EstimatorParams;
