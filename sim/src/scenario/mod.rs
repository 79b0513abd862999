//! Scenario files: schema with defaults in code, loading with file-and-line errors, the embedded
//! scenario set, and seeded random traffic.

mod actor_config;
mod bounds;
mod derived_limits;
mod embedded;
mod lidar_config;
mod load;
mod schema;
mod structure_config;
mod traffic;

pub use actor_config::{ActorConfig, CarModel};
pub(crate) use derived_limits::{GROUND_HALF_M, gigabytes, sweep_memory_bytes};
pub use embedded::EMBEDDED_SCENARIOS;
pub use lidar_config::{ElevationSpacing, LidarConfig};
pub use schema::{Scenario, TrafficConfig};
pub use structure_config::{StructureConfig, StructureKind};
pub use traffic::random_traffic;
