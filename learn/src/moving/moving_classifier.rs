//! The moving/static classifier: GP probabilistic least squares (GPML §6.5) on the
//! [`cluster_inputs`] of object hypotheses, trained on a dataset's exact flow, applied per scan,
//! and kept in a versioned `moving.json` beside the motion model.
//!
//! Training takes every object hypothesis of evenly spaced scans of every sequence (at most
//! `max_scans`), labelled by [`cluster_is_moving`], and fits an exact GP on at most `max_rows`
//! of them: a seeded draw with as many static as moving clusters. The data hold about one moving
//! cluster in fifty (parked cars, poles and bushes are hypotheses too); on the raw mix the fitted
//! offset β called nearly every cluster static, so the classes are balanced and the decision at
//! one half weighs a missed mover as much as a static cluster set in motion. A cluster that is no
//! object hypothesis (longer than any road user) is static by definition.

use std::path::Path;

use nalgebra::DMatrix;
use patchflow_dataset::Dataset;
use patchflow_gp::{GpModel, PlsParams, Squashing};
use rand::SeedableRng;
use rand::seq::SliceRandom;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::cluster_inputs::{MOVING_INPUT_NAMES, cluster_inputs, cluster_is_moving};
use crate::{FeatureParams, GpKind, GpParams, LearnError, Result, SweepFeatures};

/// The `format` tag of a moving-classifier file.
pub const MOVING_FORMAT: &str = "patchflow-moving-classifier";
/// The file version this build writes and reads.
pub const MOVING_VERSION: u32 = 1;
/// The file name beside a motion model (`models/moving.json`).
pub const MOVING_FILE_NAME: &str = "moving.json";

/// How much of a dataset the classifier learns from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingParams {
    /// Most scans read (evenly spaced over all sequences).
    pub max_scans: usize,
    /// Most clusters the GP is fitted on.
    pub max_rows: usize,
    /// Seed of the row draw and the GP's initialisation.
    pub seed: u64,
}

impl Default for MovingParams {
    fn default() -> Self {
        Self {
            max_scans: 500,
            max_rows: 800,
            seed: 7,
        }
    }
}

/// A trained moving/static classifier.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingClassifier {
    gp: GpModel,
    squashing: Squashing,
    rows: usize,
    moving_rows: usize,
}

#[derive(Serialize, Deserialize)]
struct MovingFile {
    format: String,
    version: u32,
    inputs: Vec<String>,
    rows: usize,
    moving_rows: usize,
    squashing: Squashing,
    gp: serde_json::Value,
}

impl MovingClassifier {
    /// Learns from every sequence of `dataset` with the maps of `features` (the motion model's).
    pub fn train(
        dataset: &Dataset,
        features: &FeatureParams,
        params: &MovingParams,
    ) -> Result<Self> {
        let valid = features.check()?;
        let mut scans = Vec::new();
        for info in dataset.sequences() {
            scans.extend((1..info.sweeps as usize).map(|k| (info.name.clone(), k)));
        }
        let stride = scans.len().div_ceil(params.max_scans.max(1)).max(1);
        let chosen: Vec<&(String, usize)> = scans.iter().step_by(stride).collect();
        let per_scan = chosen
            .par_iter()
            .map(|(name, k)| {
                let sequence = dataset.sequence(name)?;
                let previous = sequence.read_sweep(k - 1)?;
                let current = sequence.read_sweep(*k)?;
                let f = SweepFeatures::compute_checked(&previous, &current, &valid)?;
                Ok(f.object_hypotheses()
                    .into_iter()
                    .map(|c| (cluster_inputs(&f, c), cluster_is_moving(&f, &current, c)))
                    .collect::<Vec<_>>())
            })
            .collect::<Result<Vec<_>>>()?;
        let rows: Vec<([f64; 6], bool)> = per_scan.into_iter().flatten().collect();
        Self::fit(rows, params)
    }

