//! A study point's sensor setting applied to scenario files: the lidar's rate and channels are
//! written into each scenario's `[lidar]` table (its other fields kept), and the sweep count is
//! scaled with the rate so a scenario lasts as long at every rate; the result goes to a scenario
//! file of its own beside the data, so the generated folder records what made it.

use std::path::Path;

use patchflow_sim::ScenarioSource;

use crate::error::EvalError;
use crate::report::{create_dir, write_atomic};
use crate::study::sensor_setting::SensorSetting;

/// The lidar rate of a scenario that names none (`LidarConfig::default`).
const DEFAULT_RATE_HZ: f64 = 10.0;

/// The scenarios with `setting`'s lidar changes, written under `dir` when there are any (the
/// realism rung is not a scenario change: it goes to `GenerateOptions::realism`).
pub(crate) fn apply_setting(
    sources: &[ScenarioSource],
    setting: &SensorSetting,
    dir: &Path,
) -> Result<Vec<ScenarioSource>, EvalError> {
    if setting.rate_hz.is_none() && setting.channels.is_none() {
        return Ok(sources.to_vec());
    }
    create_dir(dir)?;
    sources
        .iter()
        .map(|source| {
            let (name, text) = read(source)?;
            let changed =
                with_setting(&text, setting).map_err(|reason| EvalError::BadParameter {
                    name: "study scenario",
                    reason: format!("{name}: {reason}"),
                })?;
            let path = dir.join(format!("{name}.toml"));
            write_atomic(&path, changed.as_bytes())?;
            Ok(ScenarioSource::File(path))
        })
        .collect()
}

/// A scenario's name and text.
fn read(source: &ScenarioSource) -> Result<(String, String), EvalError> {
    match source {
        ScenarioSource::Embedded(name, text) => Ok(((*name).to_owned(), (*text).to_owned())),
        ScenarioSource::File(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| EvalError::io(path, e))?;
            let name = path
                .file_stem()
                .map_or_else(|| "scenario".into(), |s| s.to_string_lossy().into_owned());
            Ok((name, text))
        }
    }
}

/// The scenario text with the setting's rate (sweeps scaled by new rate / old rate, at least 2)
/// and channels in its `[lidar]` table.
fn with_setting(text: &str, setting: &SensorSetting) -> Result<String, String> {
    let mut scenario: toml::Table = text.parse().map_err(|e| format!("{e}"))?;
    let lidar = scenario
        .entry("lidar")
        .or_insert_with(|| toml::Value::Table(toml::Table::new()))
        .as_table_mut()
        .ok_or("`lidar` is not a table")?;
    if let Some(channels) = setting.channels {
        lidar.insert("channels".into(), toml::Value::Integer(i64::from(channels)));
    }
    if let Some(rate_hz) = setting.rate_hz {
        let own_hz = match lidar.get("rate_hz") {
            Some(toml::Value::Float(hz)) => *hz,
            Some(toml::Value::Integer(hz)) => *hz as f64,
            Some(_) => return Err("`lidar.rate_hz` is not a number".into()),
            None => DEFAULT_RATE_HZ,
        };
        lidar.insert("rate_hz".into(), toml::Value::Float(rate_hz));
        let sweeps = scenario
            .get("sweeps")
            .and_then(toml::Value::as_integer)
            .ok_or("`sweeps` is missing or not an integer")?;
        let scaled = ((sweeps as f64) * rate_hz / own_hz).round().max(2.0) as i64;
        scenario.insert("sweeps".into(), toml::Value::Integer(scaled));
    }
    toml::to_string(&scenario).map_err(|e| format!("{e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "sweeps = 80\n[lidar]\nazimuth_steps = 720\n[ego]\nspeed_mps = 4.0\n";

    #[test]
    fn a_doubled_rate_doubles_the_sweeps_and_keeps_the_other_lidar_fields() {
        let setting = SensorSetting {
            rate_hz: Some(20.0),
            ..SensorSetting::default()
        };
        let out: toml::Table = with_setting(SCENE, &setting).unwrap().parse().unwrap();
        assert_eq!(out["sweeps"].as_integer(), Some(160));
        assert_eq!(out["lidar"]["rate_hz"].as_float(), Some(20.0));
        assert_eq!(out["lidar"]["azimuth_steps"].as_integer(), Some(720));
        assert_eq!(out["ego"]["speed_mps"].as_float(), Some(4.0));
    }

    #[test]
    fn channels_are_set_in_a_lidar_table_the_scenario_did_not_have() {
        let setting = SensorSetting {
            channels: Some(16),
            ..SensorSetting::default()
        };
        let out: toml::Table = with_setting("sweeps = 5\n", &setting)
            .unwrap()
            .parse()
            .unwrap();
        assert_eq!(out["lidar"]["channels"].as_integer(), Some(16));
        assert_eq!(out["sweeps"].as_integer(), Some(5));
    }
}
