//! patchflow's evaluation: ICP and constant-velocity Kalman baselines (thesis 3.2), metrics, the
//! five-situation benchmark (thesis 4.4), cross-validation tables (thesis 4.3), reports and plots;
//! and the occupancy-map evaluation (the DGPOM paper's Table 1 and Figure 6).
//!
//! The top level re-exports what a user of the library needs: the benchmark driver, the methods
//! and their results, the baselines, cross-validation, the occupancy evaluation and the reports.
//! Progress bars live in [`progress`], the thesis' published numbers in [`thesis_tables`], and
//! the progress-bar wrappers of the benchmark's stages (for the binary) in [`stages`].
//!
//! The crate is in rooms, one concept each; a room imports only rooms above it in this table
//! (`tests/module_imports.rs` checks that no two rooms import each other):
//!
//! | room | what | thesis / paper |
//! |---|---|---|
//! | `methods/` | the methods, their observations and estimates; `baselines/`, `learned/` | 3.2, issue 27 |
//! | `scene/` | the per-scan scene scoring: truth, metrics (Eq. 4.1), scene flow, objects | 4.1, 4.4 |
//! | `cv/` | cross-validation of the GP features | 4.3, Tables 4.1-4.4 |
//! | `report/` | the results as one value and its renderings (JSON, CSV, Markdown, plots) | 4.4 |
//! | `occupancy/` | the occupancy-map evaluation | DGPOM Table 1, Figure 6 |
//! | `pipeline/` | the benchmark's stages with progress bars, and their plan | SPEC §7 |
//! | `score/` | another method's predictions scored like the built-in ones | SPEC §7 |
//! | `study/` | one factor varied, every method scored at each point | issue #10 |
//! | `bench/` | the whole benchmark run, its report written once | SPEC §7 |
//! | `check/` | models read on targets of one's own over several worlds, against the bar | issue 24 |
//!
//! The Kalman baseline on a cluster centroid moving at 3 m/s along +y, measured every 0.1 s:
//!
//! ```
//! use patchflow_eval::{ConstantVelocityKalman, KalmanParams};
//!
//! let mut filter = ConstantVelocityKalman::new([10.0, 0.0], KalmanParams::default())?;
//! for k in 1..=20 {
//!     filter.predict(0.1);
//!     filter.update([10.0, 0.3 * f64::from(k)])?;
//! }
//! let estimate = filter.estimate().expect("twenty updates give an estimate");
//! assert!((estimate.speed_mps - 3.0).abs() < 0.1);
//! assert!((estimate.heading_rad - std::f64::consts::FRAC_PI_2).abs() < 0.05);
//! # Ok::<(), patchflow_eval::EvalError>(())
//! ```

mod bench;
mod check;
mod cv;
mod error;
mod methods;
mod occupancy;
mod pipeline;
mod report;
mod scene;
mod score;
mod study;

// ── The benchmark ──────────────────────────────────────────────────────────────────────────
pub use bench::{BenchOutcome, MethodSpread, SeedFigure, SeedSpread, run_bench};
pub use check::check_plan::{CheckPlan, parse_worlds};
pub use check::check_report::{CheckBar, CheckFiles, CheckReport, CheckTally, CheckedModel};
pub use check::run_checks::{CheckModel, run_checks};
pub use check::target_reading::TargetReading;
pub use error::EvalError;
pub use pipeline::plan::{
    BENCH_SEED, BenchPlan, DENSE_TRAFFIC_TOML, QUICK_REALISM_SITUATIONS, QUICK_SWEEP_SHARE,
};

/// Progress bars and stage timing for long commands.
pub mod progress {
    pub use crate::pipeline::progress::*;
    pub use crate::report::stage_timing::StageTiming;
}

/// The thesis' published numbers (Hess 2008, real data), printed beside ours.
pub use report::thesis_tables;

/// The benchmark's stages one by one, each with its progress bar (the binary's `cv`,
/// `evaluate`, `generate` and `occupancy` commands run them).
pub mod stages {
    pub use crate::pipeline::stages::{
        collect_samples_with_bar, cross_validate_with_bar, evaluate_with_bar,
        generate_with_progress, occupancy_with_bar,
    };
    pub use crate::pipeline::target_runs::{evaluate_targets, evaluate_targets_with_baselines};
}

// ── Methods, their estimates and scores (thesis 4.1, 4.4) ──────────────────────────────────
pub use methods::estimate::MotionEstimate;
pub use methods::learned::learned_perception::{LearnedPerception, LearnedScan};
pub use methods::method::{CANONICAL_METHODS, GpReadout, Method};
pub use pipeline::dataset_evaluation::{evaluate_dataset, scans_to_evaluate};
pub use report::benchmark_report::BenchmarkReport;
pub use report::perception_summary::PerceptionSummary;
pub use scene::flow_export::export_flow;
pub use scene::metrics::{MIN_SCORED_SPEED_MPS, MethodMetrics, score_method};
pub use scene::moving_iou::{MovingIou, is_moving_displacement};
pub use scene::result::{SceneResult, SituationResult};
pub use scene::truth_at_scan::TruthAtScan;
pub use score::{
    ExternalTally, MAX_PREDICTED_SPEED_MPS, MethodScores, MethodSource, MethodTally,
    PredictionFolder, ScoreFiles, ScoreReport, SequenceScores, score_predictions,
};
pub use study::{
    CELL_SIZES_M as STUDY_CELL_SIZES_M, FlowScores as StudyFlowScores,
    POINT_BINS as STUDY_POINT_BINS, PlanStamp, PointFile, PointResult, Scores, SensorSetting,
    StudyFactor, StudyFiles, StudyPlan, StudyPoint, StudyReport, discussion_section, merge_study,
    point_file, realism_in_bench, realism_sections, run_study, study_markdown, study_section,
    write_study,
};

// ── Baselines (thesis 3.2) ──────────────────────────────────────────────────────────────────
pub use methods::baselines::baseline_method::{BaselineMethod, run_baseline};
pub use methods::baselines::baseline_params::BaselineParams;
pub use methods::baselines::icp::{IcpAlignment, IcpParams, align_icp, align_icp_from};
pub use methods::baselines::kalman::{ConstantVelocityKalman, KalmanParams};
pub use methods::baselines::rigid_motion::{
    RigidMotion, icp_motion_estimate, icp_rigid_motion, icp_rigid_motion_from,
};
pub use methods::baselines::tracker::{MultiTargetTracker, TrackerParams};
pub use methods::baselines::velocity_measurement::{GpVelocityNoise, VelocityMeasurement};

// ── Cross-validation (thesis 4.3) ───────────────────────────────────────────────────────────
pub use cv::cross_validation::{cross_validate, cross_validate_samples};
pub use cv::cv_params::CvParams;
pub use cv::cv_report::{CvFeature, CvGp, CvReport, CvRow};

// ── Occupancy maps (DGPOM paper, SPEC §5b) ──────────────────────────────────────────────────
pub use occupancy::{
    OccupancyReport, SequenceKind, dgpom_method, evaluate_occupancy, height_slice_scan,
    learn_motion_map, load_sequence, occupancy_methods, occupancy_methods_with,
    occupancy_sequences, predict_ahead, predict_ahead_with, write_occupancy_report,
};

// ── Reports ─────────────────────────────────────────────────────────────────────────────────
pub use report::{
    ReportFiles, SceneFigures, metrics_json, write_cv_report, write_dataset_scene_figures,
    write_map_figure, write_report, write_report_with, write_scene_figures,
};