    /// Fits the classifier to labelled inputs: at most `params.max_rows / 2` moving ones and as
    /// many static ones, drawn uniformly.
    pub fn fit(mut rows: Vec<([f64; 6], bool)>, params: &MovingParams) -> Result<Self> {
        if rows.iter().any(|(x, _)| x.iter().any(|v| !v.is_finite())) {
            return Err(LearnError::degenerate_data(
                "a cluster's moving-classifier inputs are not finite".into(),
            ));
        }
        let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
        rows.shuffle(&mut rng);
        let (moving, still): (Vec<_>, Vec<_>) = rows.into_iter().partition(|(_, m)| *m);
        let n = moving
            .len()
            .min(still.len())
            .min(params.max_rows.max(2) / 2);
        let mut rows: Vec<([f64; 6], bool)> = moving.into_iter().take(n).collect();
        rows.extend(still.into_iter().take(n));
        let moving_rows = rows.iter().filter(|(_, moving)| *moving).count();
        if moving_rows == 0 || moving_rows == rows.len() {
            return Err(LearnError::degenerate_data(format!(
                "{} clusters, {moving_rows} of them moving: the moving classifier needs both classes",
                rows.len()
            )));
        }
        let x = DMatrix::from_fn(rows.len(), MOVING_INPUT_NAMES.len(), |i, d| rows[i].0[d]);
        let labels: Vec<bool> = rows.iter().map(|(_, moving)| *moving).collect();
        let gp = GpParams::new(GpKind::Full).seed(params.seed);
        let fitted = PlsParams::new(gp).fit(&x, &labels)?;
        Ok(Self {
            gp: fitted.regression().clone(),
            squashing: fitted.squashing(),
            rows: rows.len(),
            moving_rows,
        })
    }

    /// Per cluster of `features`, the probability that it moves: `Some` for object hypotheses,
    /// `None` for the clusters too long to be one object (static).
    pub fn cluster_probabilities(&self, features: &SweepFeatures) -> Result<Vec<Option<f64>>> {
        let hypotheses = features.object_hypotheses();
        let mut out = vec![None; features.clusters().len()];
        if hypotheses.is_empty() {
            return Ok(out);
        }
        let inputs: Vec<[f64; 6]> = hypotheses
            .iter()
            .map(|&c| cluster_inputs(features, c))
            .collect();
        let x = DMatrix::from_fn(inputs.len(), MOVING_INPUT_NAMES.len(), |i, d| inputs[i][d]);
        let prediction = self.gp.predict(&x)?;
        for (k, &c) in hypotheses.iter().enumerate() {
            let p = self
                .squashing
                .probability(prediction.mean[k], prediction.var_latent[k]);
            out[c] = Some(p);
        }
        Ok(out)
    }

    /// The decision per cluster: moving when the probability is above one half.
    pub fn cluster_decisions(&self, features: &SweepFeatures) -> Result<Vec<bool>> {
        Ok(self
            .cluster_probabilities(features)?
            .into_iter()
            .map(|p| p.is_some_and(|p| p > 0.5))
            .collect())
    }

    /// Clusters the GP was fitted on, and how many of them moved.
    pub fn training_rows(&self) -> (usize, usize) {
        (self.rows, self.moving_rows)
    }

    /// Writes the classifier (atomically: a temporary file renamed into place).
    pub fn save(&self, path: &Path) -> Result<()> {
        let file = MovingFile {
            format: MOVING_FORMAT.into(),
            version: MOVING_VERSION,
            inputs: MOVING_INPUT_NAMES.map(String::from).to_vec(),
            rows: self.rows,
            moving_rows: self.moving_rows,
            squashing: self.squashing,
            gp: self.gp.to_json_value()?,
        };
        let model = |reason: String| LearnError::model(path, reason);
        let mut bytes = serde_json::to_vec(&file).map_err(|e| model(e.to_string()))?;
        bytes.push(b'\n');
        Ok(patchflow_dataset::write_atomic(path, &bytes)?)
    }

