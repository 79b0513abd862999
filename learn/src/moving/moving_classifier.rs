//! The moving/static classifier: GP probabilistic least squares (GPML §6.5) on the
//! [`cluster_inputs`] of object hypotheses, trained on a dataset's exact flow, applied per scan,
//! and kept in a versioned `moving.json` beside the motion model (`moving_file.rs`).
//!
//! Training takes every object hypothesis of evenly spaced scans of every sequence (at most
//! `max_scans`), labelled by [`cluster_is_moving`], and fits a bag of `draws` exact GPs, each on
//! its own seeded draw of at most `max_rows` clusters with as many static as moving ones
//! ([`MovingDraw`]); a cluster's probability of moving is the mean of the draws'. The data hold
//! about one moving cluster in thirty (parked cars, poles and bushes are hypotheses too); on the
//! raw mix the fitted offset β called nearly every cluster static, so the classes are balanced
//! for the fit and the natural mix comes back in the decision threshold ([`iou_threshold`]),
//! read off the bag's mean held-out probabilities. A cluster that is no object hypothesis
//! (longer than any road user) is static by definition.

use std::collections::BTreeMap;
use std::collections::btree_map::Entry;

use nalgebra::DMatrix;
use patchflow_dataset::{Dataset, Sweep};
use rayon::prelude::*;

use super::change_evidence::{CHANGE_BASELINE_SCANS, ChangeEvidence};
use super::cluster_inputs::{MOVING_INPUTS, cluster_inputs};
use super::decision_threshold::{ScoredCluster, iou_threshold};
use super::moving_belief::MovingBelief;
use super::moving_draw::MovingDraw;
use crate::{FeatureParams, FeatureValidParams, HeightSlice, LearnError, Result, SweepFeatures};

/// How much of a dataset the classifier learns from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingParams {
    /// Most scans read (evenly spaced over all sequences).
    pub max_scans: usize,
    /// Most clusters each draw's GP is fitted on.
    pub max_rows: usize,
    /// Draws in the bag (at least one): GPs fitted on draws seeded `seed`, `seed + 1`, …, their
    /// probabilities averaged.
    pub draws: usize,
    /// Seed of the first draw and its GP's initialisation.
    pub seed: u64,
}

impl Default for MovingParams {
    fn default() -> Self {
        Self {
            max_scans: 500,
            // Three draws of 800 read the five situations at 0.67-0.77 moving IoU where single
            // draws read 0.44-0.68, and three of 400 at 0.59-0.62 (docs/estimator.md, "Stop 44").
            max_rows: 800,
            draws: 3,
            seed: 7,
        }
    }
}

/// One labelled training cluster.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingRow {
    /// Its [`cluster_inputs`].
    pub inputs: [f64; MOVING_INPUTS],
    /// Whether most of its points move ([`super::cluster_is_moving`]).
    pub moving: bool,
    /// Its points that truly move.
    pub moving_points: usize,
    /// Its points that do not.
    pub static_points: usize,
}

impl MovingRow {
    /// The row of cluster `c` of `features`, cut from `sweep`.
    pub fn of(features: &SweepFeatures, change: &ChangeEvidence, sweep: &Sweep, c: usize) -> Self {
        let members = features.clusters().members(c);
        let moving_points = members
            .iter()
            .filter(|&&i| {
                let v = sweep.flow_in_world_mps[features.points()[i].index];
                f64::from(v[0]).hypot(f64::from(v[1])) > super::MOVING_SPEED_MPS
            })
            .count();
        Self {
            inputs: cluster_inputs(features, change, c),
            // As `cluster_is_moving`: most of its points move (counted once, above).
            moving: 2 * moving_points > members.len(),
            moving_points,
            static_points: members.len() - moving_points,
        }
    }
}

/// A trained moving/static classifier: a bag of GPs on seeded draws and one decision threshold.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingClassifier {
    pub(super) draws: Vec<MovingDraw>,
    pub(super) threshold: f64,
}

