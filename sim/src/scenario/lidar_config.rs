//! The `[lidar]` table: a spinning multi-beam lidar, by default like a Velodyne HDL-64E on KITTI's
//! car, or (`kind = "planar"`) a planar range scanner (see `planar_config.rs`).

use serde::{Deserialize, Serialize};

use super::bounds::{
    ATTENUATION_PER_M, DROPOUT, ELEVATION_DEG, FOV_DEG, MAX_RANGE_M, MOUNT_HEIGHT_M,
    RANGE_NOISE_STD_M, RATE_HZ, check_count,
};

/// How the channels' elevations are spread between `upper_deg` and `lower_deg`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ElevationSpacing {
    /// HDL-64E-like: an upper block (first half of the channels) at 2/3 of the lower block's
    /// spacing, then the lower block; for 64 channels over +2.0°…−24.8° this gives about 0.34°
    /// and 0.51°, as in a real S3 calibration.
    Hdl64e,
    /// Evenly spaced from `upper_deg` to `lower_deg`.
    Uniform,
}

/// Which range sensor the `[lidar]` table describes: the dataset's own type, one for both.
pub use patchflow_dataset::SensorKind;

/// Settings of the range sensor. Every field can be overridden in a scenario's `[lidar]` table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LidarConfig {
    /// Spinning lidar or planar scanner; a planar scanner fixes the spinner-only fields.
    #[serde(skip_serializing_if = "SensorKind::is_spinning")]
    pub kind: SensorKind,
    /// Number of channels (lasers), stacked vertically.
    pub channels: u32,
    /// Elevation of the highest channel, degrees.
    pub upper_deg: f64,
    /// Elevation of the lowest channel, degrees.
    pub lower_deg: f64,
    /// How the elevations are spread.
    pub spacing: ElevationSpacing,
    /// Turns per second; also the sweep rate.
    pub rate_hz: f64,
    /// Azimuth steps (columns) per turn.
    pub azimuth_steps: u32,
    /// Maximum range, metres.
    pub max_range_m: f64,
    /// Height of the optical centre above the ground, metres.
    pub mount_height_m: f64,
    /// Standard deviation of the Gaussian range noise along each ray, metres.
    pub range_noise_std_m: f64,
    /// Probability that a return is lost at random.
    pub dropout_probability: f64,
    /// Atmospheric attenuation of the intensity, per metre (`exp(−a·r)`).
    pub attenuation_per_m: f64,
    /// Cast each azimuth block at its own instant (true) or the whole sweep at its start (false).
    pub rolling_shutter: bool,
    /// Azimuth blocks per turn; the scene is moved once per block.
    pub blocks: u32,
    /// Horizontal field of view of a planar scanner, degrees, centred on the forward axis
    /// (planar only; resolved to 180).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fov_deg: Option<f64>,
    /// Beams of a planar scanner, evenly spread over `fov_deg` (planar only; resolved to 181).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beams: Option<u32>,
}

impl Default for LidarConfig {
    fn default() -> Self {
        Self {
            channels: 64,
            upper_deg: 2.0,
            lower_deg: -24.8,
            spacing: ElevationSpacing::Hdl64e,
            rate_hz: 10.0,
            azimuth_steps: 1800,
            max_range_m: 120.0,
            mount_height_m: 1.73,
            range_noise_std_m: 0.02,
            dropout_probability: 0.0,
            attenuation_per_m: 0.004,
            rolling_shutter: true,
            blocks: 60,
            kind: SensorKind::Spinning,
            fov_deg: None,
            beams: None,
        }
    }
}

impl LidarConfig {
    /// Seconds one turn (one sweep) takes.
    pub fn period_secs(&self) -> f64 {
        1.0 / self.rate_hz
    }

    /// Reasons this configuration is impossible, each with the offending field's name; every
    /// number is held to its [`bounds`](super::bounds) (rays per sweep are checked with the
    /// other derived sizes).
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out: Vec<(&'static str, String)> = [
            check_count(
                "channels",
                self.channels.into(),
                1,
                512,
                "lasers stacked in the head",
            ),
            ELEVATION_DEG.check("upper_deg", self.upper_deg),
            ELEVATION_DEG.check("lower_deg", self.lower_deg),
            RATE_HZ.check("rate_hz", self.rate_hz),
            check_count(
                "azimuth_steps",
                self.azimuth_steps.into(),
                8,
                100_000,
                "columns per turn",
            ),
            MAX_RANGE_M.check("max_range_m", self.max_range_m),
            MOUNT_HEIGHT_M.check("mount_height_m", self.mount_height_m),
            RANGE_NOISE_STD_M.check("range_noise_std_m", self.range_noise_std_m),
            DROPOUT.check("dropout_probability", self.dropout_probability),
            ATTENUATION_PER_M.check("attenuation_per_m", self.attenuation_per_m),
            check_count(
                "blocks",
                self.blocks.into(),
                1,
                self.azimuth_steps.into(),
                "at most one block per azimuth step",
            ),
            self.fov_deg.and_then(|fov| FOV_DEG.check("fov_deg", fov)),
            self.beams.and_then(|beams| {
                check_count("beams", beams.into(), 2, 100_000, "beams per planar scan")
            }),
        ]
        .into_iter()
        .flatten()
        .collect();
        if out.is_empty() && self.lower_deg > self.upper_deg {
            out.push((
                "lower_deg",
                format!(
                    "lower_deg = {} is above upper_deg = {}",
                    self.lower_deg, self.upper_deg
                ),
            ));
        }
        out
    }
}
