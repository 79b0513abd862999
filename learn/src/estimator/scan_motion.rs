//! The per-scan step of thesis Algorithm 3.1: cluster the scan, build the difference map, then
//! predict and merge heading and speed for every cluster that can be an object.

use std::time::Instant;

use patchflow_dataset::Sweep;

use super::cluster_estimate::{ClusterEstimate, ScanEstimate, ScanMotion};
use crate::features::{CellSamples, MIN_OBJECT_POINTS};
use crate::{MotionEstimator, Result, SweepFeatures};

/// Largest share of the cells around a hypothesis that the previous sweep may have left
/// unobserved ([`SweepFeatures::unobserved_before_share`]) for it to get an estimate. Above it
/// the object has just come into view (from behind a building or a parked car, or into range)
/// and its difference map shows that, not its motion: a car emerging from behind a building
/// looks like one driving away from the sensor, and the GPs read it so with a stated deviation
/// of 5-8° while 140-163° off (docs/estimator.md, "Stop 45"). On the five situations' target
/// scans of ten points or more the share is at most 0.77 with the default's patch maps (the
/// thesis preset's 0.10 m maps reach it on one target scan in each of situations 4 and 5,
/// docs/estimator.md "Stop 46"); on those three scans it is 1.
pub const MAX_UNOBSERVED_BEFORE: f64 = 0.9;

/// Whether the object at `positions_xy` has just come into view ([`MAX_UNOBSERVED_BEFORE`]).
fn has_just_come_into_view(features: &SweepFeatures, positions_xy: &[[f64; 2]]) -> bool {
    features.unobserved_before_share(positions_xy) > MAX_UNOBSERVED_BEFORE
}

impl MotionEstimator {
    /// Thesis Algorithm 3.1 on one scan given the previous one. To process a sequence in order,
    /// cutting each sweep once, run a [`ScanStream`](crate::ScanStream) and call
    /// [`Self::estimate_features`] on its features.
    ///
    /// ```no_run
    /// # fn main() -> Result<(), Box<dyn std::error::Error>> {
    /// use std::path::Path;
    /// let estimator = patchflow_learn::MotionEstimator::load(Path::new("models/spgp-het.json"))?;
    /// let dataset = patchflow_dataset::Dataset::open(Path::new("data/situations"))?;
    /// let sequence = dataset.sequence("situation1")?;
    /// let scan = estimator.estimate_scan(&sequence.read_sweep(9)?, &sequence.read_sweep(10)?)?;
    /// for (c, estimate) in scan.motion.clusters.iter().enumerate() {
    ///     if let Some(all) = estimate.and_then(|e| e.all) {
    ///         println!("cluster {c}: {:.0}° at {:.1} m/s", all.heading_rad.to_degrees(), all.speed_mps);
    ///     }
    /// }
    /// # Ok(())
    /// # }
    /// ```
    pub fn estimate_scan(&self, previous: &Sweep, current: &Sweep) -> Result<ScanEstimate> {
        // Steps 1 and 2: clusters of the scan (2.2.1), difference of the maps at t and t−1 (2.1.2).
        let features = SweepFeatures::compute_checked(previous, current, &self.features)?;
        // Steps 3 and 4: heading, then speed, of every object hypothesis.
        let motion = self.estimate_features(&features)?;
        Ok(ScanEstimate { features, motion })
    }

    /// Steps 3 and 4 of thesis Algorithm 3.1 on features already computed (with this model's
    /// feature parameters): every cluster that can be one object gets a heading and a speed
    /// under both merge rules, and each of its points the prediction of its map cell.
    pub fn estimate_features(&self, features: &SweepFeatures) -> Result<ScanMotion> {
        let start = Instant::now();
        // Step 1's object hypotheses: the clusters no longer than a road user, each predicted
        // once per occupied map cell (the patches' resolution).
        // Hypotheses that have just come into view show no motion yet (MAX_UNOBSERVED_BEFORE).
        let (hypotheses, samples): (Vec<usize>, Vec<CellSamples>) = features
            .object_hypotheses()
            .into_iter()
            .map(|c| {
                (
                    c,
                    features.patch_cell_samples(features.clusters().members(c)),
                )
            })
            .filter(|(_, s)| !has_just_come_into_view(features, &s.positions))
            .unzip();
        let positions: Vec<&[[f64; 2]]> = samples.iter().map(|s| &s.positions[..]).collect();
        let hypotheses_secs = start.elapsed().as_secs_f64();
        // Steps 3 and 4 for all of them at once.
        let predicted = self.predict_clusters(features, &positions)?;
        let mut clusters = vec![None; features.clusters().len()];
        let mut points = vec![None; features.len()];
        for ((&c, samples), (estimate, motions)) in hypotheses
            .iter()
            .zip(&samples)
            .zip(predicted.estimates.into_iter().zip(predicted.points))
        {
            clusters[c] = Some(estimate);
            let members = features.clusters().members(c);
            for (&i, &sample) in members.iter().zip(&samples.sample_of_member) {
                points[i] = motions[sample];
            }
        }
        let mut timing = predicted.timing;
        timing.hypotheses_secs = hypotheses_secs;
        timing.points = hypotheses
            .iter()
            .map(|&c| features.clusters().members(c).len())
            .sum();
        Ok(ScanMotion {
            clusters,
            points,
            timing,
        })
    }

    /// Steps 3 and 4 for one cluster under both merge rules, predicted at every one of its
    /// points as thesis 4.4 does for its hand-labelled target. `members` index `features.points()`.
    /// A cluster of fewer than [`MIN_OBJECT_POINTS`] points gets no estimate, as it would not be
    /// an object hypothesis (too few cells of the difference map to show its motion), nor does
    /// one that has just come into view ([`MAX_UNOBSERVED_BEFORE`]).
    pub fn estimate_cluster(
        &self,
        features: &SweepFeatures,
        members: &[usize],
    ) -> Result<ClusterEstimate> {
        if members.len() < MIN_OBJECT_POINTS {
            return Ok(ClusterEstimate::default());
        }
        let positions = features.positions_xy(members);
        if has_just_come_into_view(features, &positions) {
            return Ok(ClusterEstimate::default());
        }
        let predicted = self.predict_clusters(features, &[&positions])?;
        Ok(predicted.estimates.into_iter().next().unwrap_or_default())
    }
}
