//! Scan-to-scan cluster association by nearest centroid with a gate, for the `ICP-AUTO` baseline
//! (thesis 3.2.1: "associating those cluster from subsequent scans whose center of mass is closest").
//!
//! Each previous cluster's centroid is first moved by its own centroid velocity (from its previous
//! association, when it had one) times Δt, so fast cars are not lost; then pairs (previous, current)
//! closer than `gate_m` are matched greedily, shortest distance first, one-to-one (ties broken by
//! index so the result is deterministic).

use crate::error::EvalError;
use crate::methods::observation::ScanObservation;

/// Knobs of the association.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentroidAssociationParams {
    /// Largest distance between a predicted previous centroid and a current centroid, metres.
    /// 2.5 m covers a 15 m/s car at 10 Hz plus a metre of partial-view centroid shift.
    pub gate_m: f64,
}

impl Default for CentroidAssociationParams {
    fn default() -> Self {
        Self { gate_m: 2.5 }
    }
}

/// Associates each scan's clusters with the previous scan's clusters.
#[derive(Debug, Clone, Default)]
pub struct CentroidAssociator {
    params: CentroidAssociationParams,
    previous: Option<PreviousScan>,
}

#[derive(Debug, Clone)]
struct PreviousScan {
    stamp_secs: f64,
    centroids_xy: Vec<[f64; 2]>,
    velocities_xy_mps: Vec<Option<[f64; 2]>>,
}

impl CentroidAssociator {
    /// An associator that has seen no scan yet.
    pub fn new(params: CentroidAssociationParams) -> Self {
        Self {
            params,
            previous: None,
        }
    }

    /// Processes one scan; returns, per cluster of `scan`, the index of its cluster in the previous scan.
    pub fn step(&mut self, scan: &ScanObservation) -> Result<Vec<Option<usize>>, EvalError> {
        let centroids: Vec<[f64; 2]> = scan.clusters.iter().map(|c| c.centroid_xy).collect();
        let mut links = vec![None; centroids.len()];
        let mut velocities = vec![None; centroids.len()];
        if let Some(previous) = &self.previous {
            let dt = scan.stamp_secs - previous.stamp_secs;
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(EvalError::BadObservation {
                    situation: "-".into(),
                    scan: scan.scan,
                    reason: format!(
                        "time stamp {} s does not follow {} s",
                        scan.stamp_secs, previous.stamp_secs
                    ),
                });
            }
            let predicted: Vec<[f64; 2]> = previous
                .centroids_xy
                .iter()
                .zip(&previous.velocities_xy_mps)
                .map(|(c, v)| v.map_or(*c, |v| [c[0] + v[0] * dt, c[1] + v[1] * dt]))
                .collect();
            links = nearest_centroid_matches(&predicted, &centroids, self.params.gate_m);
            for (ci, link) in links.iter().enumerate() {
                if let Some(pi) = link {
                    let (p, c) = (previous.centroids_xy[*pi], centroids[ci]);
                    velocities[ci] = Some([(c[0] - p[0]) / dt, (c[1] - p[1]) / dt]);
                }
            }
        }
        self.previous = Some(PreviousScan {
            stamp_secs: scan.stamp_secs,
            centroids_xy: centroids,
            velocities_xy_mps: velocities,
        });
        Ok(links)
    }
}

/// Greedy one-to-one matching of `current` to `previous` points within `gate_m`, shortest first.
/// Returns, per current point, the index of its previous point.
pub fn nearest_centroid_matches(
    previous: &[[f64; 2]],
    current: &[[f64; 2]],
    gate_m: f64,
) -> Vec<Option<usize>> {
    let mut pairs = Vec::new();
    // Pairs surely beyond the gate by their squared distance (a margin far above its rounding)
    // skip the slower `hypot` that sorts the rest: the same pairs.
    let beyond_sq = gate_m * gate_m * (1.0 + 1e-9);
    for (pi, p) in previous.iter().enumerate() {
        for (ci, c) in current.iter().enumerate() {
            let (dx, dy) = (p[0] - c[0], p[1] - c[1]);
            if dx * dx + dy * dy > beyond_sq {
                continue;
            }
            let d = dx.hypot(dy);
            if d <= gate_m {
                pairs.push((d, pi, ci));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut previous_taken = vec![false; previous.len()];
    let mut links = vec![None; current.len()];
    for (_, pi, ci) in pairs {
        if !previous_taken[pi] && links[ci].is_none() {
            previous_taken[pi] = true;
            links[ci] = Some(pi);
        }
    }
    links
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::observation::ClusterObservation;

    fn scan(k: usize, centroids: &[[f64; 2]]) -> ScanObservation {
        ScanObservation {
            scan: k,
            stamp_secs: k as f64 * 0.1,
            sensor_xy_world: [0.0, 0.0],
            clusters: centroids
                .iter()
                .enumerate()
                .map(|(i, c)| ClusterObservation::from_points(i, vec![*c]))
                .collect(),
            actors: Default::default(),
            target_actor: None,
        }
    }

    #[test]
    fn matching_is_one_to_one_and_nearest_first() {
        let links =
            nearest_centroid_matches(&[[0.0, 0.0], [1.0, 0.0]], &[[0.9, 0.0], [0.2, 0.0]], 2.0);
        assert_eq!(links, [Some(1), Some(0)]);
    }

    #[test]
    fn a_cluster_beyond_the_gate_stays_unmatched() {
        let links = nearest_centroid_matches(&[[0.0, 0.0]], &[[5.0, 0.0]], 2.5);
        assert_eq!(links, [None]);
    }

    #[test]
    fn the_velocity_prediction_keeps_a_fast_car_linked_past_a_slow_neighbour() {
        // A fast car (15 m/s, 1.5 m per scan) passes a parked car whose centroid jumps 0.8 m as
        // its visible side changes; without prediction the fast car's new centroid (0.57 m from
        // the parked car's old one) would steal the parked car's link.
        let mut assoc = CentroidAssociator::new(CentroidAssociationParams::default());
        assoc.step(&scan(0, &[[0.0, 0.0], [2.6, 0.4]])).unwrap();
        assoc.step(&scan(1, &[[1.5, 0.0], [2.6, 0.4]])).unwrap();
        let links = assoc.step(&scan(2, &[[3.0, 0.0], [2.6, 1.2]])).unwrap();
        assert_eq!(links, [Some(0), Some(1)]);
    }
}
