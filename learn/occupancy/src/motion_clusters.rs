//! Motion clusters of two consecutive scans (DGPOM paper, Section 2.3, Figure 3). Frame1 holds the
//! cells occupied in the first scan that the second also observed, Frame2 the reverse; Diff =
//! Frame2 − Frame1 (+1 where an object arrived, −1 where one left) and Same = Frame1 ∘ Frame2
//! (occupied in both). Both compare with a tolerance of one cell: a surface whose returns straddle
//! a cell boundary from scan to scan (range noise) has not moved, so a cell counts as changed only
//! if the other scan has no return within one cell of it (and the width of a Diff cluster, one
//! cell short of the displacement, gets that cell back). Clusters of Same cells are objects. A Diff cluster next to an object gets
//! a velocity: its direction along the line between the two centroids (from the object into an
//! arrived cluster, from a vacated cluster to the object), its magnitude the cluster's width
//! along that line over the scan interval. Same clusters with no Diff cluster next to them are
//! stationary (velocity 0); over a whole training run, `ChangedCells` keeps of them only the cells
//! the run never saw change.
//!
//! One addition: an object that moves farther than its own visible length between scans leaves no
//! Same cells, so neither of its Diff clusters has an object next to it. Such vacated and arrived
//! clusters are paired within the reach of `max_speed_mps`, each pair borne out by the scans
//! before and after it (`cluster_pairing`), and get the displacement of their centroids over the
//! interval (reported as [`Association::Paired`]). A scanner whose beams are farther apart than a
//! cell at the end of its reach sees a far car as one return a scan, so its one-cell clusters are
//! paired too (`fewest_cells`).

use std::collections::BTreeSet;

use serde::{Deserialize, Serialize};

use crate::cluster_pairing::{Candidate, PairScans, chosen_pairs};
use crate::scan_cells::{Cell, ScanCells, cell_clusters};

/// What a motion cluster is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ClusterKind {
    /// Diff = +1: cells an object moved into.
    Arrived,
    /// Diff = −1: cells an object left.
    Vacated,
    /// Same cells with no Diff cluster next to them: a stationary object.
    Stationary,
}

/// How a Diff cluster got its velocity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Association {
    /// The paper's rule: an adjacent object; magnitude from the cluster's width.
    AdjacentObject,
    /// The addition for fast objects: a vacated and an arrived cluster paired; magnitude from
    /// the displacement of their centroids.
    Paired,
    /// A stationary object (velocity 0).
    Stationary,
}

/// A cluster with its velocity, in the world frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotionCluster {
    /// The second scan of the pair (the cluster describes the motion up to it).
    pub scan: usize,
    /// Arrived, vacated or stationary.
    pub kind: ClusterKind,
    /// How the velocity was found.
    pub association: Association,
    /// Centres of the cluster's cells, metres.
    pub cells_m: Vec<[f64; 2]>,
    /// Centroid of the cells, metres.
    pub centroid_m: [f64; 2],
    /// Velocity, m/s.
    pub velocity_mps: [f64; 2],
}

/// Settings of the motion clusters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MotionClusterParams {
    /// Cell size of the per-scan maps, metres.
    pub cell_m: f64,
    /// Cells up to this far apart (per axis) belong to one cluster, metres.
    pub link_m: f64,
    /// A Diff cluster whose nearest cell is at most this far from an object's is next to it, metres.
    pub adjacency_m: f64,
    /// Diff clusters with no object next to them and fewer cells are not paired, where the
    /// scanner samples densely: its beams are at most a cell apart even at the end of its reach
    /// (a 3-D lidar's 0.2° columns), so every surface leaves several returns per cell and a
    /// one-cell change is an edge flickering (the 3-D slice's DGPOM fell by 0.002-0.016 when they
    /// were paired). A sparse scanner (a 1° SICK-like one reaching 80 m, its beams 1.4 m apart
    /// there) sees a far car as one return a scan and a pedestrian as one cell anywhere, so it
    /// pairs every Diff cluster, still only where the scans around bear the pair out
    /// (`fewest_cells`). Next to an object every Diff cluster counts.
    pub min_cells: usize,
    /// Fastest motion a vacated and an arrived cluster are paired across, m/s.
    pub max_speed_mps: f64,
}

impl Default for MotionClusterParams {
    fn default() -> Self {
        Self {
            cell_m: 0.5,
            link_m: 1.0,
            adjacency_m: 1.0,
            min_cells: 2,
            max_speed_mps: 15.0,
        }
    }
}

/// A cluster of lattice cells with its centres.
struct Group {
    centres: Vec<[f64; 2]>,
    centroid: [f64; 2],
}

