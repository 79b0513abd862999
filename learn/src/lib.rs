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
//! | 3.1.1-3.1.2 training samples, importance sampling | `features/samples.rs`, `features/sampler.rs`, `features/sampling.rs` |
//! | 3.1.3 SPGP-HET objective | `patchflow-gp` (`learn/gp/src/fitc.rs`, `objective.rs`) |
//! | 3.1.4 merge ALL / BEST | `estimator/merge.rs` |
//! | Algorithm 3.1, the per-scan step | `estimator/scan_motion.rs` |

mod error;
mod estimator;
mod features;
mod timing;

// ── Errors ──────────────────────────────────────────────────────────────────────────────────
pub use error::{LearnError, Result};

// ── Parameters (thesis defaults, 4.3) ───────────────────────────────────────────────────────
pub use estimator::{EstimatorParams, EstimatorValidParams};
pub use features::{FeatureParams, FeatureValidParams, GaborParams, GroundMode};

// ── One sweep's features (thesis Chapter 2) ─────────────────────────────────────────────────
pub use features::{
    ClusterShape, Clusters, FeatureKind, FeatureTiming, GaborBank, GridMap, GridWindow, GroundGrid,
    HeightSlice, MIN_OBJECT_POINTS, PATCH_LEN, Patch, Scan, ScanStream, SlicedPoint, SweepFeatures,
    synthetic, write_png,
};

// ── Training samples (thesis 3.1.1-3.1.2) ───────────────────────────────────────────────────
pub use features::{Alignment, Sample, SampleSet, importance_sample};

// ── The motion estimator (thesis 3.1, Algorithm 3.1) ────────────────────────────────────────
pub use estimator::{
    ClusterEstimate, ClusterMotion, Gaussian, MergeRule, MergedHeading, MotionEstimator,
    NoiseModel, PointMotion, PredictionTiming, Projection, Regressor, ScanEstimate, ScanMotion,
    TrainingRecord, kmeans, rows_to_matrix,
};

// ── The GPs (`patchflow-gp`) ─────────────────────────────────────────────────────────────────
pub use patchflow_gp::{GpError, GpKind, GpModel, GpParams, GpPrediction};
