//! What the motion estimator says about one scan: per cluster the merged heading and speed
//! (thesis 3.1.4), per point its own heading and speed prediction (thesis 3.1.1), and the cost.

use crate::SweepFeatures;

/// A merged motion estimate for one cluster.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClusterMotion {
    /// Heading, world frame, CCW from +x.
    pub heading_rad: f64,
    /// Approximate variance of the heading, rad².
    pub heading_var: f64,
    /// Speed, m/s.
    pub speed_mps: f64,
    /// Variance of the merged speed, (m/s)².
    pub speed_var: f64,
    /// Points whose heading predictions took part in the merge.
    pub heading_votes: usize,
}

/// What a cluster gets under both merge rules (thesis 3.1.4).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClusterEstimate {
    /// Product of all per-point predictions.
    pub all: Option<ClusterMotion>,
    /// Product of the low-variance predictions only.
    pub best: Option<ClusterMotion>,
}

/// One point's own prediction: the heading its patch votes for (its sin and cos prediction
/// turned into the world frame) and the speed its patch shows when aligned to the cluster's
/// merged (ALL) heading, as thesis 3.1.1 aligns speed patches. In the whole-scan step the points
/// of one map cell share the prediction at their mean (see `CellSamples`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointMotion {
    /// Heading, world frame, CCW from +x.
    pub heading_rad: f64,
    /// Its variance by the delta method, rad².
    pub heading_var: f64,
    /// Speed, m/s (negative predictions read as 0).
    pub speed_mps: f64,
    /// Predictive variance of the speed, (m/s)².
    pub speed_var: f64,
}

impl PointMotion {
    /// Velocity in the world's ground plane, m/s.
    pub fn velocity_xy_mps(&self) -> [f64; 2] {
        let (s, c) = self.heading_rad.sin_cos();
        [self.speed_mps * c, self.speed_mps * s]
    }
}

/// Wall time of the estimator's steps on one scan, seconds.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PredictionTiming {
    /// Choosing the clusters that can be objects.
    pub hypotheses_secs: f64,
    /// Heading and speed patches (thesis 2.2.2), Gabor responses if the model reads them.
    pub patches_secs: f64,
    /// GP predictions: sin and cos of the relative heading, speed (thesis 3.1.3).
    pub gp_secs: f64,
    /// Merging per cluster (thesis 3.1.4).
    pub merge_secs: f64,
    /// Clusters estimated.
    pub clusters: usize,
    /// Positions predicted at: occupied map cells in the whole-scan step, points for one cluster.
    pub rows: usize,
    /// Sliced points the clusters hold.
    pub points: usize,
}

impl PredictionTiming {
    /// All steps together.
    pub fn total_secs(&self) -> f64 {
        self.hypotheses_secs + self.patches_secs + self.gp_secs + self.merge_secs
    }
}

/// The estimator's result on one scan's features (thesis Algorithm 3.1, steps 3 and 4).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ScanMotion {
    /// Per cluster id of the features: its estimate, `None` for a cluster that is no object
    /// hypothesis (longer than any road user, see `ClusterShape`).
    pub clusters: Vec<Option<ClusterEstimate>>,
    /// Per sliced point of the features: its own prediction, `None` outside the hypotheses or
    /// where the cluster got no merged heading.
    pub points: Vec<Option<PointMotion>>,
    /// What the steps cost.
    pub timing: PredictionTiming,
}

/// One scan end to end: its features (thesis Algorithm 3.1, steps 1 and 2) and the estimator's
/// motion for them (steps 3 and 4).
#[derive(Debug, Clone)]
pub struct ScanEstimate {
    /// Maps, points and clusters.
    pub features: SweepFeatures,
    /// Heading and speed per cluster and per point.
    pub motion: ScanMotion,
}
