//! Occupancy maps from planar range scans, after O'Callaghan & Ramos, *Gaussian Process
//! Occupancy Maps for Dynamic Environments* (SPEC §5b): training samples from scans (returns
//! occupied, free space along the beams), exact ground-truth occupancy from the dataset's truth,
//! the occupancy-grid baseline, GP occupancy maps, and ROC AUC against the truth at the paper's
//! query times. Depends on the dataset vocabulary and the GP crate, never on the motion-estimation
//! code.
//!
//! ```
//! use patchflow_occupancy::roc_auc;
//! let auc = roc_auc(&[0.9, 0.4, 0.4, 0.1], &[true, true, false, false]).unwrap();
//! assert!((auc - 0.875).abs() < 1e-12);
//! ```

mod auc;
mod dgpom;
mod error;
mod evaluation;
mod field_raster;
mod gp_solver;
mod gpom;
mod ground_truth;
mod map_method;
mod motion_accuracy;
mod motion_clusters;
mod motion_map;
mod occupancy_grid;
mod occupancy_sequence;
mod params;
mod planar_scan;
mod predict_ahead;
mod query_grid;
mod scan_cells;
mod thinning;
mod training_samples;

pub use auc::roc_auc;
pub use dgpom::{DgpomMethod, DgpomParams};
pub use error::{OccupancyError, Result};
pub use evaluation::{MapFigure, MethodScores, SequenceScores, evaluate_sequence};
pub use field_raster::FieldRaster;
pub use gp_solver::GpSolver;
pub use gpom::{GpomMethod, GpomSpace};
pub use ground_truth::{GroundTruth, OrientedBox};
pub use map_method::{MapMethod, MapOutput, ScanWindow};
pub use motion_accuracy::MotionAccuracy;
pub use motion_clusters::{Association, ClusterKind, MotionCluster, MotionClusterParams};
pub use motion_map::{MotionMap, MotionMapParams};
pub use occupancy_grid::OccupancyGridMethod;
pub use occupancy_sequence::OccupancySequence;
pub use params::OccupancyParams;
/// The velocity and error fields DGPOM's kernel reads, implemented by [`MotionMap`].
pub use patchflow_gp::MotionField;
pub use planar_scan::{Beam, PlanarScan};
pub use predict_ahead::{AheadParams, AheadScores, evaluate_ahead};
pub use query_grid::QueryGrid;
pub use thinning::Thinning;
pub use training_samples::{OccupancySample, SampleParams, scan_samples, window_samples};