/// The rows of the chosen scans `ks` (increasing) of a sequence: for scan `k` the maps of sweeps
/// `k − 1` and `k`, the observed change since sweep `k − 5` (or the first). Each sweep is read
/// and cut once, however many of the scans need it (all of them when every scan is chosen).
fn sequence_rows(
    sequence: &patchflow_dataset::SequenceReader,
    ks: &[usize],
    valid: &FeatureValidParams,
) -> Result<Vec<MovingRow>> {
    let mut slices: BTreeMap<usize, HeightSlice> = BTreeMap::new();
    let mut rows = Vec::new();
    for &k in ks {
        let past_index = k.saturating_sub(CHANGE_BASELINE_SCANS);
        // Sweeps before the oldest this scan needs are needed by no later one.
        slices.retain(|&i, _| i >= past_index);
        let current = sequence.read_sweep(k)?;
        for i in [past_index, k - 1] {
            if let Entry::Vacant(slot) = slices.entry(i) {
                slot.insert(HeightSlice::cut(&sequence.read_sweep(i)?, valid)?);
            }
        }
        let now = HeightSlice::cut(&current, valid)?;
        let (Some(past), Some(previous)) = (slices.get(&past_index), slices.get(&(k - 1))) else {
            continue; // both inserted above
        };
        let features = SweepFeatures::from_slices(previous, &now, valid)?;
        let change = ChangeEvidence::build(past, &now, valid);
        rows.extend(
            features
                .object_hypotheses()
                .into_iter()
                .map(|c| MovingRow::of(&features, &change, &current, c)),
        );
        slices.insert(k, now);
    }
    Ok(rows)
}

impl MovingClassifier {
    /// Learns from every sequence of `dataset` with the maps of `features` (the motion model's).
    pub fn train(
        dataset: &Dataset,
        features: &FeatureParams,
        params: &MovingParams,
    ) -> Result<Self> {
        Self::fit(Self::labelled_clusters(dataset, features, params)?, params)
    }

    /// The labelled clusters [`Self::train`] fits on: those of at most `params.max_scans` scans
    /// evenly spaced over every sequence of `dataset`, read with the maps of `features`. Fitting
    /// them with [`Self::fit`] under several seeds compares draws without reading the maps again.
    pub fn labelled_clusters(
        dataset: &Dataset,
        features: &FeatureParams,
        params: &MovingParams,
    ) -> Result<Vec<MovingRow>> {
        // The classifier reads the maps, never a patch: no patch maps are built for it.
        let valid = features.without_patch_maps().check()?;
        let mut scans = Vec::new();
        for info in dataset.sequences() {
            scans.extend((1..info.sweeps as usize).map(|k| (info.name.as_str(), k)));
        }
        let stride = scans.len().div_ceil(params.max_scans.max(1)).max(1);
        // Evenly spaced scans, grouped by sequence in dataset order.
        let mut chosen: Vec<(&str, Vec<usize>)> = Vec::new();
        for &(name, k) in scans.iter().step_by(stride) {
            match chosen.last_mut() {
                Some((last, ks)) if *last == name => ks.push(k),
                _ => chosen.push((name, vec![k])),
            }
        }
        let per_sequence = chosen
            .par_iter()
            .map(|(name, ks)| sequence_rows(&dataset.sequence(name)?, ks, &valid))
            .collect::<Result<Vec<_>>>()?;
        Ok(per_sequence.into_iter().flatten().collect())
    }

    /// Fits the classifier to labelled clusters: `params.draws` GPs, each on at most
    /// `params.max_rows / 2` moving clusters and as many static ones drawn uniformly under its
    /// own seed; the decision threshold from the draws' mean held-out probabilities of all rows.
    pub fn fit(rows: Vec<MovingRow>, params: &MovingParams) -> Result<Self> {
        if rows.iter().any(|r| r.inputs.iter().any(|v| !v.is_finite())) {
            return Err(LearnError::degenerate_data(
                "a cluster's moving-classifier inputs are not finite".into(),
            ));
        }
        let seeds: Vec<u64> = (0..params.draws.max(1) as u64)
            .map(|k| params.seed.wrapping_add(k))
            .collect();
        let inputs: Vec<[f64; MOVING_INPUTS]> = rows.iter().map(|r| r.inputs).collect();
        let moving: Vec<bool> = rows.iter().map(|r| r.moving).collect();
        let fitted = seeds
            .par_iter()
            .map(|&seed| MovingDraw::fit(&inputs, &moving, params.max_rows, seed))
            .collect::<Result<Vec<_>>>()?;
        let bag = fitted.len() as f64;
        let scored: Vec<ScoredCluster> = rows
            .iter()
            .enumerate()
            .map(|(i, r)| ScoredCluster {
                probability: fitted.iter().map(|(_, p)| p[i]).sum::<f64>() / bag,
                moving_points: r.moving_points,
                static_points: r.static_points,
            })
            .collect();
        let (threshold, _) = iou_threshold(&scored);
        Ok(Self {
            draws: fitted.into_iter().map(|(draw, _)| draw).collect(),
            threshold,
        })
    }

