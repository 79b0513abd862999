//! Change that both sweeps saw, over a longer baseline than the thesis' difference map (issue 27):
//! m_t − m_{t−N} with N = [`CHANGE_BASELINE_SCANS`] sweeps, kept only in the cells that the
//! current sweep and the sweep N before it both observed (some hit or miss fell there).
//!
//! Why both: over 0.1 s a car at walking pace moves less than a map cell, so the one-sweep
//! difference map barely sees it, while over 0.5 s it moves half a metre to several metres. And
//! why only observed cells: most of what changes in a reflection map as the ego drives is not
//! motion but visibility, a parked car's far side or a wall coming out of a shadow (prior →
//! occupied), or sinking into one (occupied → prior). A cell observed free before and occupied
//! now, or the reverse, is what moves; this is the visibility test of map-based moving-object
//! detectors (free space then, a return now). A cell is observed where its value does not depend
//! on the map prior (the prior fills only the unobserved cells), so the maps at two priors from one
//! beam trace tell the two apart.

use crate::features::{GridMap, MapPair};
use crate::{FeatureValidParams, HeightSlice, ScanStream};

/// Sweeps between the two maps of the long baseline: 0.5 s at 10 Hz.
pub const CHANGE_BASELINE_SCANS: usize = 5;

/// The second prior whose maps tell observed cells from unobserved ones.
fn other_prior(prior: f64) -> f64 {
    if (prior - 0.01).abs() < 1e-9 {
        0.5
    } else {
        0.01
    }
}

/// The observed change between a past sweep and the current one, on the current map window.
#[derive(Debug, Clone, PartialEq)]
pub struct ChangeEvidence {
    /// Reflection and difference maps at the features' prior.
    maps: MapPair,
    /// The same at the other prior.
    other: MapPair,
}

impl ChangeEvidence {
    /// Traces both slices' beams once on the current sweep's map window and keeps both priors'
    /// maps. `past` is the slice [`CHANGE_BASELINE_SCANS`] sweeps back (or the oldest there is).
    pub fn build(past: &HeightSlice, current: &HeightSlice, params: &FeatureValidParams) -> Self {
        let p = params.params();
        let window = p.map_window(current.sensor_xy);
        let priors = [p.prior, other_prior(p.prior)];
        let mut pairs =
            MapPair::build_for_priors(past, current, window, p.spread, &priors).into_iter();
        let filled = |prior: f64| MapPair {
            reflection: GridMap::filled(window, prior),
            difference: GridMap::filled(window, 0.0),
        };
        let maps = pairs.next().unwrap_or_else(|| filled(priors[0]));
        let other = pairs.next().unwrap_or_else(|| filled(priors[1]));
        Self { maps, other }
    }

    /// The evidence of the scan a stream has just computed features for: its slice and the
    /// one [`CHANGE_BASELINE_SCANS`] sweeps before (or the sequence's first), with the stream's
    /// first parameter set. `None` before the stream's first scan.
    pub fn of_stream(stream: &ScanStream) -> Option<Self> {
        let past = stream.slice_back(CHANGE_BASELINE_SCANS)?;
        let current = stream.slice_back(0)?;
        Some(Self::build(past, current, stream.first_params()?))
    }

    /// m_t − m_{t−N} at world (x, y) where both sweeps observed the cell, else 0 (also outside
    /// the window).
    pub fn observed_change(&self, x_m: f64, y_m: f64) -> f64 {
        let now = self.maps.reflection.at(x_m, y_m);
        let now_other = self.other.reflection.at(x_m, y_m);
        let change = self.maps.difference.at(x_m, y_m);
        let change_other = self.other.difference.at(x_m, y_m);
        let seen_now = (now - now_other).abs() < 1e-9;
        let seen_then = ((now - change) - (now_other - change_other)).abs() < 1e-9;
        if seen_now && seen_then { change } else { 0.0 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FeatureParams;
    use crate::synthetic::{SceneBox, SyntheticLidar, SyntheticScene};

    fn evidence(scene: &SyntheticScene, seconds: f64, sensor_then: [f64; 2]) -> ChangeEvidence {
        let lidar = SyntheticLidar::with_resolution(64, 1800);
        let params = FeatureParams::default().check().unwrap();
        let past = HeightSlice::cut(&scene.scan(&lidar, sensor_then, 0.0, 0), &params).unwrap();
        let now = scene.advanced(seconds).scan(&lidar, [0.0, 0.0], 0.0, 5);
        let now = HeightSlice::cut(&now, &params).unwrap();
        ChangeEvidence::build(&past, &now, &params)
    }

    /// Cells of the 6 × 6 m square at `lo` with an observed change above 0.3 in magnitude.
    fn changed_cells(e: &ChangeEvidence, lo: [f64; 2]) -> usize {
        let mut n = 0;
        for i in 0..60 {
            for j in 0..60 {
                let (x, y) = (lo[0] + 0.1 * f64::from(i), lo[1] + 0.1 * f64::from(j));
                n += usize::from(e.observed_change(x, y).abs() > 0.3);
            }
        }
        n
    }

    #[test]
    fn a_car_that_moved_into_seen_free_space_shows_an_observed_gain() {
        // Crossing at 5 m/s, 2.5 m in 0.5 s: its new front was free space the past sweep saw.
        let scene = SyntheticScene {
            boxes: vec![SceneBox::car(1, [0.0, 12.0], 0.0, 5.0)],
        };
        let e = evidence(&scene, 0.5, [0.0, 0.0]);
        let gain = e.observed_change(4.2, 11.1);
        assert!(gain > 0.3, "observed gain at the new front {gain}");
        let changed = changed_cells(&e, [-3.0, 9.0]);
        assert!(changed >= 40, "{changed} changed cells");
    }

    #[test]
    fn a_parked_car_seen_from_a_new_place_shows_little_observed_change() {
        // The ego moved 3 m: the car's faces that come into view were in its shadow before, so
        // only cells at its corners, where the map's spread reached from the faces seen before,
        // count as observed change: 13 here against 68 for the crossing car above.
        let scene = SyntheticScene {
            boxes: vec![SceneBox::car(1, [6.0, 8.0], 0.3, 0.0)],
        };
        let e = evidence(&scene, 0.5, [-3.0, 0.0]);
        let changed = changed_cells(&e, [3.0, 5.0]);
        assert!(changed <= 20, "{changed} changed cells");
    }
}
