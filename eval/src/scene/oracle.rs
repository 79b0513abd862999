//! The oracle association of thesis 4.4, from the labels: which cluster of a scan holds most of
//! each actor's sliced points, and the target's truth at a scan. The thesis labelled its target by
//! hand; the baselines `KF` and `ICP` and every read-out of an actor's estimate use this.

use std::collections::BTreeMap;

use patchflow_dataset::Sweep;
use patchflow_learn::{FeaturedSweep, RangeProfile, SweepFeatures};

use crate::error::EvalError;
use crate::methods::observation::{ActorCluster, ClusterObservation, ScanObservation};
use crate::scene::truth_at_scan::TruthAtScan;

/// The clusters of a scan and, from the labels, which cluster holds most of each actor's points;
/// `profile` is the scan's range profile (`RangeProfile::of(features)`).
pub(crate) fn observe(
    scan: &FeaturedSweep,
    features: &SweepFeatures,
    profile: &RangeProfile,
) -> ScanObservation {
    let clusters = ClusterObservation::all_of(features, profile);
    let mut counts: BTreeMap<(u16, usize), usize> = BTreeMap::new();
    for (i, p) in features.points().iter().enumerate() {
        let actor = scan.sweep.labels[p.index].instance();
        if actor != 0 {
            *counts.entry((actor, features.cluster_of(i))).or_default() += 1;
        }
    }
    let mut actors: BTreeMap<u16, ActorCluster> = BTreeMap::new();
    for ((actor, cluster), points) in counts {
        // Clusters come in ascending order, so ties keep the lowest cluster id.
        if actors.get(&actor).is_none_or(|a| points > a.points) {
            actors.insert(actor, ActorCluster { cluster, points });
        }
    }
    ScanObservation {
        scan: scan.index,
        stamp_secs: scan.sweep.stamp_secs,
        sensor_xy_world: features.sensor_xy(),
        clusters,
        actors,
        target_actor: scan.sweep.target().map(|t| t.id),
    }
}

/// The cluster holding most of the target's sliced points (ties to the lowest cluster id).
pub(crate) fn target_cluster(features: &SweepFeatures, sweep: &Sweep) -> Option<usize> {
    let target = sweep.target()?.id;
    let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
    for (i, p) in features.points().iter().enumerate() {
        if sweep.labels[p.index].instance() == target {
            *counts.entry(features.cluster_of(i)).or_default() += 1;
        }
    }
    counts
        .into_iter()
        .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
        .map(|(c, _)| c)
}

/// The target's truth at a scan: velocity, range, and the points of its cluster.
pub(crate) fn target_at(
    scan: &FeaturedSweep,
    features: &SweepFeatures,
    profile: &RangeProfile,
    situation: &str,
) -> Result<TruthAtScan, EvalError> {
    let target = scan.sweep.target().ok_or_else(|| EvalError::BadResult {
        situation: situation.to_owned(),
        reason: format!("sweep {} has no object marked target", scan.index),
    })?;
    let [sx, sy] = features.sensor_xy();
    let members = target_cluster(features, &scan.sweep).map(|c| features.clusters().members(c));
    let hidden_ends = members.map(|m| profile.hidden_ends(&features.positions_xy(m)));
    Ok(TruthAtScan {
        range_m: Some((target.centre_m[0] - sx).hypot(target.centre_m[1] - sy)),
        target_points: Some(members.map_or(0, <[usize]>::len)),
        target_hidden_ends: hidden_ends,
        ..TruthAtScan::from_velocity(scan.index, [target.velocity_mps[0], target.velocity_mps[1]])
    })
}
