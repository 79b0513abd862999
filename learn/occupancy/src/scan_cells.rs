//! The occupancy map of one scan that the motion map starts from (DGPOM paper, Section 2.3: "the
//! procedure initially builds an occupancy map for each scan"): square cells, each beam traced
//! through every cell it crosses; a cell holding a return is occupied, a cell only crossed is
//! free, a cell no beam reached is unknown (absent). And the clusters of a set of cells: cells
//! closer than a gap are linked (single linkage on the lattice), found in sorted order so the
//! result is deterministic.

use std::collections::{BTreeMap, BTreeSet};

use patchflow_dataset::wrap_angle_rad;

use crate::PlanarScan;
use crate::occupancy_grid::{cell_of, traced_cells};

/// A lattice cell (column, row): the square [c·s, (c+1)·s) × [r·s, (r+1)·s).
pub(crate) type Cell = (i64, i64);

/// The cells one scan observed, occupied (true) or free (false).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ScanCells {
    /// Cell size, metres.
    pub cell_m: f64,
    /// Time of the scan, seconds.
    pub stamp_secs: f64,
    /// Every observed cell and whether it holds a return.
    pub cells: BTreeMap<Cell, bool>,
    /// Angle between neighbouring beams (the median over the scan), radians; 0 for a scan of
    /// fewer than two beams.
    pub beam_step_rad: f64,
    /// Length of the scan's longest beam, metres (a beam with no return runs to the range).
    pub reach_m: f64,
}

impl ScanCells {
    /// The observed cells of `scan` on a lattice of `cell_m`.
    pub fn from_scan(scan: &PlanarScan, cell_m: f64) -> Self {
        let mut cells = BTreeMap::new();
        for beam in &scan.beams {
            for cell in traced_cells(beam.start_m, beam.end_m, cell_m) {
                cells.entry(cell).or_insert(false);
            }
            if beam.hit {
                cells.insert(cell_of(beam.end_m, cell_m), true);
            }
        }
        Self {
            cell_m,
            stamp_secs: scan.stamp_secs,
            cells,
            beam_step_rad: median_beam_step_rad(scan),
            reach_m: scan
                .beams
                .iter()
                .map(|b| (b.end_m[0] - b.start_m[0]).hypot(b.end_m[1] - b.start_m[1]))
                .fold(0.0, f64::max),
        }
    }

    /// How far apart neighbouring beams are at the end of the scan's reach, metres.
    pub fn far_beam_spacing_m(&self) -> f64 {
        self.reach_m * self.beam_step_rad
    }

    /// Whether the scan observed `cell`, and if so whether it is occupied.
    pub fn state(&self, cell: Cell) -> Option<bool> {
        self.cells.get(&cell).copied()
    }

    /// The centre of `cell`, metres.
    pub fn centre_m(&self, cell: Cell) -> [f64; 2] {
        [
            (cell.0 as f64 + 0.5) * self.cell_m,
            (cell.1 as f64 + 0.5) * self.cell_m,
        ]
    }
}

/// The median angle between consecutive beams of `scan` (those that differ), radians.
fn median_beam_step_rad(scan: &PlanarScan) -> f64 {
    let azimuth = |b: &crate::Beam| (b.end_m[1] - b.start_m[1]).atan2(b.end_m[0] - b.start_m[0]);
    let mut steps: Vec<f64> = scan
        .beams
        .windows(2)
        // Wrapped into [−π, π): beams either side of ±180° are neighbours too.
        .map(|w| wrap_angle_rad(azimuth(&w[1]) - azimuth(&w[0])).abs())
        .filter(|d| *d > 1e-9)
        .collect();
    if steps.is_empty() {
        return 0.0;
    }
    steps.sort_by(f64::total_cmp);
    steps[steps.len() / 2]
}

/// The clusters of `cells`: two cells are linked when neither their columns nor their rows differ
/// by more than `gap` (single linkage), each cluster sorted, clusters in order of their first cell.
pub(crate) fn cell_clusters(cells: &BTreeSet<Cell>, gap: i64) -> Vec<Vec<Cell>> {
    let mut unvisited = cells.clone();
    let mut clusters = Vec::new();
    while let Some(&seed) = unvisited.iter().next() {
        unvisited.remove(&seed);
        let mut cluster = vec![seed];
        let mut next = 0;
        while next < cluster.len() {
            let (c, r) = cluster[next];
            next += 1;
            for dc in -gap..=gap {
                let column = (c + dc, r - gap)..=(c + dc, r + gap);
                let found: Vec<Cell> = unvisited.range(column).copied().collect();
                for cell in found {
                    unvisited.remove(&cell);
                    cluster.push(cell);
                }
            }
        }
        cluster.sort_unstable();
        clusters.push(cluster);
    }
    clusters
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Beam;

    #[test]
    fn a_scan_marks_its_return_occupied_the_cells_before_it_free_and_nothing_else() {
        let scan = PlanarScan {
            index: 0,
            stamp_secs: 2.0,
            sensor_m: [0.25, 0.25],
            yaw_rad: 0.0,
            beams: vec![Beam {
                start_m: [0.25, 0.25],
                end_m: [3.25, 0.25],
                hit: true,
            }],
        };
        let cells = ScanCells::from_scan(&scan, 0.5);
        assert_eq!(cells.state((6, 0)), Some(true));
        assert!((0..6).all(|c| cells.state((c, 0)) == Some(false)));
        assert_eq!(cells.state((7, 0)), None);
        assert_eq!(cells.state((3, 1)), None);
        assert_eq!(cells.centre_m((6, 0)), [3.25, 0.25]);
    }

    #[test]
    fn the_far_beam_spacing_is_the_reach_times_the_scans_angular_step() {
        // 91 beams 2° apart over 180° from (1, 2).
        let beams = (0..91)
            .map(|j| {
                let a = f64::from(2 * j).to_radians();
                Beam {
                    start_m: [1.0, 2.0],
                    end_m: [1.0 + 20.0 * a.cos(), 2.0 + 20.0 * a.sin()],
                    hit: false,
                }
            })
            .collect();
        let scan = PlanarScan {
            index: 0,
            stamp_secs: 0.0,
            sensor_m: [1.0, 2.0],
            yaw_rad: 0.0,
            beams,
        };
        let cells = ScanCells::from_scan(&scan, 0.5);
        let expected = 20.0 * 2f64.to_radians();
        assert!((cells.far_beam_spacing_m() - expected).abs() < 1e-9);
    }

    #[test]
    fn cells_within_the_gap_form_one_cluster_and_farther_ones_another() {
        let cells: BTreeSet<Cell> = [(0, 0), (1, 0), (3, 1), (10, 10), (11, 12), (20, 0)]
            .into_iter()
            .collect();
        let one = cell_clusters(&cells, 1);
        assert_eq!(
            one,
            vec![
                vec![(0, 0), (1, 0)],
                vec![(3, 1)],
                vec![(10, 10)],
                vec![(11, 12)],
                vec![(20, 0)]
            ]
        );
        let two = cell_clusters(&cells, 2);
        assert_eq!(
            two,
            vec![
                vec![(0, 0), (1, 0), (3, 1)],
                vec![(10, 10), (11, 12)],
                vec![(20, 0)]
            ]
        );
    }
}
