//! Which vacated and arrived clusters of two consecutive scans are one object that moved farther
//! than its own visible length (the motion clusters' addition for fast objects). Nearest first
//! is wrong in dense crossing traffic: at 6-9 m/s between 1 Hz scans a car's vacated cluster is
//! nearer the arrived cluster of the car in the opposite lane than its own (the busy
//! intersection's pairs were 38 % off by more than 3 m/s, issue 25). So where the scans before
//! and after the pair are known, a pair must be borne out by them: the arrived cells moved on by
//! the pair's displacement land on cells the next scan newly holds (occupied there, with no
//! return of the pair's second scan within one cell: not a wall), and the vacated cells moved
//! back land on cells the scan before newly held. Pairs are then chosen best supported first,
//! nearest among equals; a pair with less than `MIN_SUPPORT` is not motion.

use crate::occupancy_grid::cell_of;
use crate::scan_cells::ScanCells;

/// Share of a pair's moved cells (of those the neighbouring scans observed) that must land on a
/// newly held cell.
const MIN_SUPPORT: f64 = 0.5;
/// A moved cell lands on a newly held cell within this many cells of it (per axis).
const LANDING_CELLS: i64 = 2;

/// The scans around a pair: `first` and `second` the pair, `before` the scan before `first`
/// and `after` the one after `second` (absent at the run's ends or when not given).
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairScans<'a> {
    pub first: &'a ScanCells,
    pub second: &'a ScanCells,
    pub before: Option<&'a ScanCells>,
    pub after: Option<&'a ScanCells>,
}

/// A cluster as the pairing sees it: its cell centres and centroid, metres.
pub(crate) type Candidate<'c> = (&'c [[f64; 2]], [f64; 2]);

/// The (vacated, arrived) index pairs chosen among clusters whose centroids are at most
/// `reach_m` apart. Without neighbouring scans every pair within reach is a candidate, chosen
/// nearest first (a lone pair of scans has nothing else to go on).
pub(crate) fn chosen_pairs(
    vacated: &[Candidate<'_>],
    arrived: &[Candidate<'_>],
    scans: &PairScans<'_>,
    reach_m: f64,
) -> Vec<(usize, usize)> {
    let dt = scans.second.stamp_secs - scans.first.stamp_secs;
    let validate = scans.before.is_some() || scans.after.is_some();
    // (support, distance, vacated, arrived)
    let mut pairs: Vec<(f64, f64, usize, usize)> = Vec::new();
    for (i, (v_cells, v)) in vacated.iter().enumerate() {
        for (j, (a_cells, a)) in arrived.iter().enumerate() {
            let d = [a[0] - v[0], a[1] - v[1]];
            let dist = d[0].hypot(d[1]);
            if dist > reach_m || dt <= 0.0 {
                continue;
            }
            let support = if validate {
                match support(v_cells, a_cells, d, dt, scans) {
                    Some(s) if s >= MIN_SUPPORT => s,
                    _ => continue,
                }
            } else {
                1.0
            };
            pairs.push((support, dist, i, j));
        }
    }
    pairs.sort_by(|a, b| {
        b.0.total_cmp(&a.0)
            .then(a.1.total_cmp(&b.1))
            .then(a.2.cmp(&b.2))
            .then(a.3.cmp(&b.3))
    });
    let (mut used_v, mut used_a) = (vec![false; vacated.len()], vec![false; arrived.len()]);
    let mut chosen = Vec::new();
    for (_, _, i, j) in pairs {
        if !used_v[i] && !used_a[j] {
            used_v[i] = true;
            used_a[j] = true;
            chosen.push((i, j));
        }
    }
    chosen
}

/// The share of the moved cells that land on newly held cells of the neighbouring scans (the
/// arrived cells moved on into `after`, the vacated ones moved back into `before`), `None` if
/// the neighbours observed none of them.
fn support(
    vacated: &[[f64; 2]],
    arrived: &[[f64; 2]],
    d: [f64; 2],
    dt: f64,
    scans: &PairScans<'_>,
) -> Option<f64> {
    let (mut hits, mut seen) = (0usize, 0usize);
    if let Some(after) = scans.after {
        let k = (after.stamp_secs - scans.second.stamp_secs) / dt;
        let shift = [d[0] * k, d[1] * k];
        let (h, s) = landings(arrived, shift, after, scans.second);
        hits += h;
        seen += s;
    }
    if let Some(before) = scans.before {
        let k = (scans.first.stamp_secs - before.stamp_secs) / dt;
        let shift = [-d[0] * k, -d[1] * k];
        let (h, s) = landings(vacated, shift, before, scans.first);
        hits += h;
        seen += s;
    }
    (seen > 0).then(|| hits as f64 / seen as f64)
}

/// Of `cells` moved by `shift_m`, how many land near a cell `other` newly holds (occupied in
/// `other`, no return of `reference` within one cell), and how many `other` observed.
fn landings(
    cells: &[[f64; 2]],
    shift_m: [f64; 2],
    other: &ScanCells,
    reference: &ScanCells,
) -> (usize, usize) {
    let new_return = |(c, r): (i64, i64)| {
        other.state((c, r)) == Some(true)
            && !(-1..=1)
                .any(|dc| (-1..=1).any(|dr| reference.state((c + dc, r + dr)) == Some(true)))
    };
    let (mut hits, mut seen) = (0, 0);
    for p in cells {
        let (c, r) = cell_of([p[0] + shift_m[0], p[1] + shift_m[1]], other.cell_m);
        let observed = (-LANDING_CELLS..=LANDING_CELLS).any(|dc| {
            (-LANDING_CELLS..=LANDING_CELLS).any(|dr| other.state((c + dc, r + dr)).is_some())
        });
        if !observed {
            continue;
        }
        seen += 1;
        let landed = (-LANDING_CELLS..=LANDING_CELLS)
            .any(|dc| (-LANDING_CELLS..=LANDING_CELLS).any(|dr| new_return((c + dc, r + dr))));
        hits += usize::from(landed);
    }
    (hits, seen)
}