    /// Reads a classifier written by [`Self::save`], checking format, version and inputs.
    pub fn load(path: &Path) -> Result<Self> {
        let model = |reason: String| LearnError::model(path, reason);
        let bytes = std::fs::read(path).map_err(|source| LearnError::io(path, source))?;
        let value: serde_json::Value =
            serde_json::from_slice(&bytes).map_err(|e| model(format!("not JSON: {e}")))?;
        let format = value.get("format").and_then(|f| f.as_str()).unwrap_or("");
        if format != MOVING_FORMAT {
            return Err(model(format!(
                "not a patchflow moving classifier (format '{format}')"
            )));
        }
        let file: MovingFile =
            serde_json::from_value(value).map_err(|e| model(format!("corrupt: {e}")))?;
        if file.version != MOVING_VERSION {
            return Err(model(format!(
                "version {} (this build reads {MOVING_VERSION})",
                file.version
            )));
        }
        if file.inputs != MOVING_INPUT_NAMES {
            return Err(model(format!("inputs {:?}", file.inputs)));
        }
        let valid = file.squashing.alpha.is_finite() && file.squashing.beta.is_finite();
        if !valid || file.moving_rows == 0 || file.moving_rows >= file.rows {
            return Err(model("squashing or row counts out of range".into()));
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
            rows: file.rows,
            moving_rows: file.moving_rows,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};

    /// Features of a scene with one car at `speed_mps` and one parked car, over 0.1 s.
    fn scene(speed_mps: f64, at: [f64; 2]) -> (SweepFeatures, patchflow_dataset::Sweep) {
        let scene = SyntheticScene {
            boxes: vec![
                SceneBox::car(1, at, 0.3, speed_mps),
                SceneBox::car(2, [-at[0], -at[1]], 1.2, 0.0),
            ],
        };
        let lidar = SyntheticLidar::with_resolution(32, 720);
        let prev = scene.scan(&lidar, [0.0, 0.0], 0.0, 0);
        let curr = scene.advanced(0.1).scan(&lidar, [0.0, 0.0], 0.0, 1);
        let f = SweepFeatures::compute(&prev, &curr, &FeatureParams::default()).unwrap();
        (f, curr)
    }

    fn trained() -> MovingClassifier {
        let mut rows = Vec::new();
        for (k, speed) in [0.0, 4.0, 8.0, 12.0].iter().enumerate() {
            for r in [10.0, 15.0, 20.0] {
                let (f, sweep) = scene(*speed, [r, 2.0 + k as f64]);
                for c in f.object_hypotheses() {
                    rows.push((cluster_inputs(&f, c), cluster_is_moving(&f, &sweep, c)));
                }
            }
        }
        MovingClassifier::fit(rows, &MovingParams::default()).unwrap()
    }

    #[test]
    fn a_moving_car_is_decided_moving_and_a_parked_car_static() {
        let classifier = trained();
        let (f, sweep) = scene(10.0, [13.0, 4.0]);
        let decisions = classifier.cluster_decisions(&f).unwrap();
        let hypotheses = f.object_hypotheses();
        assert_eq!(hypotheses.len(), 2);
        for c in hypotheses {
            assert_eq!(
                decisions[c],
                cluster_is_moving(&f, &sweep, c),
                "cluster {c}"
            );
        }
    }

    #[test]
    fn a_saved_classifier_loads_back_with_the_same_probabilities() {
        let classifier = trained();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(MOVING_FILE_NAME);
        classifier.save(&path).unwrap();
        let loaded = MovingClassifier::load(&path).unwrap();
        let (f, _) = scene(6.0, [12.0, 3.0]);
        let a = classifier.cluster_probabilities(&f).unwrap();
        let b = loaded.cluster_probabilities(&f).unwrap();
        assert_eq!(a, b);
    }

    #[test]
    fn a_file_of_another_format_or_version_is_refused_with_its_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(MOVING_FILE_NAME);
        std::fs::write(&path, r#"{"format":"other","version":1}"#).unwrap();
        let err = MovingClassifier::load(&path).unwrap_err().to_string();
        assert!(
            err.contains("moving.json") && err.contains("other"),
            "{err}"
        );
        let classifier = trained();
        classifier.save(&path).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(&path, text.replace("\"version\":1", "\"version\":9")).unwrap();
        assert!(MovingClassifier::load(&path).is_err());
    }

    #[test]
    fn one_class_only_is_an_error() {
        let rows = vec![([0.0; 6], false); 10];
        assert!(MovingClassifier::fit(rows, &MovingParams::default()).is_err());
    }
}
