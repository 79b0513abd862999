//! What the perception of one scan costs (SPEC §8: a whole scan under 100 ms, the sensor's
//! 10 Hz), stage by stage as thesis Algorithm 3.1 runs: the height slice, maps and clusters once
//! per scan, then per estimator the object hypotheses, patches, GP predictions and merging.
//! Scans run one after the other, each using every core, so a scan's wall time is its latency.

use patchflow_learn::{FeatureTiming, PredictionTiming};
use serde::{Deserialize, Serialize};

use crate::scene::metrics::median;

/// Wall times of one scan, seconds.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct ScanTiming {
    /// Height slice of the new sweep (thesis 2.1.1).
    pub slice_secs: f64,
    /// Reflection and difference maps (thesis 2.1), inside their parallel branch.
    pub maps_secs: f64,
    /// Single-link clusters (thesis 2.2.1), inside their parallel branch.
    pub clusters_secs: f64,
    /// Maps and clusters, side by side.
    pub maps_and_clusters_secs: f64,
    /// Per estimator: hypotheses, patches, GP prediction and merging for the whole scan.
    pub estimators: Vec<StepTiming>,
    /// CPU time of the whole scan (features and every estimator's step), all threads, where the
    /// system reports it: the scan's latency on idle cores is at least this over their number.
    #[serde(default)]
    pub whole_scan_cpu_secs: Option<f64>,
    /// The four baselines over every cluster (KF-AUTO, ICP-AUTO on the hypotheses, the oracles).
    pub baselines_secs: f64,
    /// Per estimator, the thesis-protocol estimate of the target from all its points (the
    /// per-target tables; not part of the whole-scan step).
    pub target_secs: f64,
    /// Sliced points of the target's cluster.
    pub target_points: usize,
    /// The moving classifier on every object hypothesis, with the change evidence it reads (0
    /// without a classifier).
    #[serde(default)]
    pub segmentation_secs: f64,
    /// GP-KF over every cluster.
    #[serde(default)]
    pub gp_kf_secs: f64,
    /// GP-ICP on the hypotheses.
    #[serde(default)]
    pub gp_icp_secs: f64,
    /// CPU time of the whole learned scan with the first estimator (features, its step, the
    /// moving classifier with the change evidence it reads, GP-KF, GP-ICP), all threads, where
    /// the system reports it.
    #[serde(default)]
    pub learned_scan_cpu_secs: Option<f64>,
}

/// One estimator's whole-scan step, seconds (see [`PredictionTiming`]).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct StepTiming {
    /// Choosing the object hypotheses and their map-cell samples.
    pub hypotheses_secs: f64,
    /// Heading and speed patches.
    pub patches_secs: f64,
    /// GP predictions.
    pub gp_secs: f64,
    /// Merging per cluster.
    pub merge_secs: f64,
    /// Clusters estimated.
    pub clusters: usize,
    /// Map-cell samples predicted at.
    pub samples: usize,
    /// Sliced points those clusters hold.
    pub points: usize,
}

impl From<PredictionTiming> for StepTiming {
    fn from(t: PredictionTiming) -> Self {
        Self {
            hypotheses_secs: t.hypotheses_secs,
            patches_secs: t.patches_secs,
            gp_secs: t.gp_secs,
            merge_secs: t.merge_secs,
            clusters: t.clusters,
            samples: t.rows,
            points: t.points,
        }
    }
}

impl StepTiming {
    /// All of the step.
    pub fn total_secs(&self) -> f64 {
        self.hypotheses_secs + self.patches_secs + self.gp_secs + self.merge_secs
    }
}

impl ScanTiming {
    /// The feature stages of a scan.
    pub fn with_features(features: FeatureTiming) -> Self {
        Self {
            slice_secs: features.slice_secs,
            maps_secs: features.maps_secs,
            clusters_secs: features.clusters_secs,
            maps_and_clusters_secs: features.maps_and_clusters_secs,
            ..Self::default()
        }
    }

    /// Slice, maps and clusters.
    pub fn features_secs(&self) -> f64 {
        self.slice_secs + self.maps_and_clusters_secs
    }

    /// The whole scan for every estimator: features once, then each estimator's step.
    pub fn whole_scan_secs(&self) -> f64 {
        self.features_secs()
            + self
                .estimators
                .iter()
                .map(StepTiming::total_secs)
                .sum::<f64>()
    }

    /// The whole learned perception of a scan with one estimator: features, one GP step, the
    /// moving classifier, GP-KF and GP-ICP (issue 27's real-time figure).
    pub fn learned_scan_secs(&self) -> f64 {
        self.one_estimator_secs() + self.segmentation_secs + self.gp_kf_secs + self.gp_icp_secs
    }

    /// The whole scan for one estimator (the mean over the estimators run): what a car running
    /// one trained model needs.
    pub fn one_estimator_secs(&self) -> f64 {
        let n = self.estimators.len().max(1) as f64;
        self.features_secs()
            + self
                .estimators
                .iter()
                .map(StepTiming::total_secs)
                .sum::<f64>()
                / n
    }
}

/// Median and largest of a stage over the scans, seconds.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Spread {
    /// Median.
    pub median_secs: f64,
    /// Largest (the worst scan).
    pub worst_secs: f64,
}

impl Spread {
    /// Median and maximum of `values` (zero for none; the median of an even count is the mean of
    /// the middle two).
    pub fn of(values: impl Iterator<Item = f64>) -> Self {
        let v: Vec<f64> = values.collect();
        match (
            median(v.iter().copied()),
            v.iter().copied().max_by(f64::total_cmp),
        ) {
            (Some(median_secs), Some(worst_secs)) => Self {
                median_secs,
                worst_secs,
            },
            _ => Self::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_of_an_even_count_is_the_mean_of_the_middle_two() {
        let s = Spread::of([4.0, 1.0, 3.0, 2.0].into_iter());
        assert_eq!((s.median_secs, s.worst_secs), (2.5, 4.0));
        assert_eq!(Spread::of(std::iter::empty()), Spread::default());
    }

    #[test]
    fn the_whole_scan_counts_the_features_once_and_every_estimator() {
        let step = StepTiming {
            patches_secs: 0.010,
            gp_secs: 0.020,
            ..StepTiming::default()
        };
        let scan = ScanTiming {
            slice_secs: 0.002,
            maps_and_clusters_secs: 0.018,
            estimators: vec![step, step],
            ..ScanTiming::default()
        };
        assert!((scan.whole_scan_secs() - 0.080).abs() < 1e-12);
        assert!((scan.one_estimator_secs() - 0.050).abs() < 1e-12);
    }
}
