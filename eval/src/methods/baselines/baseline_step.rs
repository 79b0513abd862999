//! The four baselines of thesis 3.2 run scan by scan over a whole scene (SPEC §6):
//!
//! - `KF`, `ICP`: one Kalman filter per actor on its cluster's centroid, and ICP between the
//!   actor's cluster at t−1 and at t; the association comes from ground truth (as in the thesis).
//!   A filter coasts through scans where its actor is not seen and reports nothing there.
//! - `KF-AUTO`: the multi-target tracker over all clusters ([`MultiTargetTracker`]); a cluster
//!   gets the estimate of the confirmed track that took it.
//! - `ICP-AUTO`: clusters linked scan to scan by nearest predicted centroid
//!   ([`CentroidAssociator`]); ICP between a cluster and the one it was linked to.
//!
//! Each scan yields, per method and cluster, how the cluster's points move ([`ClusterFlow`]).

use std::collections::{BTreeMap, BTreeSet};

use rayon::prelude::*;

use crate::error::EvalError;
use crate::methods::baselines::baseline_params::BaselineParams;
use crate::methods::baselines::cluster_association::CentroidAssociator;
use crate::methods::baselines::kalman::ConstantVelocityKalman;
use crate::methods::baselines::rigid_motion::{RigidMotion, icp_rigid_motion};
use crate::methods::baselines::tracker::{MultiTargetTracker, TrackStatus};
use crate::methods::estimate::MotionEstimate;
use crate::methods::method::Method;
use crate::methods::observation::ScanObservation;

/// How a baseline moves the points of one cluster over the last sweep interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClusterFlow {
    /// Every point with one velocity (the Kalman filters' centroid velocity).
    Uniform(MotionEstimate),
    /// Every point by ICP's rigid transform.
    Rigid(RigidMotion),
}

impl ClusterFlow {
    /// The cluster's motion estimate (heading and speed of the object).
    pub fn estimate(&self) -> MotionEstimate {
        match self {
            Self::Uniform(estimate) => *estimate,
            Self::Rigid(motion) => motion.estimate,
        }
    }

    /// Velocity of the cluster's point at `xy` (world frame), m/s.
    pub fn velocity_at(&self, xy: [f64; 2]) -> [f64; 2] {
        match self {
            Self::Uniform(estimate) => estimate.velocity_xy_mps,
            Self::Rigid(motion) => motion.velocity_of_current_point(xy),
        }
    }
}

/// What the baselines say about one scan.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct BaselineScan {
    /// Per baseline method, per cluster of the scan: its flow, if the method has one.
    pub clusters: BTreeMap<Method, Vec<Option<ClusterFlow>>>,
    /// Per oracle method (`KF`, `ICP`), per actor seen: its estimate.
    pub actors: BTreeMap<Method, BTreeMap<u16, ClusterFlow>>,
}

impl BaselineScan {
    /// A method's flow for cluster `c`.
    pub fn cluster_flow(&self, method: Method, c: usize) -> Option<ClusterFlow> {
        *self.clusters.get(&method)?.get(c)?
    }

    /// A method's estimate of an actor: from its own oracle track for `KF` and `ICP`, from the
    /// actor's cluster for the others.
    pub fn actor_estimate(
        &self,
        method: Method,
        actor: u16,
        scan: &ScanObservation,
    ) -> Option<MotionEstimate> {
        match self.actors.get(&method) {
            Some(actors) => actors.get(&actor).map(ClusterFlow::estimate),
            None => self
                .cluster_flow(method, scan.actor_cluster(actor)?)
                .map(|f| f.estimate()),
        }
    }
}

/// The baselines' state between scans.
#[derive(Debug)]
pub struct BaselineTrackers {
    situation: String,
    params: BaselineParams,
    oracle_filters: BTreeMap<u16, ConstantVelocityKalman>,
    tracker: MultiTargetTracker,
    associator: CentroidAssociator,
    previous: Option<ScanObservation>,
}

impl BaselineTrackers {
    /// Fresh baselines for one situation (`situation` labels errors).
    pub fn new(situation: &str, params: &BaselineParams) -> Result<Self, EvalError> {
        Ok(Self {
            situation: situation.to_owned(),
            params: *params,
            oracle_filters: BTreeMap::new(),
            tracker: MultiTargetTracker::new(params.tracker)?,
            associator: CentroidAssociator::new(params.association),
            previous: None,
        })
    }

