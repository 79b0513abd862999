//! What the benchmark hands to every method, per scan: the clusters of height-sliced points in the
//! world frame (ground plane) and, for the oracle baselines and the read-out, which cluster holds
//! which actor.

use std::collections::BTreeMap;

use patchflow_learn::{ObjectEnd, RangeProfile};
use serde::{Deserialize, Serialize};

/// One cluster of height-sliced lidar points (thesis 2.2.1) in the world frame, projected to the ground plane.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClusterObservation {
    /// Cluster id within its scan (as produced by the clustering; not stable over time).
    pub id: usize,
    /// The cluster's points, world frame, x and y in metres.
    pub points_xy_world: Vec<[f64; 2]>,
    /// Centre of mass of `points_xy_world`, world frame, metres.
    pub centroid_xy: [f64; 2],
    /// The cluster's points of smallest and of largest bearing seen from the sensor, each with
    /// whether a nearer return hides what lies beyond it (`RangeProfile::ends`); `None` where the
    /// scan's range profile was not at hand (a cluster built from points alone).
    #[serde(skip)]
    pub ends: Option<[ObjectEnd; 2]>,
}

impl ClusterObservation {
    /// Every cluster of a scan's features, with its points in the world frame's ground plane and
    /// its ends read off `profile` (the scan's, `RangeProfile::of(features)`).
    pub(crate) fn all_of(
        features: &patchflow_learn::SweepFeatures,
        profile: &RangeProfile,
    ) -> Vec<Self> {
        features
            .clusters()
            .iter()
            .enumerate()
            .map(|(id, members)| {
                let points = features.positions_xy(members);
                Self {
                    ends: profile.ends(&points),
                    ..Self::from_points(id, points)
                }
            })
            .collect()
    }

    /// A cluster from its points; the centroid is their mean (the origin for an empty cluster).
    pub fn from_points(id: usize, points_xy_world: Vec<[f64; 2]>) -> Self {
        let centroid_xy = centroid_of(&points_xy_world).unwrap_or([0.0, 0.0]);
        Self {
            id,
            points_xy_world,
            centroid_xy,
            ends: None,
        }
    }
}

/// Everything a method sees of one scan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScanObservation {
    /// Scan number within the situation.
    pub scan: usize,
    /// Reference time of the sweep, seconds.
    pub stamp_secs: f64,
    /// Sensor position, world frame, metres.
    pub sensor_xy_world: [f64; 2],
    /// All clusters of this scan.
    pub clusters: Vec<ClusterObservation>,
    /// The oracle association (thesis 4.4): for every actor seen, the cluster holding most of its
    /// sliced points.
    pub actors: BTreeMap<u16, ActorCluster>,
    /// The actor the situation marks `target`, if any.
    pub target_actor: Option<u16>,
}

/// Where an actor's sliced points went in one scan's clustering.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ActorCluster {
    /// Index into the scan's clusters of the cluster holding most of the actor's points (ties to
    /// the lowest index).
    pub cluster: usize,
    /// The actor's sliced points in that cluster.
    pub points: usize,
}

impl ScanObservation {
    /// Index of the target's cluster this scan (the oracle association); `None` when the
    /// situation has no target or the target is not seen.
    pub fn target_cluster(&self) -> Option<usize> {
        self.actor_cluster(self.target_actor?)
    }

    /// Index of an actor's cluster this scan, if it is seen.
    pub fn actor_cluster(&self, actor: u16) -> Option<usize> {
        self.actors.get(&actor).map(|a| a.cluster)
    }

    /// The target's cluster this scan, if the target is seen and the index is valid.
    pub fn target(&self) -> Option<&ClusterObservation> {
        self.target_cluster().and_then(|i| self.clusters.get(i))
    }
}

/// Mean of a point set, `None` when it is empty.
pub fn centroid_of(points: &[[f64; 2]]) -> Option<[f64; 2]> {
    if points.is_empty() {
        return None;
    }
    let n = points.len() as f64;
    let (sx, sy) = points
        .iter()
        .fold((0.0, 0.0), |(sx, sy), p| (sx + p[0], sy + p[1]));
    Some([sx / n, sy / n])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cluster_built_from_points_has_their_mean_as_centroid() {
        let c = ClusterObservation::from_points(3, vec![[0.0, 0.0], [2.0, 0.0], [1.0, 3.0]]);
        assert!((c.centroid_xy[0] - 1.0).abs() < 1e-12);
        assert!((c.centroid_xy[1] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn an_out_of_range_target_index_gives_no_target() {
        let scan = ScanObservation {
            scan: 0,
            stamp_secs: 0.0,
            sensor_xy_world: [0.0, 0.0],
            clusters: vec![ClusterObservation::from_points(0, vec![[1.0, 1.0]])],
            actors: BTreeMap::from([(
                3,
                ActorCluster {
                    cluster: 4,
                    points: 1,
                },
            )]),
            target_actor: Some(3),
        };
        assert!(scan.target().is_none());
    }
}
