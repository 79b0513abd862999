//! Moving or static over time (issue 27): the classifier's per-scan probability carried along
//! each cluster's own track and smoothed in log-odds, so one scan's flicker neither sets a parked
//! car moving nor stops a passing one.
//!
//! Map-based moving-object segmentation fuses per-scan evidence recursively rather than deciding
//! each scan alone (4DMOS, Mersch et al. 2022, fuses overlapping predictions with a binary Bayes
//! filter; the occupancy grid's log-odds update, Thrun et al. 2005, 4.2). Our per-scan
//! probabilities are not independent (consecutive scans see the same half second of observed
//! change), so a plain Bayes sum would count the same evidence several times and drift away from
//! the threshold the classifier was calibrated with. The update is therefore a normalised
//! exponential average of the log-odds, l_k = γ l_{k−1} + (1 − γ) logit(p_k): a steady p keeps its
//! value (and the calibrated threshold its meaning), and a one-scan excursion moves l by only
//! (1 − γ) of its size.
//!
//! The tracks are the belief's own: each cluster of a scan is linked to the nearest cluster of the
//! scan before (predicted along its last displacement) within a gate, nearest pairs first; truth is
//! never read.

use crate::SweepFeatures;

/// The smoothing of the log-odds per scan (γ): the weight of the past.
pub const BELIEF_MEMORY: f64 = 0.8;
/// The largest distance (m) between a cluster's centroid and the prediction of a cluster of the
/// scan before for the two to be one track: 1.5 m of motion left unexplained in 0.1 s.
const GATE_M: f64 = 1.5;
/// The fastest a track's predicted motion may be (m/s).
const MAX_TRACK_SPEED_MPS: f64 = 25.0;
/// Log-odds are kept in ±this (p from 1e-4 to 1 − 1e-4).
const MAX_LOG_ODDS: f64 = 9.2;

/// One cluster's belief after a scan.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Belief {
    centroid_xy: [f64; 2],
    velocity_xy_mps: [f64; 2],
    log_odds: f64,
}

/// The tracks of the last scan and their smoothed log-odds of moving.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingBelief {
    memory: f64,
    previous: Vec<Option<Belief>>,
    previous_stamp_secs: Option<f64>,
}

impl Default for MovingBelief {
    fn default() -> Self {
        Self::new(BELIEF_MEMORY)
    }
}

fn logit(p: f64) -> f64 {
    let p = p.clamp(1e-12, 1.0 - 1e-12);
    (p / (1.0 - p)).ln().clamp(-MAX_LOG_ODDS, MAX_LOG_ODDS)
}

fn sigmoid(l: f64) -> f64 {
    1.0 / (1.0 + (-l).exp())
}

impl MovingBelief {
    /// A belief with memory γ in [0, 1) (0: every scan decides alone, as without the belief);
    /// γ is clamped to [0, 0.99], and a non-finite γ gives [`BELIEF_MEMORY`].
    pub fn new(memory: f64) -> Self {
        Self {
            memory: if memory.is_finite() {
                memory.clamp(0.0, 0.99)
            } else {
                BELIEF_MEMORY
            },
            previous: Vec::new(),
            previous_stamp_secs: None,
        }
    }

    /// The next scan (stamps increasing): per cluster its centroid (world, m) and the classifier's
    /// probability of moving (`None` for clusters it does not decide, which keep no belief).
    /// Returns the smoothed probability per cluster.
    pub fn update(
        &mut self,
        centroids_xy: &[[f64; 2]],
        probabilities: &[Option<f64>],
        stamp_secs: f64,
    ) -> Vec<Option<f64>> {
        let dt = self
            .previous_stamp_secs
            .map(|t| stamp_secs - t)
            .filter(|dt| dt.is_finite() && *dt > 0.0 && *dt < 1.0);
        let links = match dt {
            Some(dt) => self.links(centroids_xy, probabilities, dt),
            None => vec![None; centroids_xy.len()],
        };
        let mut now: Vec<Option<Belief>> = vec![None; centroids_xy.len()];
        for (c, p) in probabilities.iter().enumerate() {
            let (Some(p), Some(&xy)) = (p, centroids_xy.get(c)) else {
                continue;
            };
            let evidence = logit(*p);
            let belief = match (links.get(c).copied().flatten(), dt) {
                (Some(before), Some(dt)) => Belief {
                    centroid_xy: xy,
                    velocity_xy_mps: clamp_speed([
                        (xy[0] - before.centroid_xy[0]) / dt,
                        (xy[1] - before.centroid_xy[1]) / dt,
                    ]),
                    log_odds: self.memory * before.log_odds + (1.0 - self.memory) * evidence,
                },
                _ => Belief {
                    centroid_xy: xy,
                    velocity_xy_mps: [0.0, 0.0],
                    log_odds: evidence,
                },
            };
            now[c] = Some(belief);
        }
        self.previous = now;
        self.previous_stamp_secs = Some(stamp_secs);
        self.previous
            .iter()
            .map(|b| b.map(|b| sigmoid(b.log_odds)))
            .collect()
    }

