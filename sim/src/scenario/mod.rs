//! Scenario files: schema with defaults in code, loading with file-and-line errors, the embedded
//! scenario set, and seeded random traffic.

mod actor_config;
mod array_lengths;
mod bounds;
mod derived_limits;
mod embedded;
mod fleet;
mod lidar_config;
mod load;
mod planar_config;
mod pose_error_config;
mod problem;
mod realism;
mod road_config;
mod schema;
mod sensor_config;
mod structure_config;
mod traffic;
mod vehicle_mesh;
mod work_estimate;
mod world_config;
mod world_limits;

pub use actor_config::{ActorConfig, CarModel};
pub(crate) use bounds::gigabytes;
pub(crate) use derived_limits::{GROUND_HALF_M, sweep_memory_bytes};
pub use embedded::{EMBEDDED_OCCUPANCY_SCENARIOS, EMBEDDED_SCENARIOS};
pub use fleet::{VehicleBody, fleet_key};
pub(crate) use fleet::{drawn_bodies, reopen_for_fleet};
pub use lidar_config::{ElevationSpacing, LidarConfig, SensorKind};
pub use planar_config::{PLANAR_BEAMS, PLANAR_FOV_DEG, PLANAR_MAX_RANGE_M, PLANAR_MOUNT_HEIGHT_M};
pub use pose_error_config::{PoseErrorConfig, PoseErrorKnobs};
pub use realism::Realism;
pub use road_config::RoadConfig;
pub use schema::{Scenario, TrafficConfig};
pub use sensor_config::{SensorConfig, SensorKnobs};
pub use structure_config::{StructureConfig, StructureKind};
pub use traffic::random_traffic;
pub use vehicle_mesh::{MAX_MESH_TRIANGLES, VehicleMesh};
pub use work_estimate::WorkEstimate;
pub use world_config::{WorldConfig, WorldKnobs};
pub(crate) use world_limits::{GROUND_CELL_M, MAX_GROUND_CELLS, lidar_reach};
