//! Predicting ahead (DGPOM paper, Section 3.2, Figure 10): a map is built from the scan at a start
//! time and the ones before it, then asked for the occupancy at later times with no newer scan,
//! and scored by ROC AUC against the exact occupancy at each later time. Averaged over several
//! start times, the AUC against the time since the last observation shows how long the map's
//! beliefs stay useful: the paper's curve falls sharply (moving regions revert to the prior) and
//! then saturates (the static structure stays confident). The paper approximated its truth by a
//! map of the scan at the query time; ours is exact. The scored area is the one the scanner
//! observes at the start time, held fixed.

use serde::{Deserialize, Serialize};

use crate::{
    MapMethod, MapMethodId, OccupancyError, OccupancySequence, QueryGrid, Result, ScanWindow,
    roc_auc,
};

/// Which predictions ahead are scored.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AheadParams {
    /// The last observed scan of each map (the start times averaged over).
    pub start_scans: Vec<usize>,
    /// Scans per map: the start scan and the `scans_per_map − 1` before it.
    pub scans_per_map: usize,
    /// Predictions at the start scan's time and the times of the next `horizon_scans` scans.
    pub horizon_scans: usize,
    /// Spacing of the lattice of query points, metres.
    pub query_spacing_m: f64,
}

impl Default for AheadParams {
    fn default() -> Self {
        Self {
            start_scans: vec![3, 4, 5, 6],
            scans_per_map: 4,
            horizon_scans: 8,
            query_spacing_m: 0.5,
        }
    }
}

/// The AUC at each time since the last observation, over the start times.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AheadScores {
    /// The method.
    pub method: MapMethodId,
    /// The start scans that were scored.
    pub start_scans: Vec<usize>,
    /// Per horizon (0, 1, … scans ahead): the time since the last observation, seconds (mean
    /// over the start times).
    pub seconds_ahead: Vec<f64>,
    /// Per horizon: the AUC of every start time that reaches it (start times in order).
    pub auc: Vec<Vec<f64>>,
}

impl AheadScores {
    /// Mean and standard deviation (population) of the AUC at each horizon.
    pub fn mean_std(&self) -> Vec<(f64, f64)> {
        self.auc
            .iter()
            .map(|a| {
                let n = a.len().max(1) as f64;
                let mean = a.iter().sum::<f64>() / n;
                let var = a.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
                (mean, var.sqrt())
            })
            .collect()
    }
}

/// Scores `method`'s predictions ahead on `sequence` (Figure 10).
pub fn evaluate_ahead(
    sequence: &OccupancySequence,
    method: &dyn MapMethod,
    params: &AheadParams,
) -> Result<AheadScores> {
    let n = sequence.scans.len();
    let starts: Vec<usize> = params
        .start_scans
        .iter()
        .copied()
        .filter(|&s| s + 1 >= params.scans_per_map && s < n)
        .collect();
    if starts.is_empty() || params.scans_per_map == 0 {
        return Err(OccupancyError::Unsupported {
            path: sequence.dir.clone(),
            reason: format!(
                "no start scan of {:?} has {} scans up to it in a sequence of {n}",
                params.start_scans, params.scans_per_map
            ),
        });
    }
    let mut scores = AheadScores {
        method: method.id(),
        start_scans: starts.clone(),
        seconds_ahead: vec![0.0; params.horizon_scans + 1],
        auc: vec![Vec::new(); params.horizon_scans + 1],
    };
    let mut counts = vec![0usize; params.horizon_scans + 1];
    for &start in &starts {
        let last = &sequence.scans[start];
        let window = ScanWindow {
            scans: &sequence.scans[start + 1 - params.scans_per_map..=start],
            query_secs: last.stamp_secs,
        };
        let grid = QueryGrid::observed_by(
            last,
            &sequence.sensor,
            params.query_spacing_m,
            &sequence.truth,
            sequence.scan_height_m(),
        );
        // The times of the next scans, none of which the map sees.
        let later: Vec<f64> = sequence.scans[start..n.min(start + params.horizon_scans + 1)]
            .iter()
            .map(|s| s.stamp_secs)
            .collect();
        let maps = method.map_ahead(&window, &grid.points_m, &later)?;
        for (h, (map, &t)) in maps.iter().zip(&later).enumerate() {
            let truth = sequence
                .truth
                .occupancy(&grid.points_m, sequence.scan_height_m(), t);
            if let Some(auc) = roc_auc(&map.probability, &truth) {
                scores.auc[h].push(auc);
                scores.seconds_ahead[h] += t - last.stamp_secs;
                counts[h] += 1;
            }
        }
    }
    for (s, c) in scores.seconds_ahead.iter_mut().zip(&counts) {
        *s /= (*c).max(1) as f64;
    }
    // Horizons no start time reached are dropped.
    while scores.auc.last().is_some_and(Vec::is_empty) {
        scores.auc.pop();
        scores.seconds_ahead.pop();
    }
    Ok(scores)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_std_are_taken_over_the_start_times_of_each_horizon() {
        let scores = AheadScores {
            method: MapMethodId::Dgpom,
            start_scans: Vec::new(),
            seconds_ahead: Vec::new(),
            auc: vec![vec![0.9, 0.7], vec![0.6]],
        };
        let ms = scores.mean_std();
        assert!((ms[0].0 - 0.8).abs() < 1e-12 && (ms[0].1 - 0.1).abs() < 1e-12);
        assert!((ms[1].0 - 0.6).abs() < 1e-12 && ms[1].1.abs() < 1e-12);
    }
}