    /// Per cluster of the scan: the belief of the scan before it continues, nearest pairs
    /// first, one to one, within the gate.
    fn links(
        &self,
        centroids_xy: &[[f64; 2]],
        probabilities: &[Option<f64>],
        dt: f64,
    ) -> Vec<Option<Belief>> {
        let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
        for (c, xy) in centroids_xy.iter().enumerate() {
            if probabilities.get(c).copied().flatten().is_none() {
                continue;
            }
            for (b, before) in self.previous.iter().enumerate() {
                let Some(before) = before else { continue };
                let predicted = [
                    before.centroid_xy[0] + before.velocity_xy_mps[0] * dt,
                    before.centroid_xy[1] + before.velocity_xy_mps[1] * dt,
                ];
                let d = (xy[0] - predicted[0]).hypot(xy[1] - predicted[1]);
                if d <= GATE_M {
                    pairs.push((d, c, b));
                }
            }
        }
        pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)).then(x.2.cmp(&y.2)));
        let mut links = vec![None; centroids_xy.len()];
        let mut taken = vec![false; self.previous.len()];
        for (_, c, b) in pairs {
            if links[c].is_none() && !taken[b] {
                links[c] = self.previous[b];
                taken[b] = true;
            }
        }
        links
    }

    /// [`Self::update`] with the centroids of a scan's features.
    pub fn update_features(
        &mut self,
        features: &SweepFeatures,
        probabilities: &[Option<f64>],
        stamp_secs: f64,
    ) -> Vec<Option<f64>> {
        // Only the decided clusters carry a belief, so only they need a centroid.
        let centroids: Vec<[f64; 2]> = (0..features.clusters().len())
            .map(|c| match probabilities.get(c) {
                Some(Some(_)) => features.cluster_shape(c).centroid_xy,
                _ => [0.0, 0.0],
            })
            .collect();
        self.update(&centroids, probabilities, stamp_secs)
    }
}

fn clamp_speed(v: [f64; 2]) -> [f64; 2] {
    let speed = v[0].hypot(v[1]);
    if !speed.is_finite() {
        return [0.0, 0.0];
    }
    if speed > MAX_TRACK_SPEED_MPS {
        let s = MAX_TRACK_SPEED_MPS / speed;
        [v[0] * s, v[1] * s]
    } else {
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_memory_every_scan_keeps_its_own_probability() {
        let mut belief = MovingBelief::new(0.0);
        belief.update(&[[0.0, 0.0]], &[Some(0.9)], 0.0);
        let p = belief.update(&[[0.1, 0.0]], &[Some(0.2)], 0.1);
        assert!((p[0].unwrap() - 0.2).abs() < 1e-9, "{p:?}");
    }

    #[test]
    fn a_steady_probability_keeps_its_value_along_a_moving_track() {
        // A car at 10 m/s: 1 m a scan, inside the gate once its displacement predicts it.
        let mut belief = MovingBelief::default();
        let mut p = Vec::new();
        for k in 0..10 {
            p = belief.update(&[[f64::from(k), 5.0]], &[Some(0.85)], 0.1 * f64::from(k));
        }
        assert!((p[0].unwrap() - 0.85).abs() < 1e-9, "{p:?}");
    }

    #[test]
    fn a_one_scan_excursion_moves_the_log_odds_by_one_minus_the_memory_of_its_size() {
        let mut belief = MovingBelief::new(0.7);
        for k in 0..5 {
            belief.update(&[[0.0, 5.0]], &[Some(0.1)], 0.1 * f64::from(k));
        }
        let p = belief.update(&[[0.05, 5.0]], &[Some(0.95)], 0.5)[0].unwrap();
        let expected = sigmoid(0.7 * logit(0.1) + 0.3 * logit(0.95));
        assert!((p - expected).abs() < 1e-9, "{p} against {expected}");
        assert!(
            p < 0.5,
            "one confident scan does not set a parked car moving: {p}"
        );
    }

    #[test]
    fn a_cluster_beyond_the_gate_starts_a_track_of_its_own() {
        let mut belief = MovingBelief::default();
        belief.update(&[[0.0, 0.0]], &[Some(0.05)], 0.0);
        let p = belief.update(&[[3.0, 0.0]], &[Some(0.9)], 0.1);
        assert!((p[0].unwrap() - 0.9).abs() < 1e-9, "{p:?}");
    }

    #[test]
    fn the_nearest_pair_is_linked_first_and_each_track_continues_once() {
        let mut belief = MovingBelief::new(0.5);
        belief.update(&[[0.0, 0.0], [1.0, 0.0]], &[Some(0.1), Some(0.9)], 0.0);
        // Both new clusters are within the gate of both old ones; (1.1, 0) is nearest to the
        // confident one, (0.2, 0) to the doubtful one.
        let p = belief.update(&[[0.2, 0.0], [1.1, 0.0]], &[Some(0.5), Some(0.5)], 0.1);
        let low = sigmoid(0.5 * logit(0.1));
        let high = sigmoid(0.5 * logit(0.9));
        assert!((p[0].unwrap() - low).abs() < 1e-9, "{p:?}");
        assert!((p[1].unwrap() - high).abs() < 1e-9, "{p:?}");
    }

    #[test]
    fn clusters_without_a_probability_keep_no_belief() {
        let mut belief = MovingBelief::default();
        belief.update(&[[0.0, 0.0]], &[Some(0.9)], 0.0);
        let p = belief.update(&[[0.0, 0.0]], &[None], 0.1);
        assert_eq!(p, vec![None]);
        // The track ended: the next decided cluster there starts afresh.
        let p = belief.update(&[[0.0, 0.0]], &[Some(0.2)], 0.2);
        assert!((p[0].unwrap() - 0.2).abs() < 1e-9, "{p:?}");
    }
}
