//! The patchflow simulator: scenario files → Rapier scene → rolling-shutter spinning lidar →
//! labelled sweeps in the dataset format of SPEC §4.
//!
//! ```
//! let text = "sweeps = 1\n[lidar]\nchannels = 8\nazimuth_steps = 90\nblocks = 9\n[ego]\npath_m = [[0.0, 0.0], [50.0, 0.0]]\nspeed_mps = 5.0\n";
//! let scenario = patchflow_sim::Scenario::from_toml(text, "doc.toml", "doc").unwrap();
//! let sweep = patchflow_sim::Simulation::new(&scenario, 7).unwrap().sweep(0);
//! assert_eq!(sweep.labels.len(), sweep.len());
//! ```

mod disk_space;
mod error;
mod generate;
#[cfg(test)]
mod ground_contact_tests;
mod kitti_names;
mod lidar;
mod memory_budget;
mod motion;
mod output_folder;
mod pose_error;
mod provenance;
#[cfg(test)]
mod resume_tests;
mod scenario;
mod scenario_source;
mod scene;
mod seed;
mod sequence_queue;
mod shard;
mod simulation;
mod world;

pub use error::{Result, SimError};
pub use generate::{GenerateOptions, Progress, Shard, generate_dataset, generate_sequence};
pub use kitti_names::write_kitti_names;
pub use lidar::{Lidar, Scan, elevations_deg, sensor_info};
pub use memory_budget::{MemoryBudget, memory_budget};
pub use motion::MOVING_SPEED_MPS;
pub use motion::{MotionState, Path, PathPoint, ProfileState, SpeedProfile, Trajectory};
pub use patchflow_dataset as dataset;
pub use scenario::fleet_key;
pub use scenario::{
    ActorConfig, CarModel, EMBEDDED_OCCUPANCY_SCENARIOS, EMBEDDED_SCENARIOS, ElevationSpacing,
    LidarConfig, MAX_MESH_TRIANGLES, PLANAR_BEAMS, PLANAR_FOV_DEG, PLANAR_MAX_RANGE_M,
    PLANAR_MOUNT_HEIGHT_M, PoseErrorConfig, PoseErrorKnobs, Realism, RoadConfig, Scenario,
    SensorConfig, SensorKind, SensorKnobs, StructureConfig, StructureKind, TrafficConfig,
    VehicleBody, VehicleMesh, WorkEstimate, WorldConfig, WorldKnobs,
};
pub use scenario_source::ScenarioSource;
pub use scene::{QueryTree, Scene, SceneActor};
pub use seed::sweep_key;
pub use simulation::Simulation;
