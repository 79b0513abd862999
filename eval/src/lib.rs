//! patchflow's evaluation: ICP and constant-velocity Kalman baselines (thesis 3.2), metrics, the
//! five-situation benchmark (thesis 4.4), cross-validation tables (thesis 4.3), reports and plots;
//! and the occupancy-map evaluation (the DGPOM paper's Table 1 and Figure 6).

mod baseline_step;
mod baselines;
mod bench;
mod cluster_association;
mod cpu_time;
mod cross_validation;
mod dataset_evaluation;
mod error;
mod estimate;
mod flow_export;
mod icp;
mod kalman;
mod method;
mod metrics;
mod objects;
mod observation;
mod occupancy;
mod oracle;
mod perception_summary;
mod perception_timing;
mod progress;
mod report;
mod result;
mod rigid_fit;
mod rigid_motion;
mod scan_scoring;
mod scene_evaluation;
mod scene_flow;
mod scene_point;
mod study;
mod thesis_tables;
mod tracker;
mod truth_at_scan;

pub use baseline_step::{BaselineScan, BaselineTrackers, ClusterFlow};
pub use baselines::{BaselineMethod, BaselineParams, run_all_baselines, run_baseline};
pub use bench::{
    BENCH_SEED, BenchOutcome, BenchPlan, DENSE_TRAFFIC_TOML, collect_samples_with_bar,
    cross_validate_with_bar, evaluate_with_bar, generate_with_progress, occupancy_with_bar,
    run_bench,
};
pub use cluster_association::{
    CentroidAssociationParams, CentroidAssociator, nearest_centroid_matches,
};
pub use cpu_time::{load_average, process_cpu_secs};
pub use cross_validation::{CvParams, cross_validate, cross_validate_samples};
pub use dataset_evaluation::{evaluate_dataset, scans_to_evaluate, sequences_to_evaluate};
pub use error::EvalError;
pub use estimate::MotionEstimate;
pub use flow_export::export_flow;
pub use icp::{IcpAlignment, IcpParams, align_icp};
pub use kalman::{ConstantVelocityKalman, Innovation, KalmanParams};
pub use method::{CANONICAL_METHODS, GpReadout, Method};
pub use metrics::{
    MIN_SCORED_SPEED_MPS, MethodMetrics, heading_error_deg, mean_abs, rmse, score_method,
    wrap_angle_rad,
};
pub use objects::{
    MIN_OBJECT_POINTS, ObjectGroup, ObjectMetrics, ObjectScan, POINT_BINS, RANGE_BINS_M,
    score_objects,
};
pub use observation::{ActorCluster, ClusterObservation, ScanObservation, centroid_of};
pub use occupancy::{
    MethodsFor, OccupancyFiles, OccupancyReport, PAPER_QUERY_TIMES, PAPER_TABLE_1, PaperRow,
    evaluate_occupancy, occupancy_json, occupancy_markdown, occupancy_methods, occupancy_notes,
    occupancy_section, occupancy_sequences, plot_occupancy_figure, write_occupancy_report,
};
pub use perception_summary::{PerceptionSummary, STAGES, StageOf};
pub use perception_timing::{ScanTiming, Spread, StepTiming};
pub use progress::{StageTimer, StageTiming, progress_bar, spinner};
pub use report::{
    CvFeature, CvGp, CvReport, CvRow, ReportFiles, metrics_json, metrics_json_value, plot_heading,
    plot_speed, write_cv_report, write_report,
};
pub use result::{BenchmarkReport, SceneResult, SituationResult};
pub use rigid_fit::{fit_rigid_closed_form, fit_rigid_svd};
pub use rigid_motion::{RigidMotion, icp_motion_estimate, icp_rigid_motion};
pub use scene_evaluation::{SequenceRun, evaluate_sequence};
pub use scene_flow::{
    DYNAMIC_SPEED_MPS, SPEED_BUCKETS, SceneFlowMetrics, SceneFlowTally, end_point_error,
};
pub use scene_point::{FlowClass, ScenePoints};
pub use study::{
    POINT_BINS as STUDY_POINT_BINS, PointResult, Scores, SensorSetting, StudyFactor, StudyFiles,
    StudyPlan, StudyPoint, StudyReport, discussion_section, merge_study, point_file,
    realism_in_bench, realism_sections, run_study, study_markdown, study_section, write_study,
};
pub use thesis_tables::{
    THESIS_CV_HEADING_LOW_VAR_RMSE_DEG, THESIS_CV_HEADING_RMSE_DEG,
    THESIS_CV_SPEED_LOW_VAR_RMSE_MPS, THESIS_CV_SPEED_RMSE_MPS, THESIS_SITUATIONS, ThesisRow,
    ThesisSituation, thesis_row, thesis_situation,
};
pub use tracker::{MultiTargetTracker, Track, TrackStatus, TrackerParams};
pub use truth_at_scan::TruthAtScan;
