//! patchflow's evaluation: ICP and constant-velocity Kalman baselines (thesis 3.2), metrics, the
//! five-situation benchmark (thesis 4.4), cross-validation tables (thesis 4.3), reports and plots;
//! and the occupancy-map evaluation (the DGPOM paper's Table 1 and Figure 6).
//!
//! The top level re-exports what a user of the library needs: the benchmark driver, the methods
//! and their results, the baselines, cross-validation, the occupancy evaluation and the reports.
//! Progress bars live in [`progress`], the thesis' published numbers in [`thesis_tables`], and
//! the progress-bar wrappers of the benchmark's stages (for the binary) in [`stages`].
//!
//! | thesis / paper | file |
//! |---|---|
//! | 3.2 ICP baseline | `icp.rs`, `rigid_fit.rs`, `rigid_motion.rs` |
//! | 3.2 Kalman filter baseline | `kalman.rs`, `tracker.rs` (KF-AUTO), `cluster_association.rs` (ICP-AUTO) |
//! | 4.1 metrics (Eq. 4.1) | `metrics.rs`, `scene_flow.rs`, `objects.rs` |
//! | 4.3 cross-validation (Tables 4.1-4.4) | `cross_validation.rs` |
//! | 4.4 the five situations, scan by scan | `scene_evaluation.rs`, `baseline_step.rs` |
//! | DGPOM Table 1, Figure 6 | `occupancy/` |

mod baseline_params;
mod baseline_step;
mod baselines;
mod bench;
mod cluster_association;
mod cpu_time;
mod cross_validation;
mod cv_fold;
mod cv_params;
mod dataset_evaluation;
mod error;
mod estimate;
mod flow_export;
mod icp;
mod kalman;
mod learned_perception;
mod learned_step;
mod method;
mod metrics;
mod moving_iou;
mod objects;
mod observation;
mod occupancy;
mod oracle;
mod perception_summary;
mod perception_timing;
pub mod progress;
mod report;
mod result;
mod rigid_fit;
mod rigid_motion;
mod scan_scoring;
mod scene_evaluation;
mod scene_flow;
mod scene_point;
mod study;
pub mod thesis_tables;
mod tracker;
mod truth_at_scan;
mod velocity_measurement;

// ── The benchmark ──────────────────────────────────────────────────────────────────────────
pub use bench::{
    BENCH_SEED, BenchOutcome, BenchPlan, DENSE_TRAFFIC_TOML, MethodSpread,
    QUICK_REALISM_SITUATIONS, QUICK_SWEEP_SHARE, SeedFigure, SeedSpread, run_bench,
};
pub use error::EvalError;

/// The benchmark's stages one by one, each with its progress bar (the binary's `cv`,
/// `evaluate`, `generate` and `occupancy` commands run them).
pub mod stages {
    pub use crate::bench::{
        collect_draws_with_bar, collect_samples_with_bar, cross_validate_with_bar,
        evaluate_targets, evaluate_with_bar, generate_with_progress, occupancy_with_bar,
    };
}

// ── Methods, their estimates and scores (thesis 4.1, 4.4) ──────────────────────────────────
pub use dataset_evaluation::evaluate_dataset;
pub use estimate::MotionEstimate;
pub use flow_export::export_flow;
pub use learned_perception::{LearnedPerception, LearnedScan};
pub use method::{CANONICAL_METHODS, GpReadout, Method};
pub use metrics::{MIN_SCORED_SPEED_MPS, MethodMetrics, score_method};
pub use moving_iou::{MovingIou, is_moving_displacement};
pub use perception_summary::PerceptionSummary;
pub use result::{BenchmarkReport, SceneResult, SituationResult};
pub use study::{
    CELL_SIZES_M as STUDY_CELL_SIZES_M, FlowScores as StudyFlowScores,
    POINT_BINS as STUDY_POINT_BINS, PointResult, Scores, SensorSetting, StudyFactor, StudyFiles,
    StudyPlan, StudyPoint, StudyReport, discussion_section, merge_study, point_file,
    realism_in_bench, realism_sections, run_study, study_markdown, study_section, write_study,
};
pub use truth_at_scan::TruthAtScan;

// ── Baselines (thesis 3.2) ──────────────────────────────────────────────────────────────────
pub use baseline_params::BaselineParams;
pub use baselines::{BaselineMethod, run_baseline};
pub use icp::{IcpAlignment, IcpParams, align_icp, align_icp_from};
pub use kalman::{ConstantVelocityKalman, KalmanParams};
pub use rigid_motion::{RigidMotion, icp_motion_estimate, icp_rigid_motion, icp_rigid_motion_from};
pub use tracker::{MultiTargetTracker, TrackerParams};
pub use velocity_measurement::{VelocityFloors, VelocityMeasurement};

// ── Cross-validation (thesis 4.3) ───────────────────────────────────────────────────────────
pub use cross_validation::{cross_validate, cross_validate_samples};
pub use cv_params::CvParams;

// ── Occupancy maps (DGPOM paper, SPEC §5b) ──────────────────────────────────────────────────
pub use occupancy::{
    OccupancyReport, SequenceKind, dgpom_method, evaluate_occupancy, height_slice_scan,
    learn_motion_map, load_sequence, occupancy_methods, occupancy_sequences, predict_ahead,
    write_occupancy_report,
};

// ── Reports ─────────────────────────────────────────────────────────────────────────────────
pub use report::{
    CvFeature, CvGp, CvReport, CvRow, ReportFiles, SceneFigures, add_to_metrics, metrics_json,
    write_cv_report, write_dataset_scene_figures, write_map_figure, write_report,
    write_scene_figures,
};
