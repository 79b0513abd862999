//! The files a sequence holds once, beside its sweeps: the static-world truth (`static.json`) and
//! the sensor's beam pattern (`sensor.json`). Datasets written before they existed lack them;
//! reading one then is a [`DatasetError::Missing`] that names the file and says to regenerate.

use std::path::Path;

use crate::limits::{MAX_JSON_BYTES, read_limited};
use crate::writer::{SENSOR_JSON, STATIC_JSON};
use crate::{DatasetError, Result, SensorInfo, SequenceReader, StaticObstacle};

impl SequenceReader {
    /// The static obstacles (`static.json`). Datasets written before it existed lack the file:
    /// that is a [`DatasetError::Missing`] naming it.
    pub fn static_obstacles(&self) -> Result<Vec<StaticObstacle>> {
        let path = self.dir().join(STATIC_JSON);
        let obstacles: Vec<StaticObstacle> = read_json_file(&path, "static-world truth")?;
        if let Some(i) = obstacles.iter().position(|o| {
            let numbers = o.centre_m.iter().chain(&o.size_m).chain([&o.yaw_rad]);
            let huge = numbers.clone().any(|v| v.abs() > crate::MAX_COORDINATE_M);
            numbers.clone().any(|v| !v.is_finite()) || o.size_m.iter().any(|&v| v < 0.0) || huge
        }) {
            let reason = format!(
                "obstacle {i} has a non-finite number, a negative size or a value beyond ±{} m",
                crate::MAX_COORDINATE_M
            );
            return Err(DatasetError::corrupt(&path, reason));
        }
        Ok(obstacles)
    }

    /// The sensor's beam pattern (`sensor.json`). Datasets written before it existed lack the
    /// file: that is a [`DatasetError::Missing`] naming it.
    pub fn sensor(&self) -> Result<SensorInfo> {
        let path = self.dir().join(SENSOR_JSON);
        let sensor: SensorInfo = read_json_file(&path, "sensor description")?;
        if let Some(reason) = sensor.problems().into_iter().next() {
            return Err(DatasetError::corrupt(&path, reason));
        }
        Ok(sensor)
    }
}

/// Reads a JSON file of this format; a file that does not exist is [`DatasetError::Missing`]
/// (`what` says what it holds; datasets of older builds lack it: regenerate them).
fn read_json_file<T: serde::de::DeserializeOwned>(path: &Path, what: &str) -> Result<T> {
    if !path.is_file() {
        return Err(DatasetError::Missing {
            path: path.to_owned(),
            what: format!(
                "{what} (written by `patchflow generate` since this build; regenerate the dataset)"
            ),
        });
    }
    serde_json::from_slice(&read_limited(path, MAX_JSON_BYTES)?)
        .map_err(|e| DatasetError::corrupt(path, e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reader::tests::{sample_sweep, write_sequence};
    use crate::{Dataset, SequenceWriter};

    #[test]
    fn static_truth_and_the_sensor_read_back_and_their_absence_names_the_file() {
        let dir = tempfile::tempdir().unwrap();
        write_sequence(dir.path(), &[sample_sweep(0)]);
        let seq = Dataset::open(dir.path()).unwrap().sequence("seq").unwrap();
        let err = seq.static_obstacles().unwrap_err();
        assert!(
            matches!(err, DatasetError::Missing { .. }) && err.to_string().contains("static.json"),
            "{err}"
        );
        let writer = SequenceWriter::open(dir.path(), "seq").unwrap();
        let wall = StaticObstacle {
            semantic: 51,
            centre_m: [10.0, 0.0, 1.25],
            size_m: [0.3, 10.0, 2.5],
            yaw_rad: 0.5,
            exact: true,
        };
        writer
            .write_static_obstacles(std::slice::from_ref(&wall))
            .unwrap();
        let sensor = SensorInfo {
            kind: crate::SensorKind::Planar,
            rate_hz: 1.0,
            max_range_m: 20.0,
            mount_height_m: 0.5,
            columns: 70,
            first_azimuth_deg: 90.0,
            azimuth_step_deg: -180.0 / 69.0,
            elevations_deg: vec![0.0],
        };
        writer.write_sensor(&sensor).unwrap();
        assert_eq!(seq.static_obstacles().unwrap(), vec![wall]);
        assert_eq!(seq.sensor().unwrap(), sensor);
    }

    #[test]
    fn a_static_obstacle_of_astronomical_size_or_place_is_refused_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        write_sequence(dir.path(), &[sample_sweep(0)]);
        let seq = Dataset::open(dir.path()).unwrap().sequence("seq").unwrap();
        let path = seq.dir().join(STATIC_JSON);
        for text in [
            r#"[{"semantic": 51, "centre_m": [1e300, 0, 1], "size_m": [1, 1, 1], "yaw_rad": 0, "exact": true}]"#,
            r#"[{"semantic": 51, "centre_m": [3, 0, 1], "size_m": [1, 2e9, 1], "yaw_rad": 0, "exact": true}]"#,
        ] {
            std::fs::write(&path, text).unwrap();
            let err = seq.static_obstacles().unwrap_err().to_string();
            assert!(
                err.contains("static.json") && err.contains("obstacle 0"),
                "{err}"
            );
        }
    }
}
