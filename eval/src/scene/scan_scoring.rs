//! Scores one scan of a whole scene: how each method moves every scored point (scene flow), and
//! what it estimates for every actor.
//!
//! A method moves the points of the clusters it estimates; every other point stands still. Only
//! object hypotheses are estimated (clusters no longer than a road user, `ClusterShape`): the
//! same segmentation for every method, so that the methods differ only in their motion.

use std::collections::BTreeMap;

use patchflow_dataset::Sweep;
use rayon::prelude::*;

use crate::methods::baselines::baseline_step::{BaselineScan, ClusterFlow};
use crate::methods::estimate::MotionEstimate;
use crate::methods::method::Method;
use crate::methods::observation::ScanObservation;
use crate::scene::objects::{MIN_OBJECT_POINTS, ObjectScan};
use crate::scene::scene_flow::{SceneFlowTally, end_point_error};
use crate::scene::scene_point::ScenePoints;
use crate::scene::truth_at_scan::TruthAtScan;

/// How one method moves the scored points of one scan.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum MethodFlow {
    /// Per cluster of the scan (`None` outside the hypotheses and where the method has nothing).
    Clusters(Vec<Option<ClusterFlow>>),
    /// Per scored point, a world-frame velocity.
    Points(Vec<Option<[f64; 2]>>),
    /// Nothing moves.
    Zero,
}

impl MethodFlow {
    /// Velocity of scored point `i` at `xy`, in cluster `cluster`, m/s.
    fn velocity(&self, i: usize, cluster: usize, xy: [f64; 2]) -> [f64; 2] {
        let velocity = match self {
            Self::Clusters(flows) => flows[cluster].map(|f| f.velocity_at(xy)),
            Self::Points(velocities) => velocities[i],
            Self::Zero => None,
        };
        velocity.unwrap_or([0.0, 0.0])
    }

    /// The method's estimate for cluster `c`: its flow's, none for per-point flows, zero for ZERO-FLOW.
    fn cluster_estimate(&self, c: usize) -> Option<MotionEstimate> {
        match self {
            Self::Clusters(flows) => flows[c].map(|f| f.estimate()),
            Self::Points(_) => None,
            Self::Zero => Some(MotionEstimate::from_velocity([0.0, 0.0])),
        }
    }
}

/// Mean end-point error per method and actor on one scan: (sum, points).
type ActorErrors = BTreeMap<Method, BTreeMap<u16, (f64, usize)>>;

/// Adds every scored point of a scan to each method's tally; returns the errors per actor. The
/// methods are scored side by side, each over the points in order, so each tally and sum is the
/// one a loop over the methods would give.
pub(crate) fn score_points(
    points: &ScenePoints,
    cluster_of: &[usize],
    flows: &BTreeMap<Method, MethodFlow>,
    tallies: &mut BTreeMap<Method, SceneFlowTally>,
) -> ActorErrors {
    for &method in flows.keys() {
        tallies.entry(method).or_default();
    }
    let jobs: Vec<(Method, &MethodFlow, &mut SceneFlowTally)> = tallies
        .iter_mut()
        .filter_map(|(method, tally)| Some((*method, flows.get(method)?, tally)))
        .collect();
    jobs.into_par_iter()
        .map(|(method, flow, tally)| {
            let mut per_actor = BTreeMap::new();
            for (i, &cluster) in cluster_of.iter().enumerate().take(points.len()) {
                let velocity = flow.velocity(i, cluster, points.xy[i]);
                let predicted = points.displacement_of(velocity);
                tally.add(
                    predicted,
                    points.truth_m[i],
                    points.class[i],
                    points.dt_secs,
                );
                if points.actor[i] != 0 {
                    let entry = per_actor.entry(points.actor[i]).or_insert((0.0, 0));
                    entry.0 += end_point_error(predicted, points.truth_m[i]);
                    entry.1 += 1;
                }
            }
            (method, per_actor)
        })
        .collect()
}

/// Every actor of the sweep with enough scored points, with each method's estimate for it.
pub(crate) fn object_scans(
    sweep: &Sweep,
    points: &ScenePoints,
    observation: &ScanObservation,
    flows: &BTreeMap<Method, MethodFlow>,
    baselines: &BaselineScan,
    errors: &ActorErrors,
) -> Vec<ObjectScan> {
    let [sx, sy] = observation.sensor_xy_world;
    let mut counts: BTreeMap<u16, usize> = BTreeMap::new();
    for &actor in &points.actor {
        *counts.entry(actor).or_default() += 1;
    }
    let mut objects = Vec::new();
    for actor in &sweep.objects {
        let points = counts.get(&actor.id).copied().unwrap_or(0);
        let Some(seen) = observation.actors.get(&actor.id) else {
            continue;
        };
        if points < MIN_OBJECT_POINTS {
            continue;
        }
        let truth = TruthAtScan {
            range_m: Some((actor.centre_m[0] - sx).hypot(actor.centre_m[1] - sy)),
            target_points: Some(points),
            ..TruthAtScan::from_velocity(
                observation.scan,
                [actor.velocity_mps[0], actor.velocity_mps[1]],
            )
        };
        let estimates = flows
            .iter()
            .filter(|(m, _)| m.is_per_cluster() || !m.has_heading())
            .map(|(&method, flow)| {
                let estimate = if method.is_oracle() {
                    baselines.actor_estimate(method, actor.id, observation)
                } else {
                    flow.cluster_estimate(seen.cluster)
                };
                (method, estimate)
            })
            .collect();
        let point_epe_m = errors
            .iter()
            .filter_map(|(&method, per_actor)| {
                let (sum, n) = per_actor.get(&actor.id)?;
                Some((method, sum / *n as f64))
            })
            .collect();
        objects.push(ObjectScan {
            scan: observation.scan,
            actor: actor.id,
            class: actor.class,
            truth,
            estimates,
            point_epe_m,
        });
    }
    objects
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::scene_point::FlowClass;

    fn two_points() -> ScenePoints {
        ScenePoints {
            dt_secs: 0.1,
            xy: vec![[10.0, 0.0], [20.0, 5.0]],
            truth_m: vec![[0.5, 0.0, 0.0], [0.0, 0.0, 0.0]],
            class: vec![FlowClass::Car, FlowClass::Background],
            actor: vec![4, 0],
        }
    }

    #[test]
    fn points_outside_the_estimated_clusters_stand_still() {
        let moving = MotionEstimate::from_velocity([5.0, 0.0]);
        let flows = BTreeMap::from([
            (
                Method::KfAuto,
                MethodFlow::Clusters(vec![Some(ClusterFlow::Uniform(moving)), None]),
            ),
            (Method::ZeroFlow, MethodFlow::Zero),
        ]);
        let mut tallies = BTreeMap::new();
        let errors = score_points(&two_points(), &[0, 1], &flows, &mut tallies);
        let kf = tallies[&Method::KfAuto].metrics();
        assert_eq!(kf.epe3d_m, Some(0.0));
        let zero = tallies[&Method::ZeroFlow].metrics();
        assert!((zero.epe3d_m.unwrap() - 0.25).abs() < 1e-12);
        // Actor 4's one point: exact for KF-AUTO, 0.5 m off for zero flow; the static world has no actor.
        assert_eq!(errors[&Method::KfAuto][&4], (0.0, 1));
        assert_eq!(errors[&Method::ZeroFlow][&4], (0.5, 1));
        assert!(!errors[&Method::ZeroFlow].contains_key(&0));
    }
}
