//! The learned perception of issue 27 as a car would run it, scan by scan and without any
//! truth: thesis Algorithm 3.1's whole-scan step of one estimator, the moving classifier on every
//! object hypothesis, then GP-KF over every cluster and GP-ICP on the hypotheses. The benchmark's
//! evaluation runs the same steps beside the baselines; this is the public entry for one model
//! (and the Criterion bench of the whole learned scan).

use patchflow_learn::{
    ChangeEvidence, MotionEstimator, MovingBelief, MovingClassifier, RangeProfile, ScanMotion,
    SweepFeatures,
};

use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::methods::baselines::velocity_measurement::GpVelocityNoise;
use crate::methods::estimate::{MotionEstimate, to_estimate};
use crate::methods::learned::learned_step::{LearnedCluster, LearnedTrackers};
use crate::methods::learned::plausible_motion::implausible_motion;
use crate::methods::observation::{ClusterObservation, ScanObservation};

/// What the learned perception says about one scan, per cluster of its features.
#[derive(Debug, Clone, PartialEq)]
pub struct LearnedScan {
    /// The estimator's step (per cluster ALL and BEST, per point).
    pub motion: ScanMotion,
    /// The moving classifier's decision per object hypothesis (`None` without a classifier and
    /// for the clusters too long to be one object).
    pub moving: Vec<Option<bool>>,
    /// GP-KF's estimate per cluster.
    pub gp_kf: Vec<Option<MotionEstimate>>,
    /// GP-ICP's estimate per hypothesis linked to a cluster of the scan before.
    pub gp_icp: Vec<Option<MotionEstimate>>,
}

/// One estimator, an optional moving classifier and the GP-informed trackers over a sequence.
#[derive(Debug)]
pub struct LearnedPerception<'a> {
    estimator: &'a MotionEstimator,
    moving: Option<&'a MovingClassifier>,
    belief: MovingBelief,
    trackers: LearnedTrackers,
    scans: usize,
}

impl<'a> LearnedPerception<'a> {
    /// Fresh trackers (the baselines' filter, gate and ICP parameters).
    pub fn new(
        estimator: &'a MotionEstimator,
        moving: Option<&'a MovingClassifier>,
        params: &BaselineParams,
    ) -> Result<Self, EvalError> {
        Ok(Self {
            estimator,
            moving,
            belief: MovingBelief::default(),
            trackers: LearnedTrackers::new(params, GpVelocityNoise::default())?,
            scans: 0,
        })
    }

    /// The next scan's features (computed with the estimator's feature parameters) and the
    /// change observed on it over the last half second (what the moving classifier reads beside
    /// the features: [`ChangeEvidence`]), taken at `stamp_secs` (increasing from scan to scan).
    pub fn step(
        &mut self,
        features: &SweepFeatures,
        change: &ChangeEvidence,
        stamp_secs: f64,
    ) -> Result<LearnedScan, EvalError> {
        let motion = self.estimator.estimate_features(features)?;
        if let Some(reason) = implausible_motion(&motion) {
            return Err(EvalError::BadObservation {
                situation: "-".to_owned(),
                scan: self.scans,
                reason,
            });
        }
        let moving: Vec<Option<bool>> = match self.moving {
            Some(classifier) => {
                classifier.tracked_decisions(&mut self.belief, features, change, stamp_secs)?
            }
            None => vec![None; features.clusters().len()],
        };
        let observation = ScanObservation {
            scan: self.scans,
            stamp_secs,
            sensor_xy_world: features.sensor_xy(),
            clusters: ClusterObservation::all_of(features, &RangeProfile::of(features)),
            actors: Default::default(),
            target_actor: None,
        };
        self.scans += 1;
        let learned: Vec<LearnedCluster> = (0..features.clusters().len())
            .map(|c| LearnedCluster {
                gp: motion.clusters[c].and_then(|e| e.all).map(to_estimate),
                moving: moving[c],
            })
            .collect();
        let mut hypotheses = vec![false; features.clusters().len()];
        for c in features.object_hypotheses() {
            hypotheses[c] = true;
        }
        let estimates =
            |flows: Vec<Option<crate::methods::baselines::baseline_step::ClusterFlow>>| {
                flows
                    .into_iter()
                    .map(|f| f.map(|f| f.estimate()))
                    .collect::<Vec<_>>()
            };
        let gp_kf = estimates(self.trackers.step_kf(&observation, &learned)?);
        let gp_icp = estimates(
            self.trackers
                .step_icp(&observation, &learned, &hypotheses)?,
        );
        Ok(LearnedScan {
            motion,
            moving,
            gp_kf,
            gp_icp,
        })
    }
}
