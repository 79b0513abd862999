//! The moving classifier's file, `moving.json` beside a motion model: format and version, the
//! inputs it reads, the baseline of its observed change, the squashing and decision threshold,
//! and the GP regression on the ±1 labels.

use std::path::Path;

use patchflow_gp::{GpModel, Squashing};
use serde::{Deserialize, Serialize};

use super::change_evidence::CHANGE_BASELINE_SCANS;
use super::cluster_inputs::MOVING_INPUT_NAMES;
use super::moving_classifier::MovingClassifier;
use crate::{LearnError, Result};

/// The `format` tag of a moving-classifier file.
pub const MOVING_FORMAT: &str = "patchflow-moving-classifier";
/// The file version this build writes and reads. Version 2 adds the observed change over
/// [`CHANGE_BASELINE_SCANS`] sweeps to the inputs and the decision threshold; version 1 files
/// are refused (retrain).
pub const MOVING_VERSION: u32 = 2;
/// The file name beside a motion model (`models/moving.json`).
pub const MOVING_FILE_NAME: &str = "moving.json";

/// Largest classifier file read (its GP holds at most a few thousand rows).
const MAX_MOVING_BYTES: u64 = 64 << 20;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct MovingFile {
    format: String,
    version: u32,
    inputs: Vec<String>,
    change_baseline_scans: usize,
    rows: usize,
    moving_rows: usize,
    squashing: Squashing,
    threshold: f64,
    gp: serde_json::Value,
}

impl MovingClassifier {
    /// Writes the classifier (atomically: a temporary file renamed into place).
    pub fn save(&self, path: &Path) -> Result<()> {
        let file = MovingFile {
            format: MOVING_FORMAT.into(),
            version: MOVING_VERSION,
            inputs: MOVING_INPUT_NAMES.map(String::from).to_vec(),
            change_baseline_scans: CHANGE_BASELINE_SCANS,
            rows: self.rows,
            moving_rows: self.moving_rows,
            squashing: self.squashing,
            threshold: self.threshold,
            gp: self.gp.to_json_value()?,
        };
        let model = |reason: String| LearnError::model(path, reason);
        let mut bytes = serde_json::to_vec(&file).map_err(|e| model(e.to_string()))?;
        bytes.push(b'\n');
        Ok(patchflow_dataset::write_atomic(path, &bytes)?)
    }

    /// Reads a classifier written by [`Self::save`], checking format, version, inputs and values.
    pub fn load(path: &Path) -> Result<Self> {
        let model = |reason: String| LearnError::model(path, reason);
        let bytes = patchflow_dataset::read_limited(path, MAX_MOVING_BYTES)?;
        let value: serde_json::Value =
            serde_json::from_slice(&bytes).map_err(|e| model(format!("not JSON: {e}")))?;
        let format = value.get("format").and_then(|f| f.as_str()).unwrap_or("");
        if format != MOVING_FORMAT {
            return Err(model(format!(
                "not a patchflow moving classifier (format '{format}')"
            )));
        }
        let version = value.get("version").and_then(|v| v.as_u64()).unwrap_or(0);
        if version != u64::from(MOVING_VERSION) {
            return Err(model(format!(
                "moving classifier version {version} (this build reads {MOVING_VERSION}); retrain it with `patchflow train`"
            )));
        }
        let file: MovingFile =
            serde_json::from_value(value).map_err(|e| model(format!("corrupt: {e}")))?;
        if file.inputs != MOVING_INPUT_NAMES {
            return Err(model(format!("inputs {:?}", file.inputs)));
        }
        if file.change_baseline_scans != CHANGE_BASELINE_SCANS {
            return Err(model(format!(
                "observed change over {} sweeps; this build reads {CHANGE_BASELINE_SCANS}",
                file.change_baseline_scans
            )));
        }
        let valid = file.squashing.alpha.is_finite() && file.squashing.beta.is_finite();
        if !valid || file.moving_rows == 0 || file.moving_rows >= file.rows {
            return Err(model("squashing or row counts out of range".into()));
        }
        if !(0.5..1.0).contains(&file.threshold) {
            return Err(model(format!(
                "decision threshold {} outside [0.5, 1)",
                file.threshold
            )));
        }
        let gp = GpModel::from_json_value(file.gp, path)?;
        if gp.input_names().len() != MOVING_INPUT_NAMES.len() {
            return Err(model(format!(
                "the GP reads {} inputs, not {}",
                gp.input_names().len(),
                MOVING_INPUT_NAMES.len()
            )));
        }
        Ok(Self {
            gp,
            squashing: file.squashing,
            threshold: file.threshold,
            rows: file.rows,
            moving_rows: file.moving_rows,
        })
    }
}
