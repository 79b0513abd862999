//! The dataset vocabulary of patchflow: plain data shared by the simulator, the learner and the
//! evaluation, and the one on-disk format (SemanticKITTI layout plus motion truth, SPEC §4).
//!
//! This crate knows nothing of Rapier: `learn` and `eval` read datasets through it without pulling
//! in the scene code.
//!
//! ```
//! use patchflow_dataset::{PointLabel, SemanticClass};
//! let label = PointLabel::new(SemanticClass::MovingCar, 7);
//! assert_eq!(label.semantic(), 252);
//! assert_eq!(label.instance(), 7);
//! ```

mod angle;
mod atomic_file;
mod error;
mod folder_lock;
mod input_file;
mod limits;
mod manifest;
mod object;
mod pose;
mod reader;
mod record_files;
mod seed_mix;
mod semantic;
mod sensor_info;
mod sequence_files;
mod static_obstacle;
mod sweep;
mod sweep_checks;
mod sweep_integrity;
mod writer;
mod written_files;

pub use angle::{wrap_angle_rad, wrap_angle_upper_rad};
pub use atomic_file::write_atomic;
pub use error::{DatasetError, Result};
pub use folder_lock::{FolderLock, LOCK_FILE};
pub use input_file::check_input_file;
pub use limits::{MAX_POINTS_PER_SWEEP, MAX_SWEEPS, read_limited};
pub use manifest::{FORMAT_NAME, FORMAT_VERSION, Manifest, SequenceInfo};
pub use object::{ActorClass, MAX_OBJECT_SIZE_M, MAX_OBJECT_SPEED_MPS, ObjectTruth};
pub use pose::{format_kitti_pose, parse_kitti_pose};
pub use reader::{Dataset, SequenceReader};
pub use seed_mix::{GOLDEN_GAMMA, fnv1a, splitmix64, splitmix64_finalize};
pub use semantic::{PointLabel, SemanticClass};
pub use sensor_info::{SensorInfo, SensorKind};
pub use static_obstacle::StaticObstacle;
pub use sweep::Sweep;
pub use sweep_integrity::sha256_hex;
pub use writer::SequenceWriter;
pub use written_files::remove_written_files;

/// Farthest a pose translation or object centre may lie from the world origin, metres: 1,000 km,
/// far beyond any scene, and where f32 sensor-frame points still resolve centimetres after
/// subtracting the pose.
pub const MAX_COORDINATE_M: f64 = 1e6;

/// Rigid transform type used for every pose (`world_from_sensor` and friends), f64 in the world frame.
pub type Pose = nalgebra::Isometry3<f64>;
