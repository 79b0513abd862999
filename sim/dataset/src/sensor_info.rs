//! The range sensor's beam pattern, written once per sequence as `sequences/<name>/sensor.json`:
//! enough to rebuild every beam of a scan, also the beams that returned nothing (the free space
//! out to the maximum range that occupancy maps learn from).

use serde::{Deserialize, Serialize};

/// What kind of range sensor wrote a sequence, or a scenario's `[lidar]` table describes (the
/// simulator's scenario files use this type too).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SensorKind {
    /// A spinning multi-beam lidar (columns over the full turn, rolling shutter; HDL-64E-like),
    /// the default.
    #[default]
    Spinning,
    /// A planar range scanner (one channel at 0°, beams over a field of view, one instant per scan;
    /// SICK LMS291-like).
    Planar,
}

impl SensorKind {
    /// True for the spinning lidar (the kind left out of resolved scenario files).
    pub fn is_spinning(&self) -> bool {
        *self == Self::Spinning
    }
}

/// The beam pattern of a sequence's sensor, sensor frame (x forward, y left, z up).
///
/// Column `j` (0-based, in firing order) points at azimuth `first_azimuth_deg + j ·
/// azimuth_step_deg`; each column fires one ray per channel, at the channel's elevation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorInfo {
    /// Spinning lidar or planar scanner.
    pub kind: SensorKind,
    /// Scans per second.
    pub rate_hz: f64,
    /// Maximum range: a beam that returns nothing saw free space out to here, metres.
    pub max_range_m: f64,
    /// Height of the optical centre above the ground, metres.
    pub mount_height_m: f64,
    /// Columns (azimuth steps of a spinning lidar, beams of a planar scanner).
    pub columns: u32,
    /// Azimuth of column 0, degrees counter-clockwise from the forward axis.
    pub first_azimuth_deg: f64,
    /// Azimuth change from one column to the next, degrees (negative: clockwise seen from above).
    pub azimuth_step_deg: f64,
    /// Elevation of each channel, degrees, highest first.
    pub elevations_deg: Vec<f64>,
}

impl SensorInfo {
    /// Azimuth of column `j`, radians in the sensor frame.
    pub fn azimuth_rad(&self, j: u32) -> f64 {
        (self.first_azimuth_deg + f64::from(j) * self.azimuth_step_deg).to_radians()
    }

    /// The column whose azimuth is nearest to `azimuth_rad` (sensor frame), if it lies within
    /// half a step of one.
    ///
    /// ```
    /// use patchflow_dataset::{SensorInfo, SensorKind};
    /// let sick = SensorInfo {
    ///     kind: SensorKind::Planar,
    ///     rate_hz: 1.0,
    ///     max_range_m: 80.0,
    ///     mount_height_m: 0.5,
    ///     columns: 181,
    ///     first_azimuth_deg: 90.0,
    ///     azimuth_step_deg: -1.0,
    ///     elevations_deg: vec![0.0],
    /// };
    /// assert_eq!(sick.column_of(0.0), Some(90));
    /// assert_eq!(sick.column_of(-100f64.to_radians()), None);
    /// ```
    pub fn column_of(&self, azimuth_rad: f64) -> Option<u32> {
        if self.azimuth_step_deg == 0.0 || self.columns == 0 {
            return None;
        }
        let offset_deg = azimuth_rad.to_degrees() - self.first_azimuth_deg;
        // Azimuths wrap: count steps within one turn, the last half step before a full turn
        // counting as just before column 0.
        let per_turn = (360.0 / self.azimuth_step_deg).abs();
        let mut steps = (offset_deg / self.azimuth_step_deg).rem_euclid(per_turn);
        if steps > per_turn - 0.5 {
            steps -= per_turn;
        }
        let j = steps.round();
        let inside = j >= 0.0 && j < f64::from(self.columns);
        (inside && (steps - j).abs() <= 0.5 + 1e-9).then_some(j as u32)
    }

    /// Reasons this description is unusable (empty fan, non-finite values), for readers.
    pub fn problems(&self) -> Vec<String> {
        let mut out = Vec::new();
        let finite = [
            self.rate_hz,
            self.max_range_m,
            self.mount_height_m,
            self.first_azimuth_deg,
            self.azimuth_step_deg,
        ];
        if finite.iter().any(|v| !v.is_finite()) {
            out.push("a number is not finite".to_owned());
        }
        if self.columns == 0 || self.elevations_deg.is_empty() {
            out.push("no beams (columns or elevations_deg empty)".to_owned());
        }
        if !(self.max_range_m > 0.0 && self.rate_hz > 0.0) {
            out.push("max_range_m and rate_hz must be positive".to_owned());
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn planar_70() -> SensorInfo {
        SensorInfo {
            kind: SensorKind::Planar,
            rate_hz: 1.0,
            max_range_m: 20.0,
            mount_height_m: 0.5,
            columns: 70,
            first_azimuth_deg: 90.0,
            azimuth_step_deg: -180.0 / 69.0,
            elevations_deg: vec![0.0],
        }
    }

    #[test]
    fn every_beam_is_found_again_from_its_own_azimuth_and_a_little_off_it() {
        let sensor = planar_70();
        for j in 0..70 {
            let a = sensor.azimuth_rad(j);
            assert_eq!(sensor.column_of(a), Some(j));
            assert_eq!(sensor.column_of(a + 0.01), Some(j));
        }
        assert_eq!(sensor.column_of(91f64.to_radians()), Some(0));
        assert_eq!(sensor.column_of(170f64.to_radians()), None);
    }

    #[test]
    fn a_spinning_fan_wraps_around_the_seam_behind_the_car() {
        let sensor = SensorInfo {
            kind: SensorKind::Spinning,
            columns: 1800,
            first_azimuth_deg: 180.0,
            azimuth_step_deg: -0.2,
            elevations_deg: vec![2.0, -24.8],
            ..planar_70()
        };
        // Column 0 at 180°, column 1 at 179.8°, column 1799 at −179.8°.
        assert_eq!(sensor.column_of(179.85f64.to_radians()), Some(1));
        assert_eq!(sensor.column_of(-179.95f64.to_radians()), Some(0));
        assert_eq!(sensor.column_of(-179.85f64.to_radians()), Some(1799));
        assert_eq!(sensor.column_of(0.0), Some(900));
    }
}
