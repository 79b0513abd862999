//! The spinning lidar: beam pattern, intensity model, rolling-shutter ray casting.

mod beams;
mod intensity;
mod lidar;

pub use beams::elevations_deg;

pub use lidar::{Lidar, Scan};
