//! The beam pattern: channel elevations (HDL-64E-like two blocks, or uniform) and the azimuth of
//! each column. Azimuth columns start behind the car and turn clockwise seen from above, like a
//! Velodyne, so the seam of a sweep lies behind the ego car as in KITTI; a planar scanner's
//! columns are its beams over its field of view (`planar_scanner.rs`).

use patchflow_dataset::SensorInfo;

use super::planar_scanner::planar_azimuth_rad;
use crate::scenario::{ElevationSpacing, LidarConfig, SensorKind};

/// Elevation of every channel, degrees, highest first.
pub fn elevations_deg(config: &LidarConfig) -> Vec<f64> {
    let n = config.channels as usize;
    let span = config.upper_deg - config.lower_deg;
    if n == 1 {
        return vec![config.upper_deg];
    }
    match config.spacing {
        ElevationSpacing::Uniform => (0..n)
            .map(|i| config.upper_deg - span * i as f64 / (n - 1) as f64)
            .collect(),
        ElevationSpacing::Hdl64e => {
            // Upper block at 2/3 of the lower block's spacing; one lower spacing between blocks.
            let upper = n.div_ceil(2);
            let lower = n - upper;
            let step_lower = span / ((upper - 1) as f64 * 2.0 / 3.0 + lower as f64);
            let step_upper = step_lower * 2.0 / 3.0;
            let top_of_lower = config.upper_deg - (upper - 1) as f64 * step_upper - step_lower;
            (0..upper)
                .map(|i| config.upper_deg - i as f64 * step_upper)
                .chain((0..lower).map(|i| top_of_lower - i as f64 * step_lower))
                .collect()
        }
    }
}

/// Azimuth of column `j` of `steps`, radians in the sensor frame (x forward, y left).
pub fn azimuth_rad(j: u32, steps: u32) -> f64 {
    std::f64::consts::PI - std::f64::consts::TAU * f64::from(j) / f64::from(steps)
}

/// Azimuth of column `j` of the sensor, radians in the sensor frame: a spinning lidar's columns
/// cover the full turn from behind the car, a planar scanner's beams its field of view.
pub fn column_azimuth_rad(config: &LidarConfig, j: u32) -> f64 {
    match config.kind {
        SensorKind::Spinning => azimuth_rad(j, config.azimuth_steps),
        SensorKind::Planar => planar_azimuth_rad(config, j),
    }
}

/// The beam pattern as the dataset describes it (`sensor.json`): kind, range, mount height,
/// columns with their first azimuth and step, and the channel elevations.
pub fn sensor_info(config: &LidarConfig) -> SensorInfo {
    let columns = config.azimuth_steps;
    let first = column_azimuth_rad(config, 0);
    let step = if columns > 1 {
        column_azimuth_rad(config, 1) - first
    } else {
        0.0
    };
    SensorInfo {
        kind: config.kind,
        rate_hz: config.rate_hz,
        max_range_m: config.max_range_m,
        mount_height_m: config.mount_height_m,
        columns,
        first_azimuth_deg: first.to_degrees(),
        azimuth_step_deg: step.to_degrees(),
        elevations_deg: elevations_deg(config),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hdl64e_fan_spans_the_requested_range_with_two_block_spacings() {
        let config = LidarConfig::default();
        let el = elevations_deg(&config);
        assert_eq!(el.len(), 64);
        assert!((el[0] - 2.0).abs() < 1e-12);
        assert!((el[63] + 24.8).abs() < 1e-9);
        let upper_step = el[0] - el[1];
        let lower_step = el[40] - el[41];
        assert!((upper_step - 0.339).abs() < 0.002, "{upper_step}");
        assert!((lower_step - 0.509).abs() < 0.002, "{lower_step}");
        assert!(el.windows(2).all(|w| w[0] > w[1]));
    }

    #[test]
    fn a_uniform_fan_is_evenly_spaced() {
        let config = LidarConfig {
            spacing: ElevationSpacing::Uniform,
            channels: 5,
            upper_deg: 0.0,
            lower_deg: -8.0,
            ..LidarConfig::default()
        };
        assert_eq!(elevations_deg(&config), vec![0.0, -2.0, -4.0, -6.0, -8.0]);
    }

    #[test]
    fn the_described_pattern_gives_every_column_its_own_azimuth() {
        let config = LidarConfig {
            azimuth_steps: 90,
            ..LidarConfig::default()
        };
        let info = sensor_info(&config);
        for j in 0..90 {
            let described = info.azimuth_rad(j);
            let cast = column_azimuth_rad(&config, j);
            assert!((described - cast).abs() < 1e-9, "column {j}");
        }
        assert_eq!(info.elevations_deg, elevations_deg(&config));
    }
}
