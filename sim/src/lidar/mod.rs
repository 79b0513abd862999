//! The range sensor: a spinning lidar or a planar scanner; beam pattern, intensity model,
//! rolling-shutter ray casting.

mod beams;
mod block_caster;
mod firing_table;
mod intensity;
mod mixed_pixels;
mod planar_scanner;
mod real_return;
mod scan;
mod self_occlusion;
mod sensor_model;
mod spinning_lidar;

pub use beams::{elevations_deg, sensor_info};
pub use scan::Scan;
pub use spinning_lidar::Lidar;
