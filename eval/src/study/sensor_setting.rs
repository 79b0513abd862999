//! How a study point's world, sensor and features differ from the scenario files and the
//! default estimator's features (the realism rung, the lidar's rate and channels, the map cell
//! size), and the names its datasets and models are kept under.

use patchflow_learn::{EstimatorParams, FeatureParams};
use patchflow_sim::Realism;

/// How the world and the sensor of a dataset differ from the scenario files; `None` keeps theirs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SensorSetting {
    /// Realism rung replacing every scenario's own.
    pub realism: Option<Realism>,
    /// Lidar turn rate, Hz (sweeps scaled so each scenario lasts as long as at its own rate).
    pub rate_hz: Option<f64>,
    /// Lidar channels.
    pub channels: Option<u32>,
    /// Cell size of the maps the estimator's patches sample, metres (not a change of the data:
    /// the sweeps are shared; the clusters and the moving classifier keep their maps).
    pub cell_m: Option<f64>,
}

impl SensorSetting {
    /// A name for this setting (`default` for none), e.g. `20hz`, `16ch`, `0.05m`.
    pub fn key(&self) -> String {
        let mut parts = self.data_parts();
        if let Some(cell_m) = self.cell_m {
            parts.push(format!("{cell_m}m"));
        }
        join_parts(parts)
    }

    /// The folder name of the datasets of this setting: the key without the feature parameters,
    /// so points that differ only in those share their sweeps.
    pub fn data_key(&self) -> String {
        join_parts(self.data_parts())
    }

    /// The feature parameters of this setting: the default estimator's (its slice under the belt
    /// line, not the thesis preset's) with this setting's patch cell size, so a study's default
    /// point is the model `bench` trains.
    pub fn features(&self) -> FeatureParams {
        let defaults = EstimatorParams::default().features;
        FeatureParams {
            patch_cell_m: self.cell_m.unwrap_or(defaults.patch_cell_m),
            ..defaults
        }
    }

    fn data_parts(&self) -> Vec<String> {
        let mut parts = Vec::new();
        if let Some(r) = self.realism {
            parts.push(r.name().to_owned());
        }
        if let Some(hz) = self.rate_hz {
            parts.push(format!("{hz}hz"));
        }
        if let Some(c) = self.channels {
            parts.push(format!("{c}ch"));
        }
        parts
    }
}

fn join_parts(parts: Vec<String>) -> String {
    if parts.is_empty() {
        "default".to_owned()
    } else {
        parts.join("-")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_study_point_cuts_the_default_estimators_slice_not_the_thesis_ones() {
        let default = EstimatorParams::default().features;
        let features = SensorSetting::default().features();
        assert_eq!(features, default);
        let cell = SensorSetting {
            cell_m: Some(0.2),
            ..SensorSetting::default()
        }
        .features();
        assert_eq!(
            (cell.slice_min_m, cell.slice_max_m, cell.patch_cell_m),
            (default.slice_min_m, default.slice_max_m, 0.2)
        );
        assert_eq!(cell.cell_m, default.cell_m);
        assert_ne!(cell.slice_max_m, FeatureParams::default().slice_max_m);
    }
}
