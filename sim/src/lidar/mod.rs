//! The spinning lidar: beam pattern, intensity model, rolling-shutter ray casting.

mod beams;
mod intensity;
mod spinning_lidar;

pub use beams::elevations_deg;

pub use spinning_lidar::{Lidar, Scan};