    /// Runs every baseline on the next scan (in time order). ICP-AUTO, the costly one, runs only
    /// for the clusters with `icp_wanted[c]` (a shorter slice means the rest are not wanted).
    pub fn step(
        &mut self,
        scan: ScanObservation,
        icp_wanted: &[bool],
    ) -> Result<BaselineScan, EvalError> {
        let dt = self.interval(&scan)?;
        let label = |err: EvalError| match err {
            EvalError::BadObservation { scan, reason, .. } => EvalError::BadObservation {
                situation: self.situation.clone(),
                scan,
                reason,
            },
            other => other,
        };
        let n = scan.clusters.len();
        let mut out = BaselineScan::default();
        // KF: predict every actor's filter to this scan, update those seen.
        let mut kf = BTreeMap::new();
        if let Some(dt) = dt {
            for filter in self.oracle_filters.values_mut() {
                filter.predict(dt);
            }
        }
        for (&actor, seen) in &scan.actors {
            let centroid = scan.clusters[seen.cluster].centroid_xy;
            match self.oracle_filters.get_mut(&actor) {
                Some(filter) => {
                    filter.update(centroid)?;
                }
                None => {
                    let filter = ConstantVelocityKalman::new(centroid, self.params.kalman)?;
                    self.oracle_filters.insert(actor, filter);
                }
            }
            if let Some(estimate) = self.oracle_filters[&actor].estimate() {
                kf.insert(actor, ClusterFlow::Uniform(estimate));
            }
        }
        // KF-AUTO: the confirmed track that took each cluster.
        let centroids: Vec<[f64; 2]> = scan.clusters.iter().map(|c| c.centroid_xy).collect();
        let track_of_cluster = self
            .tracker
            .step(scan.scan, scan.stamp_secs, &centroids)
            .map_err(label)?;
        let kf_auto = track_of_cluster
            .iter()
            .map(|id| {
                let track = self.tracker.track((*id)?)?;
                (track.status == TrackStatus::Confirmed)
                    .then(|| track.filter.estimate())
                    .flatten()
                    .map(ClusterFlow::Uniform)
            })
            .collect();
        // ICP: the actor's cluster at t−1 against its cluster at t. ICP-AUTO: each wanted
        // cluster against the cluster it was linked to. Both often ask for the same pair of
        // clusters, so every distinct pair is aligned once, all pairs in parallel (each alignment
        // is independent of the others).
        let links = self.associator.step(&scan).map_err(label)?;
        // The scan before and the interval to it; neither ICP runs without both.
        let prior = self.previous.as_ref().zip(dt);
        let icp_pairs: Vec<(u16, (usize, usize))> = prior.map_or_else(Vec::new, |(previous, _)| {
            scan.actors
                .iter()
                .filter_map(|(&actor, seen)| {
                    Some((actor, (previous.actor_cluster(actor)?, seen.cluster)))
                })
                .collect()
        });
        let auto_pairs: Vec<Option<(usize, usize)>> = (0..n)
            .map(|c| {
                prior?;
                let wanted = icp_wanted.get(c).copied().unwrap_or(false);
                wanted.then(|| links.get(c).copied().flatten().map(|before| (before, c)))?
            })
            .collect();
        let aligned = prior.map_or_else(BTreeMap::new, |(previous, dt)| {
            align_pairs(
                previous,
                &scan,
                icp_pairs
                    .iter()
                    .map(|(_, pair)| *pair)
                    .chain(auto_pairs.iter().flatten().copied()),
                dt,
                &self.params,
            )
        });
        let flow_of =
            |pair: &(usize, usize)| aligned.get(pair).copied().flatten().map(ClusterFlow::Rigid);
        let icp: BTreeMap<u16, ClusterFlow> = icp_pairs
            .iter()
            .filter_map(|(actor, pair)| Some((*actor, flow_of(pair)?)))
            .collect();
        let icp_auto: Vec<Option<ClusterFlow>> = auto_pairs
            .iter()
            .map(|pair| flow_of(pair.as_ref()?))
            .collect();
        out.clusters.insert(Method::Kf, oracle_clusters(&kf, &scan));
        out.clusters
            .insert(Method::Icp, oracle_clusters(&icp, &scan));
        out.clusters.insert(Method::KfAuto, kf_auto);
        out.clusters.insert(Method::IcpAuto, icp_auto);
        out.actors.insert(Method::Kf, kf);
        out.actors.insert(Method::Icp, icp);
        self.previous = Some(scan);
        Ok(out)
    }

