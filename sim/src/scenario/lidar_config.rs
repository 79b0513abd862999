//! The `[lidar]` table: a spinning multi-beam lidar, by default like a Velodyne HDL-64E on KITTI's
//! car, or (`kind = "planar"`) a planar range scanner (see `planar_config.rs`).

use serde::{Deserialize, Serialize};

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

/// Which range sensor the `[lidar]` table describes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensorKind {
    /// A spinning multi-beam lidar (the default, HDL-64E-like).
    #[default]
    Spinning,
    /// A planar range scanner: one channel at 0° elevation, `beams` beams over `fov_deg`
    /// centred on the sensor's forward axis, each scan cast at one instant (SICK LMS291-like).
    Planar,
}

impl SensorKind {
    /// True for the spinning lidar (the kind left out of resolved scenario files).
    pub fn is_spinning(&self) -> bool {
        *self == Self::Spinning
    }
}

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

    /// Reasons this configuration is impossible, each with the offending field's name.
    pub(crate) fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        let mut check = |field: &'static str, ok: bool, reason: String| {
            if !ok {
                out.push((field, reason));
            }
        };
        check(
            "channels",
            (1..=512).contains(&self.channels),
            format!("channels must be 1 to 512, got {}", self.channels),
        );
        check(
            "upper_deg",
            self.upper_deg.is_finite() && self.upper_deg.abs() < 90.0,
            format!(
                "upper_deg must be a finite angle within ±90°, got {}",
                self.upper_deg
            ),
        );
        check(
            "lower_deg",
            self.lower_deg.is_finite()
                && self.lower_deg.abs() < 90.0
                && self.lower_deg <= self.upper_deg,
            format!(
                "lower_deg must be finite, within ±90° and not above upper_deg, got {}",
                self.lower_deg
            ),
        );
        check(
            "rate_hz",
            self.rate_hz.is_finite() && self.rate_hz > 0.0 && self.rate_hz <= 100.0,
            format!("rate_hz must be in (0, 100], got {}", self.rate_hz),
        );
        check(
            "azimuth_steps",
            (8..=100_000).contains(&self.azimuth_steps),
            format!(
                "azimuth_steps must be 8 to 100000, got {}",
                self.azimuth_steps
            ),
        );
        check(
            "max_range_m",
            self.max_range_m.is_finite() && self.max_range_m > 0.0,
            format!("max_range_m must be positive, got {}", self.max_range_m),
        );
        check(
            "mount_height_m",
            self.mount_height_m.is_finite() && self.mount_height_m > 0.0,
            format!(
                "mount_height_m must be positive, got {}",
                self.mount_height_m
            ),
        );
        check(
            "range_noise_std_m",
            self.range_noise_std_m.is_finite() && self.range_noise_std_m >= 0.0,
            format!(
                "range_noise_std_m must be zero or positive, got {}",
                self.range_noise_std_m
            ),
        );
        check(
            "dropout_probability",
            (0.0..1.0).contains(&self.dropout_probability),
            format!(
                "dropout_probability must be in [0, 1), got {}",
                self.dropout_probability
            ),
        );
        check(
            "attenuation_per_m",
            self.attenuation_per_m.is_finite() && self.attenuation_per_m >= 0.0,
            format!(
                "attenuation_per_m must be zero or positive, got {}",
                self.attenuation_per_m
            ),
        );
        check(
            "blocks",
            self.blocks >= 1 && self.blocks <= self.azimuth_steps,
            format!(
                "blocks must be 1 to azimuth_steps ({}), got {}",
                self.azimuth_steps, self.blocks
            ),
        );
        if let Some(fov) = self.fov_deg {
            check(
                "fov_deg",
                fov.is_finite() && fov > 0.0 && fov <= 360.0,
                format!("fov_deg must be in (0, 360], got {fov}"),
            );
        }
        if let Some(beams) = self.beams {
            check(
                "beams",
                (2..=100_000).contains(&beams),
                format!("beams must be 2 to 100000, got {beams}"),
            );
        }
        out
    }
}
