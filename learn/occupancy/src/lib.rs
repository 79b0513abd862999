//! Occupancy maps from planar range scans, after O'Callaghan & Ramos, *Gaussian Process
//! Occupancy Maps for Dynamic Environments* (SPEC §5b): training samples from scans (returns
//! occupied, free space along the beams), exact ground-truth occupancy from the dataset's truth,
//! the occupancy-grid baseline, GP occupancy maps, and ROC AUC against the truth at the paper's
//! query times. Depends on the dataset vocabulary and the GP crate, never on the motion-estimation
//! code.
//!
//! Map one planar scan of a wall 8 m ahead with GPOM and score it against the truth:
//!
//! ```
//! use patchflow_occupancy::{
//!     Beam, GpomMethod, MapMethod, PlanarScan, SampleParams, ScanWindow, roc_auc,
//! };
//! // 41 beams fanned over 90 degrees; those that reach y = 8 m within |x| <= 4 m hit the wall.
//! let beams = (0..41)
//!     .map(|j| {
//!         let a = (45.0 + 90.0 * f64::from(j) / 40.0_f64).to_radians();
//!         let range_m = 8.0 / a.sin();
//!         let hit = (a.cos() * range_m).abs() <= 4.0;
//!         let r = if hit { range_m } else { 12.0 };
//!         Beam { start_m: [0.0, 0.0], end_m: [a.cos() * r, a.sin() * r], hit }
//!     })
//!     .collect();
//! let scan = PlanarScan {
//!     index: 0,
//!     stamp_secs: 0.0,
//!     sensor_m: [0.0, 0.0],
//!     yaw_rad: std::f64::consts::FRAC_PI_2,
//!     beams,
//! };
//! let scans = [scan];
//! let window = ScanWindow { scans: &scans, query_secs: 0.0 };
//! // Query on the wall (occupied) and in the free space before it.
//! let points_m: Vec<[f64; 2]> =
//!     (-3..=3).flat_map(|x| [[f64::from(x), 8.0], [f64::from(x), 3.0]]).collect();
//! let occupied: Vec<bool> = points_m.iter().map(|p| p[1] == 8.0).collect();
//! let gpom = GpomMethod::space(SampleParams { free_spacing_m: 1.0, ..SampleParams::default() });
//! let map = gpom.map(&window, &points_m)?;
//! assert!(roc_auc(&map.probability, &occupied).is_some_and(|auc| auc > 0.95));
//! # Ok::<(), patchflow_occupancy::OccupancyError>(())
//! ```

mod auc;
mod changed_cells;
mod cluster_pairing;
mod dgpom;
mod error;
mod evaluation;
mod field_raster;
mod gp_solver;
mod gpom;
mod ground_truth;
mod map_jobs;
mod map_method;
mod map_method_id;
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
mod velocity_samples;

pub use auc::roc_auc;
pub use dgpom::{DgpomMethod, DgpomParams};
pub use error::{OccupancyError, Result};
pub use evaluation::{MapFigure, MethodScores, SequenceScores, evaluate_sequence};
pub use field_raster::FieldRaster;
pub use gp_solver::{GpSolver, TEMPORAL_RANGE_SECS};
pub use gpom::{GpomMethod, GpomSpace};
pub use ground_truth::{GroundTruth, OrientedBox};
pub use map_method::{MapMethod, MapOutput, ScanWindow};
pub use map_method_id::MapMethodId;
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