impl Group {
    fn new(cells: Vec<Cell>, map: &ScanCells) -> Self {
        let centres: Vec<[f64; 2]> = cells.iter().map(|&c| map.centre_m(c)).collect();
        let n = centres.len().max(1) as f64;
        let centroid = [
            centres.iter().map(|p| p[0]).sum::<f64>() / n,
            centres.iter().map(|p| p[1]).sum::<f64>() / n,
        ];
        Self { centres, centroid }
    }

    /// Smallest distance between a cell centre of `self` and one of `other`.
    fn gap_m(&self, other: &Group) -> f64 {
        let mut best = f64::INFINITY;
        for p in &self.centres {
            for q in &other.centres {
                best = best.min((p[0] - q[0]).hypot(p[1] - q[1]));
            }
        }
        best
    }

    /// Extent of the cells along the unit direction `u`, counting whole cells.
    fn width_m(&self, u: [f64; 2], cell_m: f64) -> f64 {
        let proj = self.centres.iter().map(|p| p[0] * u[0] + p[1] * u[1]);
        let (lo, hi) = proj.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
        hi - lo + cell_m
    }

    fn into_cluster(
        self,
        scan: usize,
        kind: ClusterKind,
        association: Association,
        v: [f64; 2],
    ) -> MotionCluster {
        MotionCluster {
            scan,
            kind,
            association,
            cells_m: self.centres,
            centroid_m: self.centroid,
            velocity_mps: v,
        }
    }
}

/// The motion clusters between the maps `scans.first` and `scans.second` of two consecutive
/// scans (the scans around them check the pairing of fast objects); `scan` is the second scan's
/// index.
pub(crate) fn motion_clusters(
    scans: &PairScans<'_>,
    scan: usize,
    params: &MotionClusterParams,
) -> Vec<MotionCluster> {
    let (first, second) = (scans.first, scans.second);
    let dt = second.stamp_secs - first.stamp_secs;
    if dt <= 0.0 {
        return Vec::new();
    }
    // Frame1, Frame2: occupied in one map and observed in the other. A cell changed (Diff) when
    // the other map saw it and has no return within one cell of it; else it stayed (Same).
    let (arrived, same2) = changed_and_same(second, first);
    let (vacated, same1) = changed_and_same(first, second);
    let same: BTreeSet<Cell> = same1.union(&same2).copied().collect();
    let gap = (params.link_m / params.cell_m).round().max(1.0) as i64;
    let groups = |cells: &BTreeSet<Cell>, min: usize| -> Vec<Group> {
        cell_clusters(cells, gap)
            .into_iter()
            .filter(|c| c.len() >= min)
            .map(|c| Group::new(c, second))
            .collect()
    };
    let objects = groups(&same, 1);
    // Every Diff cluster next to an object counts, one cell included: a 1 m/s car moves two
    // 0.5 m cells a scan, and the one-cell tolerance leaves it a one-cell Diff cluster. Only
    // the pairing of clusters without an object (below) needs `min_cells` (`fewest_cells`).
    let diffs: Vec<(ClusterKind, Group)> = groups(&arrived, 1)
        .into_iter()
        .map(|g| (ClusterKind::Arrived, g))
        .chain(
            groups(&vacated, 1)
                .into_iter()
                .map(|g| (ClusterKind::Vacated, g)),
        )
        .collect();
    let mut out = Vec::new();
    // The paper's rule: a Diff cluster next to an object moved out of or into it.
    let mut unmatched = Vec::new();
    for (kind, group) in diffs {
        let nearest = objects
            .iter()
            .map(|o| (group.gap_m(o), o))
            .filter(|(gap, _)| *gap <= params.adjacency_m + 1e-9)
            .min_by(|a, b| a.0.total_cmp(&b.0));
        match nearest {
            Some((_, object)) => {
                let (from, to) = match kind {
                    ClusterKind::Arrived => (object.centroid, group.centroid),
                    _ => (group.centroid, object.centroid),
                };
                let v = match unit(from, to) {
                    Some(u) => {
                        // One cell of the displacement is lost to the tolerance; count it back.
                        let speed = (group.width_m(u, params.cell_m) + params.cell_m) / dt;
                        [u[0] * speed, u[1] * speed]
                    }
                    None => [0.0, 0.0],
                };
                out.push(group.into_cluster(scan, kind, Association::AdjacentObject, v));
            }
            None if group.centres.len() >= fewest_cells(kind, scans, params) => {
                unmatched.push((kind, group))
            }
            None => {}
        }
    }
    // Stationary objects: Same clusters without a Diff cluster next to them.
    let near = |object: &Group| {
        out.iter()
            .any(|c| min_gap(&object.centres, &c.cells_m) <= params.adjacency_m + 1e-9)
            || unmatched
                .iter()
                .any(|(_, g)| object.gap_m(g) <= params.adjacency_m + 1e-9)
    };
    let stationary: Vec<Group> = objects.into_iter().filter(|o| !near(o)).collect();
    out.extend(stationary.into_iter().map(|o| {
        o.into_cluster(
            scan,
            ClusterKind::Stationary,
            Association::Stationary,
            [0.0, 0.0],
        )
    }));
    out.extend(paired(unmatched, scans, scan, dt, params).0);
    out
}

