//! A cluster's points grouped by map cell: the whole-scan step predicts once per occupied cell.
//!
//! Patches are sampled from maps of 0.1 m cells (thesis 4.3), so points closer than a cell carry
//! the same patch up to sub-cell interpolation; a lidar puts up to a hundred sliced points into one
//! cell of a car a few metres away, and predicting each would cost a hundred GP evaluations for one
//! cell's worth of information (and let the nearest surfaces outvote the rest when merging). One
//! sample per cell, at the mean of its points, keeps the information and makes the cost follow the
//! area the clusters cover rather than the lidar's density.

use std::collections::BTreeMap;

use crate::SlicedPoint;
use crate::features::grid::GridWindow;

/// Cell samples of one cluster.
#[derive(Debug, Clone, PartialEq)]
pub struct CellSamples {
    /// Mean world x, y of the points of each occupied cell, in cell order (row-major).
    pub positions: Vec<[f64; 2]>,
    /// For each member, in the order given, the index of its sample in `positions`.
    pub sample_of_member: Vec<usize>,
}

impl CellSamples {
    /// Groups `members` (indices of `points`) by their cell of `window`; a point outside the
    /// window gets a sample of its own.
    pub fn group(points: &[SlicedPoint], members: &[usize], window: &GridWindow) -> Self {
        // Cell key → (sample, sum x, sum y, count); points outside the window key past the cells.
        let mut cells: BTreeMap<usize, (usize, f64, f64, usize)> = BTreeMap::new();
        let mut key_of_member = Vec::with_capacity(members.len());
        for (k, &i) in members.iter().enumerate() {
            let p = points[i];
            let key = window
                .cell_of(p.x_m, p.y_m)
                .map_or(window.len() + k, |(c, r)| window.index(c, r));
            let entry = cells.entry(key).or_insert((0, 0.0, 0.0, 0));
            entry.1 += p.x_m;
            entry.2 += p.y_m;
            entry.3 += 1;
            key_of_member.push(key);
        }
        let mut positions = Vec::with_capacity(cells.len());
        for (sample, entry) in cells.values_mut().enumerate() {
            entry.0 = sample;
            let n = entry.3 as f64;
            positions.push([entry.1 / n, entry.2 / n]);
        }
        let sample_of_member = key_of_member.iter().map(|key| cells[key].0).collect();
        Self {
            positions,
            sample_of_member,
        }
    }

    /// Number of samples (occupied cells).
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// True if the cluster had no points.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(x_m: f64, y_m: f64, index: usize) -> SlicedPoint {
        SlicedPoint { x_m, y_m, index }
    }

    #[test]
    fn points_of_one_cell_share_a_sample_at_their_mean() {
        let window = GridWindow::centred([0.0, 0.0], 5.0, 0.1);
        let points = [
            point(1.01, 2.01, 0),
            point(3.0, -1.0, 1),
            point(1.03, 2.07, 2),
            point(1.05, 2.03, 3),
        ];
        let samples = CellSamples::group(&points, &[0, 1, 2, 3], &window);
        assert_eq!(samples.len(), 2);
        let s = samples.sample_of_member[0];
        assert_eq!(samples.sample_of_member, {
            let other = 1 - s;
            vec![s, other, s, s]
        });
        let [x, y] = samples.positions[s];
        assert!((x - 1.03).abs() < 1e-12 && (y - 2.036_666_666_666_667).abs() < 1e-12);
    }

    #[test]
    fn a_point_outside_the_window_is_its_own_sample() {
        let window = GridWindow::centred([0.0, 0.0], 1.0, 0.1);
        let points = [
            point(50.0, 0.0, 0),
            point(50.0, 0.0, 1),
            point(0.05, 0.05, 2),
        ];
        let samples = CellSamples::group(&points, &[0, 1, 2], &window);
        assert_eq!(samples.len(), 3);
        assert_eq!(samples.positions[samples.sample_of_member[1]], [50.0, 0.0]);
    }
}
