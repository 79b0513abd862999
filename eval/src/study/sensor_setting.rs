//! How a study point's world, sensor and features differ from the scenario files and the
//! feature defaults (the realism rung, the lidar's rate and channels, the map cell size), and
//! the names its datasets and models are kept under.

use patchflow_learn::FeatureParams;
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
    /// Map cell size of the features, metres (not a change of the data: the sweeps are shared).
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

    /// The feature parameters of this setting: the defaults with its cell size.
    pub fn features(&self) -> FeatureParams {
        let defaults = FeatureParams::default();
        FeatureParams {
            cell_m: self.cell_m.unwrap_or(defaults.cell_m),
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
