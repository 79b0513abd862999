//! The moving classifier's file, `moving.json` beside a motion model: format and version, the
//! inputs it reads, the baseline of its observed change, the decision threshold, and per draw of
//! the bag its squashing and GP regression on the ±1 labels.

use std::path::Path;

use patchflow_gp::{GpModel, Squashing};
use serde::{Deserialize, Serialize};

use super::change_evidence::CHANGE_BASELINE_SCANS;
use super::cluster_inputs::MOVING_INPUT_NAMES;
use super::moving_classifier::MovingClassifier;
use super::moving_draw::MovingDraw;
use crate::{LearnError, Result};

/// The `format` tag of a moving-classifier file.
pub const MOVING_FORMAT: &str = "patchflow-moving-classifier";
/// The file version this build writes. Version 3 holds a bag of GPs (`draws`); version 2 (one GP,
/// the observed change over [`CHANGE_BASELINE_SCANS`] sweeps among the inputs) still reads, as a
/// bag of one; version 1 files are refused (retrain).
pub const MOVING_VERSION: u32 = 3;
/// The file name beside a motion model (`models/moving.json`).
pub const MOVING_FILE_NAME: &str = "moving.json";

/// Largest classifier file read (its GPs hold at most a few thousand rows).
const MAX_MOVING_BYTES: u64 = 64 << 20;

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct MovingFile {
    format: String,
    version: u32,
    inputs: Vec<String>,
    change_baseline_scans: usize,
    threshold: f64,
    draws: Vec<DrawFile>,
}

/// One GP of the bag.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct DrawFile {
    rows: usize,
    moving_rows: usize,
    squashing: Squashing,
    gp: serde_json::Value,
}

/// Version 2: one GP, its fields beside the threshold.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MovingFileV2 {
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

impl MovingFileV2 {
    fn into_current(self) -> MovingFile {
        MovingFile {
            format: self.format,
            version: self.version,
            inputs: self.inputs,
            change_baseline_scans: self.change_baseline_scans,
            threshold: self.threshold,
            draws: vec![DrawFile {
                rows: self.rows,
                moving_rows: self.moving_rows,
                squashing: self.squashing,
                gp: self.gp,
            }],
        }
    }
}

impl MovingClassifier {
    /// Writes the classifier (atomically: a temporary file renamed into place).
    pub fn save(&self, path: &Path) -> Result<()> {
        let draws = self
            .draws
            .iter()
            .map(|d| {
                Ok(DrawFile {
                    rows: d.rows,
                    moving_rows: d.moving_rows,
                    squashing: d.squashing,
                    gp: d.gp.to_json_value()?,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let file = MovingFile {
            format: MOVING_FORMAT.into(),
            version: MOVING_VERSION,
            inputs: MOVING_INPUT_NAMES.map(String::from).to_vec(),
            change_baseline_scans: CHANGE_BASELINE_SCANS,
            threshold: self.threshold,
            draws,
        };
        let model = |reason: String| LearnError::model(path, reason);
        let mut bytes = serde_json::to_vec(&file).map_err(|e| model(e.to_string()))?;
        bytes.push(b'\n');
        Ok(patchflow_dataset::write_atomic(path, &bytes)?)
    }

    /// Reads a classifier written by [`Self::save`] (or a version-2 file), checking format,
    /// version, inputs and values.
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
        let corrupt = |e: serde_json::Error| model(format!("corrupt: {e}"));
        let file: MovingFile = match version {
            3 => serde_json::from_value(value).map_err(corrupt)?,
            2 => serde_json::from_value::<MovingFileV2>(value)
                .map_err(corrupt)?
                .into_current(),
            _ => {
                return Err(model(format!(
                    "moving classifier version {version} (this build reads 2 and {MOVING_VERSION}); retrain it with `patchflow train`"
                )));
            }
        };
        if file.inputs != MOVING_INPUT_NAMES {
            return Err(model(format!("inputs {:?}", file.inputs)));
        }
        if file.change_baseline_scans != CHANGE_BASELINE_SCANS {
            return Err(model(format!(
                "observed change over {} sweeps; this build reads {CHANGE_BASELINE_SCANS}",
                file.change_baseline_scans
            )));
        }
        if !(0.5..1.0).contains(&file.threshold) {
            return Err(model(format!(
                "decision threshold {} outside [0.5, 1)",
                file.threshold
            )));
        }
        if file.draws.is_empty() {
            return Err(model("no GP in the bag (`draws` is empty)".into()));
        }
        let mut draws = Vec::with_capacity(file.draws.len());
        for (k, draw) in file.draws.into_iter().enumerate() {
            let valid = draw.squashing.alpha.is_finite() && draw.squashing.beta.is_finite();
            if !valid || draw.moving_rows == 0 || draw.moving_rows >= draw.rows {
                return Err(model(format!(
                    "draw {k}: squashing or row counts out of range"
                )));
            }
            let gp = GpModel::from_json_value(draw.gp, path)?;
            if gp.input_names().len() != MOVING_INPUT_NAMES.len() {
                return Err(model(format!(
                    "draw {k}: the GP reads {} inputs, not {}",
                    gp.input_names().len(),
                    MOVING_INPUT_NAMES.len()
                )));
            }
            draws.push(MovingDraw {
                gp,
                squashing: draw.squashing,
                rows: draw.rows,
                moving_rows: draw.moving_rows,
            });
        }
        Ok(Self {
            draws,
            threshold: file.threshold,
        })
    }
}
