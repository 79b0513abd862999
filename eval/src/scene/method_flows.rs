//! How each method moves a scan's points: the GP readouts per cluster (ALL, BEST, the `+MOS`
//! decision) and per point, the baselines' and the learned trackers' cluster flows on the object
//! hypotheses, and zero flow. The scene flow and the moving-object IoU score these.

use std::collections::BTreeMap;

use patchflow_learn::{ClusterEstimate, ClusterMotion, ScanMotion, SweepFeatures};

use crate::methods::baselines::baseline_step::{BaselineScan, ClusterFlow};
use crate::methods::estimate::{MotionEstimate, to_estimate};
use crate::methods::method::Method;
use crate::scene::scan_scoring::MethodFlow;

/// Which clusters of the scan are object hypotheses.
pub(crate) fn hypothesis_flags(features: &SweepFeatures) -> Vec<bool> {
    let mut flags = vec![false; features.clusters().len()];
    for c in features.object_hypotheses() {
        flags[c] = true;
    }
    flags
}

/// How each method moves the scan's points. `decisions` (with a moving classifier): per cluster,
/// moving or static for the object hypotheses.
pub(crate) fn method_flows(
    motions: &[(patchflow_learn::GpKind, ScanMotion)],
    baseline: &BaselineScan,
    learned: &BTreeMap<Method, Vec<Option<ClusterFlow>>>,
    hypotheses: &[bool],
    decisions: Option<&[Option<bool>]>,
) -> BTreeMap<Method, MethodFlow> {
    let mut flows = BTreeMap::new();
    for (kind, motion) in motions {
        let [all, best, point] = Method::of_estimator(*kind);
        let merged = |pick: fn(&ClusterEstimate) -> Option<ClusterMotion>| {
            let clusters = motion.clusters.iter();
            let flows = clusters.map(|e| e.as_ref().and_then(pick));
            MethodFlow::Clusters(
                flows
                    .map(|m| m.map(|m| ClusterFlow::Uniform(to_estimate(m))))
                    .collect(),
            )
        };
        flows.insert(all, merged(|e| e.all));
        flows.insert(best, merged(|e| e.best));
        if let Some(decisions) = decisions {
            let decided = motion.clusters.iter().zip(decisions).map(|(e, moving)| {
                let all = e.as_ref().and_then(|e| e.all).map(to_estimate);
                match moving {
                    Some(false) => {
                        Some(MotionEstimate::at_rest(all.map_or(0.0, |e| e.heading_rad)))
                    }
                    _ => all,
                }
                .map(ClusterFlow::Uniform)
            });
            flows.insert(
                Method::gp_decided(*kind),
                MethodFlow::Clusters(decided.collect()),
            );
        }
        let velocities = motion.points.iter().map(|p| p.map(|p| p.velocity_xy_mps()));
        flows.insert(point, MethodFlow::Points(velocities.collect()));
    }
    for (&method, clusters) in baseline.clusters.iter().chain(learned) {
        let kept = clusters
            .iter()
            .zip(hypotheses)
            .map(|(flow, &hypothesis)| flow.filter(|_| hypothesis))
            .collect();
        flows.insert(method, MethodFlow::Clusters(kept));
    }
    flows.insert(Method::ZeroFlow, MethodFlow::Zero);
    flows
}