/// The addition for fast objects: vacated and arrived clusters without an adjacent object,
/// paired within `max_speed_mps · dt` as [`chosen_pairs`] chooses, each with its centroids'
/// displacement; and the clusters left unpaired.
fn paired(
    unmatched: Vec<(ClusterKind, Group)>,
    scans: &PairScans<'_>,
    scan: usize,
    dt: f64,
    params: &MotionClusterParams,
) -> (Vec<MotionCluster>, Vec<(ClusterKind, Group)>) {
    let (vacated, arrived): (Vec<_>, Vec<_>) = unmatched
        .into_iter()
        .partition(|(k, _)| *k == ClusterKind::Vacated);
    let v_refs: Vec<Candidate<'_>> = vacated
        .iter()
        .map(|(_, g)| (g.centres.as_slice(), g.centroid))
        .collect();
    let a_refs: Vec<Candidate<'_>> = arrived
        .iter()
        .map(|(_, g)| (g.centres.as_slice(), g.centroid))
        .collect();
    let chosen = chosen_pairs(&v_refs, &a_refs, scans, params.max_speed_mps * dt);
    let mut vacated: Vec<Option<Group>> = vacated.into_iter().map(|(_, g)| Some(g)).collect();
    let mut arrived: Vec<Option<Group>> = arrived.into_iter().map(|(_, g)| Some(g)).collect();
    let mut out = Vec::new();
    for (i, j) in chosen {
        if let (Some(v), Some(a)) = (vacated[i].take(), arrived[j].take()) {
            let velocity = [
                (a.centroid[0] - v.centroid[0]) / dt,
                (a.centroid[1] - v.centroid[1]) / dt,
            ];
            out.push(v.into_cluster(scan, ClusterKind::Vacated, Association::Paired, velocity));
            out.push(a.into_cluster(scan, ClusterKind::Arrived, Association::Paired, velocity));
        }
    }
    let rest = (vacated.into_iter().map(|g| (ClusterKind::Vacated, g)))
        .chain(arrived.into_iter().map(|g| (ClusterKind::Arrived, g)))
        .filter_map(|(k, g)| g.map(|g| (k, g)))
        .collect();
    (out, rest)
}

/// The fewest cells a Diff cluster without an object next to it needs to be paired: one if the
/// scan that drew it (the first for a vacated cluster, the second for an arrived one) samples
/// sparsely (beams more than a cell apart at the end of its reach), else `min_cells`.
fn fewest_cells(kind: ClusterKind, scans: &PairScans<'_>, params: &MotionClusterParams) -> usize {
    let map = match kind {
        ClusterKind::Vacated => scans.first,
        _ => scans.second,
    };
    if map.far_beam_spacing_m() > params.cell_m {
        1
    } else {
        params.min_cells
    }
}

/// The occupied cells of `map` that `other` saw with no return within one cell (changed), and
/// those with one (same).
pub(crate) fn changed_and_same(
    map: &ScanCells,
    other: &ScanCells,
) -> (BTreeSet<Cell>, BTreeSet<Cell>) {
    let mut changed = BTreeSet::new();
    let mut same = BTreeSet::new();
    for (&(c, r), _) in map.cells.iter().filter(|&(_, &occupied)| occupied) {
        if other.state((c, r)).is_none() {
            continue;
        }
        let near =
            (-1..=1).any(|dc| (-1..=1).any(|dr| other.state((c + dc, r + dr)) == Some(true)));
        if near {
            same.insert((c, r));
        } else {
            changed.insert((c, r));
        }
    }
    (changed, same)
}

fn min_gap(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    let mut best = f64::INFINITY;
    for p in a {
        for q in b {
            best = best.min((p[0] - q[0]).hypot(p[1] - q[1]));
        }
    }
    best
}

/// The unit vector from `from` to `to`, `None` if they coincide.
fn unit(from: [f64; 2], to: [f64; 2]) -> Option<[f64; 2]> {
    let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
    let n = dx.hypot(dy);
    (n > 1e-9).then(|| [dx / n, dy / n])
}

#[cfg(test)]
#[path = "motion_clusters_tests.rs"]
mod tests;