    /// Seconds since the previous scan (`None` for the first), checked to increase.
    fn interval(&self, scan: &ScanObservation) -> Result<Option<f64>, EvalError> {
        let Some(previous) = &self.previous else {
            return Ok(None);
        };
        let dt = scan.stamp_secs - previous.stamp_secs;
        if dt > 0.0 && dt.is_finite() {
            Ok(Some(dt))
        } else {
            Err(EvalError::BadObservation {
                situation: self.situation.clone(),
                scan: scan.scan,
                reason: format!(
                    "time stamp {} s does not follow {} s",
                    scan.stamp_secs, previous.stamp_secs
                ),
            })
        }
    }
}

/// ICP between cluster `before` of `previous` and cluster `current` of `scan` for every distinct
/// pair asked for, in parallel; a pair whose alignment fails (or names no cluster) maps to `None`.
fn align_pairs(
    previous: &ScanObservation,
    scan: &ScanObservation,
    pairs: impl Iterator<Item = (usize, usize)>,
    dt: f64,
    params: &BaselineParams,
) -> BTreeMap<(usize, usize), Option<RigidMotion>> {
    let distinct: Vec<(usize, usize)> = pairs.collect::<BTreeSet<_>>().into_iter().collect();
    let motions: Vec<Option<RigidMotion>> = distinct
        .par_iter()
        .map(|&(before, current)| {
            let before = &previous.clusters.get(before)?.points_xy_world;
            let current = &scan.clusters.get(current)?.points_xy_world;
            icp_rigid_motion(&thinned(before), &thinned(current), dt, &params.icp)
        })
        .collect();
    distinct.into_iter().zip(motions).collect()
}

/// Per cluster, the oracle flow of the actor with most points in it (ties to the lower id).
fn oracle_clusters(
    flows: &BTreeMap<u16, ClusterFlow>,
    scan: &ScanObservation,
) -> Vec<Option<ClusterFlow>> {
    let mut out: Vec<Option<(usize, ClusterFlow)>> = vec![None; scan.clusters.len()];
    for (actor, flow) in flows {
        let Some(seen) = scan.actors.get(actor) else {
            continue;
        };
        let slot = &mut out[seen.cluster];
        if slot.is_none_or(|(points, _)| seen.points > points) {
            *slot = Some((seen.points, *flow));
        }
    }
    out.into_iter().map(|s| s.map(|(_, f)| f)).collect()
}

/// Most points of a cluster that ICP aligns. Clusters of walls and parked cars reach 10,000
/// sliced points, and aligning those dominated the whole-scene evaluation's time; every
/// `k`-th point of such a cluster keeps its shape at a few centimetres' spacing. Targets stay
/// under the cap nearly always (a few hundred to about 1,500 points).
pub const MAX_ICP_POINTS: usize = 1500;

/// The cluster's points, or every `k`-th of them when there are more than [`MAX_ICP_POINTS`].
pub(crate) fn thinned(points: &[[f64; 2]]) -> std::borrow::Cow<'_, [[f64; 2]]> {
    if points.len() <= MAX_ICP_POINTS {
        return std::borrow::Cow::Borrowed(points);
    }
    let stride = points.len().div_ceil(MAX_ICP_POINTS);
    std::borrow::Cow::Owned(points.iter().step_by(stride).copied().collect())
}

#[cfg(test)]
mod thinning_tests {
    use super::*;

    #[test]
    fn a_large_cluster_is_thinned_to_at_most_the_cap_and_a_small_one_is_kept() {
        let large: Vec<[f64; 2]> = (0..10_000).map(|i| [i as f64 * 0.01, 0.0]).collect();
        let thin = thinned(&large);
        assert!(thin.len() <= MAX_ICP_POINTS && thin.len() > MAX_ICP_POINTS / 2);
        assert_eq!(thin[0], large[0]);
        let small = &large[..MAX_ICP_POINTS];
        assert_eq!(thinned(small).len(), MAX_ICP_POINTS);
    }
}