    /// Per cluster of `features`, the probability that it moves (the mean of the draws'): `Some`
    /// for object hypotheses, `None` for the clusters too long to be one object (static).
    /// `change` is the observed change since [`CHANGE_BASELINE_SCANS`] sweeps back on the same
    /// current sweep.
    pub fn cluster_probabilities(
        &self,
        features: &SweepFeatures,
        change: &ChangeEvidence,
    ) -> Result<Vec<Option<f64>>> {
        let hypotheses = features.object_hypotheses();
        let mut out = vec![None; features.clusters().len()];
        if hypotheses.is_empty() {
            return Ok(out);
        }
        // Every hypothesis' inputs, then every draw's probabilities, side by side; the mean adds
        // the draws in their order.
        let inputs: Vec<[f64; MOVING_INPUTS]> = hypotheses
            .par_iter()
            .map(|&c| cluster_inputs(features, change, c))
            .collect();
        let x = DMatrix::from_fn(inputs.len(), MOVING_INPUTS, |i, d| inputs[i][d]);
        let per_draw: Vec<Vec<f64>> = self
            .draws
            .par_iter()
            .map(|draw| draw.probabilities(&x))
            .collect::<Result<_>>()?;
        let mut mean = vec![0.0; hypotheses.len()];
        for probabilities in per_draw {
            for (m, p) in mean.iter_mut().zip(probabilities) {
                *m += p / self.draws.len() as f64;
            }
        }
        for (&c, p) in hypotheses.iter().zip(mean) {
            out[c] = Some(p);
        }
        Ok(out)
    }

    /// The decision per cluster: `Some(true)` for an object hypothesis whose probability of moving
    /// is above [`Self::threshold`], `None` for the clusters that are no object hypothesis.
    pub fn cluster_decisions(
        &self,
        features: &SweepFeatures,
        change: &ChangeEvidence,
    ) -> Result<Vec<Option<bool>>> {
        Ok(self.decided(self.cluster_probabilities(features, change)?))
    }

    /// [`Self::cluster_decisions`] on the probabilities smoothed along the clusters' own tracks
    /// ([`MovingBelief`]; the scans of one sequence in order, `stamp_secs` increasing): what the
    /// benchmark's learned methods decide with.
    pub fn tracked_decisions(
        &self,
        belief: &mut MovingBelief,
        features: &SweepFeatures,
        change: &ChangeEvidence,
        stamp_secs: f64,
    ) -> Result<Vec<Option<bool>>> {
        let probabilities = self.cluster_probabilities(features, change)?;
        Ok(self.decided(belief.update_features(features, &probabilities, stamp_secs)))
    }

    /// Moving where a probability is above [`Self::threshold`].
    fn decided(&self, probabilities: Vec<Option<f64>>) -> Vec<Option<bool>> {
        probabilities
            .into_iter()
            .map(|p| p.map(|p| p > self.threshold))
            .collect()
    }

    /// The probability above which a cluster is called moving: the one that maximised the moving
    /// IoU on the training clusters (`decision_threshold.rs`).
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// Per draw of the bag, the clusters its GP was fitted on and how many of them moved.
    pub fn training_rows(&self) -> Vec<(usize, usize)> {
        self.draws.iter().map(|d| (d.rows, d.moving_rows)).collect()
    }
}

#[cfg(test)]
#[path = "moving_classifier_tests.rs"]
mod tests;
