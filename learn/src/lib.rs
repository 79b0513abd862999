//! patchflow's learner: reflection and difference maps, single-link clusters, map-patch and Gabor
//! features (thesis Chapter 2), and the motion estimator on the sparse heteroscedastic Gaussian
//! processes of `patchflow-gp` (thesis Chapter 3).
//!
//! Where each thesis step lives (ARCHITECTURE.md has the full table):
//!
//! | thesis | file |
//! |---|---|
//! | 2.1.1 height slice (above the estimated ground) | `features/slice.rs`, `features/ground_*.rs` |
//! | 2.1.1-2.1.2 reflection map, difference map (Eq. 2.8-2.9) | `features/reflection_map.rs`, `features/difference_map.rs` |
//! | 2.2.1 single-link clusters | `features/cluster.rs`, `features/cluster_shape.rs` |
//! | 2.2.2 map patches | `features/patch.rs` |
//! | 2.2.3 Gabor responses | `features/gabor.rs` |
//! | 3.1.1-3.1.2 training samples, importance sampling | `features/training_sample.rs`, `features/sample_set.rs`, `features/run_sampler.rs`, `features/importance_sampling.rs` |
//! | 3.1.3 SPGP-HET objective | `patchflow-gp` (`learn/gp/src/fitc.rs`, `objective.rs`) |
//! | 3.1.4 merge ALL / BEST | `estimator/merge.rs` |
//! | Algorithm 3.1, the per-scan step | `estimator/scan_motion.rs` |
//!
//! Two sweeps of a synthetic street (a car driving away at 6 m/s, a wall beside the road, the ego
//! moving 0.5 m between them) give two clusters, and the car's heading patches hold far more
//! change than the wall's:
//!
//! ```
//! use patchflow_learn::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};
//! use patchflow_learn::{FeatureParams, SweepFeatures};
//!
//! let scene = SyntheticScene {
//!     boxes: vec![
//!         SceneBox::car(7, [14.0, 0.0], 0.0, 6.0),
//!         SceneBox::wall([0.0, 12.0], 0.0, [10.0, 0.4, 2.5]),
//!     ],
//! };
//! let lidar = SyntheticLidar::with_resolution(64, 1800);
//! let prev = scene.scan(&lidar, [0.0, -0.5], 0.0, 0);
//! let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
//! let params = FeatureParams { half_extent_m: 25.0, ..FeatureParams::default() };
//! let features = SweepFeatures::compute(&prev, &curr, &params)?;
//! assert_eq!(features.clusters().len(), 2);
//!
//! let change_where = |on: &dyn Fn(f64, f64) -> bool| {
//!     let idx: Vec<usize> =
//!         (0..features.len()).filter(|&i| on(features.points()[i].x_m, features.points()[i].y_m)).collect();
//!     idx.iter().map(|&i| features.heading_patch(i).mean_abs_difference()).sum::<f64>()
//!         / idx.len() as f64
//! };
//! let car = change_where(&|x, _| x > 5.0);
//! let wall = change_where(&|_, y| y > 10.0);
//! assert!(car > 3.0 * wall, "car {car}, wall {wall}");
//! # Ok::<(), patchflow_learn::LearnError>(())
//! ```

mod error;
mod estimator;
mod features;
mod moving;
mod timing;

// ── Errors ──────────────────────────────────────────────────────────────────────────────────
pub use error::{LearnError, Result};

// ── Parameters (thesis defaults, 4.3) ───────────────────────────────────────────────────────
pub use estimator::{BELOW_BELT_SLICE_M, EstimatorParams, EstimatorValidParams, WIDE_PATCH_CELL_M};
pub use features::{FeatureParams, FeatureValidParams, GaborParams, GroundMode};

// ── One sweep's features (thesis Chapter 2) ─────────────────────────────────────────────────
pub use features::{
    ClusterShape, Clusters, FeatureKind, FeatureTiming, FeaturedSweep, GaborBank, GridMap,
    GridWindow, GroundGrid, HeightSlice, MIN_OBJECT_POINTS, ObjectEnd, PATCH_LEN, Patch,
    RangeProfile, ScanStream, SlicedPoint, SweepFeatures, synthetic, write_png,
};

// ── Training samples (thesis 3.1.1-3.1.2) ───────────────────────────────────────────────────
pub use features::{Alignment, SampleSet, SideBalanced, TrainingSample, importance_sample};

// ── The motion estimator (thesis 3.1, Algorithm 3.1) ────────────────────────────────────────
pub use estimator::{
    ClusterEstimate, ClusterMotion, Gaussian, MAX_UNOBSERVED_BEFORE, MergeRule, MergedHeading,
    MotionEstimator, NoiseModel, PointMotion, PredictionTiming, Projection, Regressor,
    ScanEstimate, ScanMotion, TrainingRecord, kmeans, rows_to_matrix,
};

// ── Moving or static, learned (issue 27) ──────────────────────────────────────────────────
pub use moving::{
    BELIEF_MEMORY, CHANGE_BASELINE_SCANS, ChangeEvidence, MOVING_FILE_NAME, MOVING_FORMAT,
    MOVING_INPUT_NAMES, MOVING_INPUTS, MOVING_SPEED_MPS, MOVING_VERSION, MovingBelief,
    MovingClassifier, MovingParams, MovingRow, cluster_inputs, cluster_is_moving,
};

// ── The GPs (`patchflow-gp`) ─────────────────────────────────────────────────────────────────
pub use patchflow_gp::{GpError, GpKind, GpModel, GpParams, GpPrediction};
