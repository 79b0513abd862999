//! Where a training run saw the occupancy change, and so where a Same cell is no evidence of a
//! still object (DGPOM paper, Section 2.3, with one addition). The paper takes Same clusters with
//! no Diff cluster next to them as stationary. Between two scans that is all it can know, but a
//! training run holds many pairs: a static structure never changes while it is observed (the
//! one-cell tolerance of the Diff map absorbs range noise), so a cell that was a Diff cell at some
//! pair of the run is a place where objects come and go. Seen Same at another pair, it is a moving
//! surface whose motion the scanner cannot see: a car's side face sliding along itself, hit by
//! the same beam in the same cell in both scans (at grazing incidence a face holds one return
//! every few metres, so its ends, where the motion would show, fall between the beams), or the
//! next car of a queue in the place of the one before. Such cells are dropped from the stationary
//! clusters; the rest of a stationary cluster stays. Static surfaces keep all their cells however
//! sparsely they are sampled, which a rule on the cluster's size (one cell at 80 m is a building
//! too) cannot do.

use std::collections::BTreeSet;

use crate::motion_clusters::changed_and_same;
use crate::occupancy_grid::cell_of;
use crate::scan_cells::{Cell, ScanCells};
use crate::{ClusterKind, MotionCluster};

/// The cells that were Diff cells (arrived or vacated, before any clustering) at some pair of
/// consecutive scans of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct ChangedCells {
    cells: BTreeSet<Cell>,
    cell_m: f64,
}

impl ChangedCells {
    /// The changed cells of every pair of consecutive maps of `maps` (all on one lattice).
    pub fn of_run(maps: &[ScanCells]) -> Self {
        let mut cells = BTreeSet::new();
        for pair in maps.windows(2) {
            let (arrived, _) = changed_and_same(&pair[1], &pair[0]);
            let (vacated, _) = changed_and_same(&pair[0], &pair[1]);
            cells.extend(arrived);
            cells.extend(vacated);
        }
        let cell_m = maps.first().map_or(0.0, |m| m.cell_m);
        Self { cells, cell_m }
    }

    /// Whether the run saw `cell` change.
    pub fn contains(&self, cell: Cell) -> bool {
        self.cells.contains(&cell)
    }

    /// What of `cluster` is evidence of motion or stillness: a moving cluster as it is, a
    /// stationary one without the cells the run saw change (`None` if that leaves nothing).
    pub fn evidence(&self, mut cluster: MotionCluster) -> Option<MotionCluster> {
        if cluster.kind != ClusterKind::Stationary {
            return Some(cluster);
        }
        cluster
            .cells_m
            .retain(|&p| !self.contains(cell_of(p, self.cell_m)));
        let n = cluster.cells_m.len();
        if n == 0 {
            return None;
        }
        let sum = cluster
            .cells_m
            .iter()
            .fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
        cluster.centroid_m = [sum[0] / n as f64, sum[1] / n as f64];
        Some(cluster)
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::cluster_pairing::PairScans;
    use crate::motion_clusters::motion_clusters;
    use crate::{Association, MotionClusterParams};

    /// A map at `t` of 0.5 m cells: `occupied` hold a return, `free` were only crossed.
    fn map(t: f64, occupied: &[Cell], free: &[Cell]) -> ScanCells {
        let mut cells = BTreeMap::new();
        cells.extend(free.iter().map(|&c| (c, false)));
        cells.extend(occupied.iter().map(|&c| (c, true)));
        ScanCells {
            cell_m: 0.5,
            stamp_secs: t,
            cells,
            beam_step_rad: 0.0,
            reach_m: 0.0,
        }
    }

    /// A wall cell seen in every scan, and a lane cell the same beam crossed (free) at scan 0
    /// and hit at scans 1 and 2: a car's side face arrived there and slid along itself.
    const WALL: Cell = (0, 20);
    const LANE: Cell = (10, 8);

    fn run() -> Vec<ScanCells> {
        vec![
            map(0.0, &[WALL], &[LANE]),
            map(1.0, &[WALL, LANE], &[]),
            map(2.0, &[WALL, LANE], &[]),
        ]
    }

    #[test]
    fn a_cell_where_an_object_arrived_is_changed_and_a_wall_seen_in_every_scan_is_not() {
        let changed = ChangedCells::of_run(&run());
        assert!(changed.contains(LANE));
        assert!(!changed.contains(WALL));
    }

    #[test]
    fn a_surface_whose_return_moves_to_the_next_cell_has_not_changed() {
        // Range noise: the wall's return falls one cell farther in the second scan.
        let maps = [
            map(0.0, &[WALL], &[(0, 19)]),
            map(1.0, &[(0, 21)], &[(0, 19), WALL]),
        ];
        let changed = ChangedCells::of_run(&maps);
        assert!(!changed.contains(WALL) && !changed.contains((0, 21)));
    }

    #[test]
    fn a_face_sliding_along_itself_is_no_evidence_of_stillness_but_the_wall_stays_still() {
        // Scans 1 and 2 alone call both cells stationary (the paper's rule).
        let maps = run();
        let scans = PairScans {
            first: &maps[1],
            second: &maps[2],
            before: Some(&maps[0]),
            after: None,
        };
        let found = motion_clusters(&scans, 2, &MotionClusterParams::default());
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(found.iter().all(|c| c.kind == ClusterKind::Stationary));
        // The run saw the lane cell change: only the wall is left as evidence of stillness.
        let changed = ChangedCells::of_run(&maps);
        let still: Vec<MotionCluster> = found
            .into_iter()
            .filter_map(|c| changed.evidence(c))
            .collect();
        assert_eq!(still.len(), 1, "{still:?}");
        assert_eq!(still[0].cells_m, vec![[0.25, 10.25]]);
        assert_eq!(still[0].centroid_m, [0.25, 10.25]);
    }

    #[test]
    fn a_stationary_cluster_keeps_its_unchanged_cells_and_a_moving_one_is_untouched() {
        let changed = ChangedCells::of_run(&run());
        let cluster = |kind, cells_m: Vec<[f64; 2]>| MotionCluster {
            scan: 2,
            kind,
            association: Association::Stationary,
            centroid_m: [0.0, 0.0],
            cells_m,
            velocity_mps: [0.0, 0.0],
        };
        // The lane cell (5.25, 4.25) and two wall cells in one stationary cluster.
        let mixed = cluster(
            ClusterKind::Stationary,
            vec![[5.25, 4.25], [0.25, 10.25], [0.75, 10.25]],
        );
        let kept = changed.evidence(mixed).expect("the wall cells stay");
        assert_eq!(kept.cells_m, vec![[0.25, 10.25], [0.75, 10.25]]);
        assert!((kept.centroid_m[0] - 0.5).abs() < 1e-12);
        let moving = cluster(ClusterKind::Arrived, vec![[5.25, 4.25]]);
        assert_eq!(changed.evidence(moving.clone()), Some(moving));
        let lane_only = cluster(ClusterKind::Stationary, vec![[5.25, 4.25]]);
        assert_eq!(changed.evidence(lane_only), None);
    }
}
