//! patchflow's evaluation: ICP and constant-velocity Kalman baselines (thesis 3.2), metrics, the
//! five-situation benchmark (thesis 4.4), cross-validation tables (thesis 4.3), reports and plots.

mod baselines;
mod cluster_association;
mod error;
mod estimate;
mod icp;
mod kalman;
mod metrics;
mod observation;
mod progress;
mod result;
mod rigid_fit;
mod tracker;

pub use baselines::{BaselineMethod, BaselineParams, run_all_baselines, run_baseline};
pub use cluster_association::{
    CentroidAssociationParams, CentroidAssociator, nearest_centroid_matches,
};
pub use error::EvalError;
pub use estimate::MotionEstimate;
pub use icp::{IcpAlignment, IcpParams, align_icp, icp_motion_estimate};
pub use kalman::{ConstantVelocityKalman, Innovation, KalmanParams};
pub use metrics::{
    MIN_SCORED_SPEED_MPS, MethodMetrics, heading_error_deg, mean_abs, rmse, score_method,
    wrap_angle_rad,
};
pub use observation::{ClusterObservation, ScanObservation, centroid_of};
pub use progress::{StageTimer, StageTiming, progress_bar, spinner};
pub use result::{BenchmarkReport, SituationResult, TruthAtScan};
pub use rigid_fit::{fit_rigid_closed_form, fit_rigid_svd};
pub use tracker::{MultiTargetTracker, Track, TrackStatus, TrackerParams};
