//! The motion estimator of thesis 3.1: per-point GP predictions from map patches, merged per
//! cluster; the per-scan step of Algorithm 3.1 in `scan_motion.rs`.

mod cluster_estimate;
mod cluster_prediction;
mod feature_matrix;
mod kmeans;
mod merge;
mod model_file;
mod motion_estimator;
mod params;
mod projection;
mod regressor;
mod scan_motion;

pub use cluster_estimate::{
    ClusterEstimate, ClusterMotion, PointMotion, PredictionTiming, ScanEstimate, ScanMotion,
};
pub use feature_matrix::rows_to_matrix;
pub use kmeans::kmeans;
pub use merge::{Gaussian, MergeRule, MergedHeading};
pub use motion_estimator::{MotionEstimator, TrainingRecord};
pub use params::{BELOW_BELT_SLICE_M, EstimatorParams, EstimatorValidParams, WIDE_PATCH_CELL_M};
pub use projection::Projection;
pub use regressor::{NoiseModel, Regressor};
pub use scan_motion::MAX_UNOBSERVED_BEFORE;
