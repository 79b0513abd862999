//! The occupancy-grid baseline (DGPOM paper, Table 1's comparison; Elfes): square cells, each
//! holding hits / (hits + misses) of the beams of the window's scans, 0.5 where no beam passed.
//! A beam is traced from its start (the sensor, or its entry into a 3-D lidar's height slice)
//! through every cell it crosses (Amanatides-Woo): cells before its end count a miss, the end
//! cell a hit if the beam returned there, a miss if it saw nothing to maximum range.

use std::collections::HashMap;

use crate::{MapMethod, MapMethodId, MapOutput, OccupancyError, PlanarScan, Result, ScanWindow};

/// The occupancy grid as a map method.
#[derive(Debug, Clone, PartialEq)]
pub struct OccupancyGridMethod {
    /// Cell size, metres.
    pub cell_m: f64,
}

impl Default for OccupancyGridMethod {
    fn default() -> Self {
        Self { cell_m: 0.5 }
    }
}

impl MapMethod for OccupancyGridMethod {
    fn id(&self) -> MapMethodId {
        MapMethodId::Grid
    }

    fn map(&self, window: &ScanWindow<'_>, points_m: &[[f64; 2]]) -> Result<MapOutput> {
        if !(self.cell_m.is_finite() && self.cell_m > 0.0) {
            return Err(OccupancyError::BadParameter {
                name: "OccupancyGridMethod.cell_m",
                reason: format!("must be positive, got {}", self.cell_m),
            });
        }
        let grid = CountGrid::from_scans(window.scans, self.cell_m);
        let beams = window.scans.iter().map(|s| s.beams.len()).sum();
        Ok(MapOutput {
            probability: points_m.iter().map(|&p| grid.probability(p)).collect(),
            variance: None,
            training_points: beams,
            drawn_points: beams,
            summary: format!(
                "{} m cells, {} cells observed",
                self.cell_m,
                grid.counts.len()
            ),
            solver: None,
            temporal_lengthscales: Vec::new(),
        })
    }
}

/// Hits and misses per cell.
#[derive(Debug, Clone, Default)]
struct CountGrid {
    cell_m: f64,
    counts: HashMap<(i64, i64), (u32, u32)>,
}

impl CountGrid {
    fn from_scans(scans: &[PlanarScan], cell_m: f64) -> Self {
        let mut grid = Self {
            cell_m,
            counts: HashMap::new(),
        };
        for scan in scans {
            for beam in &scan.beams {
                let cells = traced_cells(beam.start_m, beam.end_m, cell_m);
                let last = cells.len().saturating_sub(1);
                for (k, cell) in cells.into_iter().enumerate() {
                    let entry = grid.counts.entry(cell).or_default();
                    if k == last && beam.hit {
                        entry.0 += 1;
                    } else {
                        entry.1 += 1;
                    }
                }
            }
        }
        grid
    }

    /// hits / (hits + misses) of the cell holding `p`, 0.5 if no beam passed it.
    fn probability(&self, p: [f64; 2]) -> f64 {
        match self.counts.get(&cell_of(p, self.cell_m)) {
            Some(&(hits, misses)) if hits + misses > 0 => {
                f64::from(hits) / f64::from(hits + misses)
            }
            _ => 0.5,
        }
    }
}

/// The cell holding `p`.
pub(crate) fn cell_of(p: [f64; 2], cell_m: f64) -> (i64, i64) {
    (
        (p[0] / cell_m).floor() as i64,
        (p[1] / cell_m).floor() as i64,
    )
}

/// Every cell the segment from `a` to `b` crosses, in order, `b`'s cell last (Amanatides & Woo).
pub(crate) fn traced_cells(a: [f64; 2], b: [f64; 2], cell_m: f64) -> Vec<(i64, i64)> {
    let (mut cell, end) = (cell_of(a, cell_m), cell_of(b, cell_m));
    let d = [b[0] - a[0], b[1] - a[1]];
    let step = [d[0].signum() as i64, d[1].signum() as i64];
    // Distance (in units of the segment) to the first boundary on each axis, and between them.
    let boundary = |axis: usize, c: i64| -> f64 {
        if d[axis] == 0.0 {
            return f64::INFINITY;
        }
        let next_cell = if d[axis] > 0.0 { c + 1 } else { c };
        let next = next_cell as f64 * cell_m;
        (next - [a[0], a[1]][axis]) / d[axis]
    };
    let mut t_max = [boundary(0, cell.0), boundary(1, cell.1)];
    let t_delta = [cell_m / d[0].abs(), cell_m / d[1].abs()];
    let limit = (end.0 - cell.0).unsigned_abs() + (end.1 - cell.1).unsigned_abs();
    let mut out = Vec::with_capacity(limit as usize + 1);
    out.push(cell);
    for _ in 0..limit {
        if cell == end {
            break;
        }
        if t_max[0] < t_max[1] {
            cell.0 += step[0];
            t_max[0] += t_delta[0];
        } else {
            cell.1 += step[1];
            t_max[1] += t_delta[1];
        }
        out.push(cell);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Beam;

    #[test]
    fn a_traced_beam_crosses_every_cell_between_its_ends_once() {
        let cells = traced_cells([0.25, 0.25], [2.25, 1.25], 0.5);
        assert_eq!(cells.first(), Some(&(0, 0)));
        assert_eq!(cells.last(), Some(&(4, 2)));
        // 4 steps in x and 2 in y.
        assert_eq!(cells.len(), 7);
        assert!(
            cells
                .windows(2)
                .all(|w| (w[1].0 - w[0].0).abs() + (w[1].1 - w[0].1).abs() == 1)
        );
    }

    #[test]
    fn cells_before_a_return_are_free_its_cell_occupied_and_unseen_cells_unknown() {
        let scan = PlanarScan {
            index: 0,
            stamp_secs: 0.0,
            sensor_m: [0.25, 0.25],
            yaw_rad: 0.0,
            beams: vec![
                Beam {
                    start_m: [0.25, 0.25],
                    end_m: [5.25, 0.25],
                    hit: true,
                },
                Beam {
                    start_m: [0.25, 0.25],
                    end_m: [0.25, 5.25],
                    hit: false,
                },
            ],
        };
        let window = ScanWindow {
            scans: std::slice::from_ref(&scan),
            query_secs: 0.0,
        };
        let points = [[2.0, 0.3], [5.2, 0.3], [0.3, 5.2], [3.0, 3.0]];
        let out = OccupancyGridMethod::default()
            .map(&window, &points)
            .unwrap();
        assert_eq!(out.probability, [0.0, 1.0, 0.0, 0.5]);
        assert!(out.variance.is_none());
    }
}
